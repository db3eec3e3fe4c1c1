#pragma once
// Everything a benchmark run is told: where its frames come from, which methods it compares,
// what it measures, and the tree configuration every method gets.

#include <eco/config.hpp>
#include <eco/sim/simulator.hpp>
#include <eco/workloads/scan_source.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace eco::bench {

enum class WorkloadKind { Static, Dynamic };

struct BenchOptions {
  std::optional<std::filesystem::path> data;  ///< what open_source() reads; none: the simulator's default drive
  workloads::SourceOptions source;            ///< how (--poses, --topic, --time-field, --time-unit)
  WorkloadKind workload = WorkloadKind::Static;
  std::vector<std::string> methods{"eco",       "eco_exact",  "octree_base", "ioctree_global", "ioctree_target",
                                   "nanoflann", "pcl_octree", "scan_pass"};
  std::size_t frames = 0;              ///< frames to run; 0 = the whole sequence
  std::filesystem::path out;  ///< the results folder; empty: results/bench-<date>-<time> (fresh_results_folder)
  Config config = paper_config();      ///< given to every method
  double map_resolution = 0.02;        ///< [m] static map voxel (paper: 0.9–1.5 M points per box)
  double voxel_resolution = 0.1;       ///< [m] voxel map timed and compared (Chamfer)
  std::size_t knn_queries = 1000;      ///< queries per frame, timed as one batch
  std::size_t knn_k = 5;
  std::uint64_t seed = 1;              ///< query draws; the simulator's seed when there is no data
  std::size_t sim_frames = 200;        ///< length of the default simulated drive
  sim::SimConfig sim;                  ///< its vehicle's manoeuvre and speed (seed and frames: the two above)
  bool check_every_frame = false;      ///< also run check_invariants() after every update (slow)
  bool time_snapshots = false;         ///< then time publishing snapshots (bench/snapshot_timing.hpp)

  /// The paper's settings: L = 20 m, N_max = 8, ShiftInOnly.
  static Config paper_config() {
    Config c;
    c.leaf_capacity = 8;
    c.insert_policy = InsertPolicy::ShiftInOnly;
    return c;
  }
};

/// Named settings of the benchmark. `paper`: Table II (ShiftInOnly, N_max = 8, the default).
/// The robot's case — raw scans, every point in the box kept, the library's N_max = 128:
/// `robot` (no cap), `robot-cap-0.2` (1 point per 0.2 m cell, voxel map at 0.2 m: how LiDAR
/// odometry keeps its map), `robot-cap-0.1` (2 points per 0.1 m cell, voxel map at 0.1 m: eco run's
/// default). Throws std::invalid_argument for another name.
inline void apply_preset(const std::string& name, BenchOptions& o) {
  if (name == "paper") {
    o.config = BenchOptions::paper_config();
    return;
  }
  Config c;  // the library's defaults: AllInBox, N_max = 128
  o.workload = WorkloadKind::Dynamic;
  if (name == "robot") {
    o.voxel_resolution = 0.1;
  } else if (name == "robot-cap-0.2") {
    c.density_cap = {0.2, 1};
    o.voxel_resolution = 0.2;
  } else if (name == "robot-cap-0.1") {
    c.density_cap = {0.1, 2};
    o.voxel_resolution = 0.1;
  } else {
    throw std::invalid_argument("unknown preset '" + name + "' (known: paper, robot, robot-cap-0.2, robot-cap-0.1)");
  }
  o.config = c;
}

[[nodiscard]] inline std::string to_string(WorkloadKind kind) {
  return kind == WorkloadKind::Static ? "static" : "dynamic";
}

}  // namespace eco::bench
