#pragma once
// Opens the frames a benchmark runs on: a KITTI-layout folder or the simulator, as the static
// (aggregated map) or dynamic (raw scans) workload.

#include "bench/bench_options.hpp"

#include <eco/workloads/workload.hpp>

#include <functional>
#include <memory>
#include <string>

namespace eco::bench {

struct OpenedWorkload {
  std::unique_ptr<workloads::Workload> frames;
  std::string source;       ///< the folder, or "simulator (seed S, N frames)"
  std::size_t map_points = 0;  ///< static workload: points of the aggregated map
};

/// Throws eco::io::Error (bad folder) or std::invalid_argument. `status` hears what is being
/// done (aggregating a map can take a while).
OpenedWorkload open_workload(const BenchOptions& options, const std::function<void(const std::string&)>& status);

}  // namespace eco::bench
