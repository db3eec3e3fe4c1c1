#pragma once
// Runs the methods over the same stream, frame by frame (every method gets frame t before any
// gets frame t+1, so machine drift hits all alike), and records what the paper measures.

#include "bench/bench_options.hpp"
#include "bench/map_file_timing.hpp"
#include "bench/snapshot_timing.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace eco::bench {

struct FrameRecord {
  std::size_t frame = 0;
  std::size_t input_points = 0;  ///< points in the frame given to update
  double update_ms = 0.0;
  long update_faults = 0;        ///< minor page faults during the update
  double caller_ms = 0.0;        ///< the caller's own work after the update (bench/caller_work.hpp)
  long caller_faults = 0;        ///< ... and its page faults
  double voxel_ms = 0.0;         ///< voxel map of the held points at voxel_resolution
  double knn_ms = 0.0;           ///< the frame's whole batch of queries
  std::size_t points = 0;        ///< held after the update
  std::size_t nodes = 0;
  double mean_depth = 0.0;       ///< mean leaf depth (0: no octree)
  int max_depth = 0;
  std::size_t bytes = 0;
  double chamfer_m = 0.0;        ///< voxel map vs the reference's (BenchRun), clipped to the box; NaN without it
  // ECO's region (Config::region), zero for the others:
  std::size_t region_tested = 0;  ///< held points tested one by one for the region's surface alone
  double region_scale = 1.0;      ///< the budget's scale after the update
  bool over_budget = false;       ///< more held than region.max_points after the update
};

struct MethodRun {
  std::string name;
  std::vector<FrameRecord> frames;
  std::optional<MapFileTiming> map_file;  ///< after the last frame, for the methods that are an EgoOctree
};

struct BenchRun {
  BenchOptions options;
  std::string source;           ///< where the frames came from
  std::size_t map_points = 0;   ///< static workload: points in the aggregated map
  std::vector<MethodRun> methods;
  /// The method whose voxel map the others are compared with (Chamfer), as the paper does:
  /// `octree_base` (the same points, rebuilt) on the static workload, `scan_only` (the current
  /// scan alone) on the dynamic one, added to the methods if they were not given it.
  std::string chamfer_reference;
  std::optional<SnapshotTiming> snapshots;  ///< with BenchOptions::time_snapshots
  double seconds = 0.0;         ///< wall time of the run, loading included
};

struct Progress {
  std::function<void(const std::string&)> status = [](const std::string&) {};
  /// After each frame: frames done, frames in all, the run so far.
  std::function<void(std::size_t, std::size_t, const BenchRun&)> frame = [](std::size_t, std::size_t,
                                                                             const BenchRun&) {};
};

/// The method the voxel maps of a `workload` run are compared with (BenchRun::chamfer_reference).
[[nodiscard]] std::string chamfer_reference(WorkloadKind workload);

/// Throws std::invalid_argument for an unknown method or a bad configuration, eco::io::Error for
/// an unreadable data folder, std::runtime_error if a method breaks its invariants (with
/// check_every_frame).
BenchRun run_bench(const BenchOptions& options, const Progress& progress = {});

}  // namespace eco::bench
