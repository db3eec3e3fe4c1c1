#pragma once
// What a map's caller does between updates, for `eco bench` to time beside them: a registration
// loop's own per-frame work allocates a scan-sized buffer, fills it and reads it back (KISS-ICP's
// preprocessing and voxel downsampling do). A map that hands memory back to the kernel after its
// update makes this work fault fresh pages; timing it shows what a map costs its caller.

#include <eco/types.hpp>

#include <cstddef>

namespace eco::bench {

/// Minor page faults of this process so far (getrusage).
[[nodiscard]] long minor_faults();

struct CallerWork {
  double ms = 0.0;
  long faults = 0;  ///< minor page faults during the work
  double sum = 0.0;  ///< what the work computed, so that it is not optimised away
};

/// Copies `scan`'s points into a vector of doubles grown as they come, keeps one per 1 m voxel
/// through a hash map, and sums those; times it.
[[nodiscard]] CallerWork run_caller_work(const ScanView& scan);

}  // namespace eco::bench
