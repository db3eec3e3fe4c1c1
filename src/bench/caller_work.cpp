#include "bench/caller_work.hpp"

#include "bench/stopwatch.hpp"

#include <Eigen/Core>

#include <sys/resource.h>

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace eco::bench {

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

CallerWork run_caller_work(const ScanView& scan) {
  CallerWork work;
  const long faults = minor_faults();
  const auto start = Clock::now();
  {
    // as a registration loop's preprocessing does: the points copied in double precision into a
    // vector that grows as they come, then one kept per 1 m voxel through a hash map
    std::vector<Eigen::Vector3d> points;
    for (std::size_t i = 0; i < scan.count; ++i) {
      const float* p = scan.data + i * scan.stride;
      points.emplace_back(p[0], p[1], p[2]);
    }
    std::unordered_map<std::int64_t, Eigen::Vector3d> voxels;
    voxels.reserve(points.size());
    for (const Eigen::Vector3d& p : points) {
      const auto at = [&](int a) { return std::int64_t(std::floor(p[a])) & 0x1FFFFF; };
      voxels.emplace(at(0) | at(1) << 21 | at(2) << 42, p);
    }
    std::vector<Eigen::Vector3d> kept;
    for (const auto& [key, p] : voxels) kept.push_back(p);
    for (const Eigen::Vector3d& p : kept) work.sum += p.sum();
  }
  work.ms = ms_since(start);
  work.faults = minor_faults() - faults;
  return work;
}

}  // namespace eco::bench
