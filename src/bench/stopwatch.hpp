#pragma once
// The clock the benchmark times with.

#include <chrono>

namespace eco::bench {

using Clock = std::chrono::steady_clock;

/// Milliseconds from `start` to now.
inline double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace eco::bench
