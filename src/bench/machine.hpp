#pragma once
// What the benchmark ran on, for the results folder: CPU model, cores, the core it was pinned to.

#include <string>

namespace eco::bench {

/// "Intel(R) Xeon(R) ... , 2 cores, pinned to core 1" (what /proc/cpuinfo and the scheduler say).
std::string describe_machine();

/// Pins this process to the core it runs on now, so every method is timed on one core (the
/// paper's protocol). Returns the core, or -1 if the scheduler refused.
int pin_to_one_core();

}  // namespace eco::bench
