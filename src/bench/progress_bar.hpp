#pragma once
// A one-line progress bar on stderr, redrawn in place; silent when stderr is not a terminal.

#include "bench/runner.hpp"

namespace eco::bench {

/// Progress callbacks that draw the bar (frames done, ETA, each method's last update time).
Progress terminal_progress();

}  // namespace eco::bench
