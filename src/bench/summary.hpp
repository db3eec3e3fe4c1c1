#pragma once
// One line per method out of its per-frame records: the figures summary.md and summary.json
// report.

#include "bench/runner.hpp"

#include <string>
#include <vector>

namespace eco::bench {

/// Times are means over the frames after the first: on the first frame every method builds its
/// tree from nothing, which says little about updating it (first_update_ms reports it).
struct MethodSummary {
  std::string name;
  std::size_t frames = 0;
  double first_update_ms = 0.0; ///< the first frame's update: a build from nothing
  double update_ms = 0.0;       ///< mean over frames after the first
  double update_ms_p99 = 0.0;   ///< 99th percentile (nearest rank)
  double update_faults = 0.0;   ///< mean page faults per update, over frames after the first
  double caller_ms = 0.0;       ///< the caller's work after each update, mean over frames after the first
  double caller_faults = 0.0;   ///< ... its page faults, mean
  double voxel_ms = 0.0;        ///< mean over frames after the first
  double knn_ms = 0.0;          ///< ... per batch of queries
  double points = 0.0;          ///< mean held
  double nodes = 0.0;           ///< mean
  double mean_depth = 0.0;      ///< mean over frames of the mean leaf depth
  int max_depth = 0;            ///< deepest leaf seen
  double first_depth = 0.0;     ///< mean leaf depth after the first frame
  double last_depth = 0.0;      ///< ... and after the last
  std::size_t bytes = 0;        ///< peak over the run
  double bytes_per_point = 0.0; ///< mean over frames holding points
  double chamfer_m = 0.0;       ///< mean; NaN without octree_base in the run
  double region_tested = 0.0;   ///< mean per update after the first (ECO's region)
  double region_scale_min = 1.0;  ///< the smallest scale the budget took
  std::size_t frames_over_budget = 0;
};

[[nodiscard]] MethodSummary summarize(const MethodRun& run);
[[nodiscard]] std::vector<MethodSummary> summarize(const BenchRun& run);

}  // namespace eco::bench
