#include "bench/runner.hpp"

#include "bench/caller_work.hpp"
#include "bench/chamfer.hpp"
#include "bench/query_batch.hpp"
#include "bench/stopwatch.hpp"
#include "bench/workload_source.hpp"

#include "baselines/method.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace eco::bench {

std::string chamfer_reference(WorkloadKind workload) {
  return workload == WorkloadKind::Dynamic ? "scan_only" : "octree_base";
}

BenchRun run_bench(const BenchOptions& given, const Progress& progress) {
  const auto started = Clock::now();
  BenchOptions options = given;
  options.config.validate();
  if (options.knn_k == 0) throw std::invalid_argument("k = 0 must be >= 1");  // KNN of no neighbour measures nothing
  const std::string reference = chamfer_reference(options.workload);
  if (options.workload == WorkloadKind::Dynamic &&
      std::find(options.methods.begin(), options.methods.end(), reference) == options.methods.end()) {
    options.methods.push_back(reference);  // the paper's dynamic reference: the scan alone
  }
  std::vector<std::unique_ptr<baselines::Method>> methods;
  BenchRun run;
  run.options = options;
  run.chamfer_reference = reference;
  for (const std::string& name : options.methods) {
    methods.push_back(baselines::make_method(name, options.config));
    run.methods.push_back({name, {}, std::nullopt});
  }
  OpenedWorkload workload = open_workload(options, progress.status);
  run.source = workload.source;
  run.map_points = workload.map_points;
  const std::size_t total =
      options.frames > 0 ? std::min(options.frames, workload.frames->size()) : workload.frames->size();
  std::ptrdiff_t base = -1;  // index of the voxel maps' reference
  for (std::size_t m = 0; m < methods.size(); ++m) {
    if (methods[m]->name() == reference) base = std::ptrdiff_t(m);
  }
  std::vector<Neighbor> found(options.knn_k);
  std::vector<std::vector<VoxelKey>> maps(methods.size());
  double sink = 0.0;  // keeps the timed queries from being optimised away
  for (std::size_t t = 0; t < total; ++t) {
    const workloads::WorkloadFrame frame = workload.frames->frame(t);
    const std::vector<Eigen::Vector3d> queries =
        make_queries(frame, options.config.box_side, options.knn_queries, options.seed);
    for (std::size_t i = 0; i < methods.size(); ++i) {
      const std::size_t m = (i + t) % methods.size();  // each method goes first as often: caches
      baselines::Method& method = *methods[m];
      FrameRecord r;
      r.frame = t;
      r.input_points = frame.points.size();
      std::optional<workloads::AttributedScan> attributed;  // made before the clock starts
      const ScanView scan = workloads::scan_for(frame, options.config.attributes, attributed);
      const long faults = minor_faults();
      auto start = Clock::now();
      method.update(frame.world_T_sensor, scan);
      r.update_ms = ms_since(start);
      r.update_faults = minor_faults() - faults;
      const CallerWork caller = run_caller_work(scan);
      r.caller_ms = caller.ms;
      r.caller_faults = caller.faults;
      sink += caller.sum;
      if (method.indexed()) {  // scan_pass would scan every point per query: not timed
        start = Clock::now();
        maps[m] = method.voxel_keys(options.voxel_resolution);
        r.voxel_ms = ms_since(start);
        start = Clock::now();
        for (const Eigen::Vector3d& q : queries) {
          const std::size_t n = method.knn(q, std::span<Neighbor>(found));
          if (n > 0) sink += found[n - 1].sq_dist;
        }
        r.knn_ms = ms_since(start);
        std::sort(maps[m].begin(), maps[m].end());  // Chamfer looks keys up by binary search
      } else {
        maps[m] = method.voxel_keys(options.voxel_resolution);
        r.voxel_ms = r.knn_ms = std::numeric_limits<double>::quiet_NaN();
      }
      if (const EgoOctree* tree = method.ego_octree()) {
        const UpdateStats& u = tree->last_update();
        r.region_tested = u.region_tested;
        r.region_scale = u.region.scale;
        const std::uint32_t budget = tree->config().region.max_points;
        r.over_budget = budget > 0 && tree->size() > budget;
      }
      const Stats s = method.stats();
      r.points = s.points;
      r.nodes = s.nodes;
      r.mean_depth = s.mean_leaf_depth;
      r.max_depth = s.max_leaf_depth;
      r.bytes = s.bytes;
      if (options.check_every_frame) {
        const std::string broken = method.check_invariants();
        if (!broken.empty()) {
          throw std::runtime_error(method.name() + " frame " + std::to_string(t) + ": " + broken);
        }
      }
      run.methods[m].frames.push_back(r);
    }
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(options.config.box_side / 2);
    const Eigen::Vector3d centre = frame.world_T_sensor.translation();
    for (std::size_t m = 0; m < methods.size(); ++m) {
      double& chamfer = run.methods[m].frames.back().chamfer_m;
      if (base < 0) {
        chamfer = std::numeric_limits<double>::quiet_NaN();
      } else if (std::ptrdiff_t(m) != base) {
        chamfer = chamfer_distance(clip_to_box(maps[m], centre - half, centre + half, options.voxel_resolution),
                                   maps[std::size_t(base)], options.voxel_resolution);
      }
    }
    progress.frame(t + 1, total, run);
  }
  for (std::size_t m = 0; m < methods.size(); ++m) {
    if (const EgoOctree* tree = methods[m]->ego_octree(); tree != nullptr && total > 0) {
      progress.status("timing " + methods[m]->name() + "'s map file");
      run.methods[m].map_file = time_map_file(*tree);
    }
  }
  if (options.time_snapshots) run.snapshots = time_snapshots(options, progress.status);
  run.seconds = std::chrono::duration<double>(Clock::now() - started).count() + (sink < 0 ? 1 : 0);
  return run;
}

}  // namespace eco::bench
