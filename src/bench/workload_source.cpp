#include "bench/workload_source.hpp"

#include "bench/sim_workload.hpp"

#include <eco/io/error.hpp>
#include <eco/workloads/frame_window.hpp>
#include <eco/workloads/static_map.hpp>
#include <eco/workloads/static_workload.hpp>

namespace eco::bench {

OpenedWorkload open_workload(const BenchOptions& options, const std::function<void(const std::string&)>& status) {
  OpenedWorkload out;
  std::unique_ptr<workloads::Workload> scans;
  if (options.data) {
    workloads::OpenedSource opened = workloads::open_source(*options.data, options.source);
    if (!opened.has_poses) {
      throw io::Error(options.data->string(), "", "has no poses, and the benchmark places each scan by its pose: give "
                                                  "--poses FILE, or estimate them with eco odometry");
    }
    for (const std::string& warning : opened.warnings) status("warning: " + warning);
    scans = std::move(opened.frames);
    out.source = options.data->string();
  } else {
    sim::SimConfig sim = options.sim;
    sim.seed = options.seed;
    sim.frames = options.source.start + options.sim_frames;
    scans = workloads::frame_window(std::make_unique<SimWorkload>(sim), options.source.start);
    out.source = "simulator (seed " + std::to_string(sim.seed) + ", " + std::to_string(sim.frames) + " frames)";
  }
  if (options.workload == WorkloadKind::Dynamic) {
    out.frames = std::move(scans);
    return out;
  }
  status("aggregating " + std::to_string(scans->size()) + " scans into the static map at " +
         std::to_string(options.map_resolution) + " m");
  auto map = std::make_shared<const workloads::StaticMap>(
      workloads::StaticMap::aggregate(*scans, options.map_resolution));
  out.map_points = map->size();
  std::vector<Eigen::Isometry3d> poses;
  const std::size_t n = options.frames > 0 ? std::min(options.frames, scans->size()) : scans->size();
  for (std::size_t i = 0; i < n; ++i) poses.push_back(scans->pose(i));
  out.frames = std::make_unique<workloads::StaticWorkload>(map, poses, options.config.box_side);
  return out;
}

}  // namespace eco::bench
