#pragma once
// How well two scans agree once placed with their poses: the share of scan b's points (within
// `max_range` of its sensor, and higher than `min_z` in its frame) that fall in a voxel
// occupied by scan a. Registered scans of a static scene score high; scans placed with wrong
// poses score low. Leave the road out (min_z = -1.3 for a sensor 1.73 m up): its range rings
// look alike from everywhere, so they match even with no motion at all.

#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace eco::test {

inline double voxel_overlap(const std::vector<Eigen::Vector3f>& a, const Eigen::Isometry3d& world_T_a,
                            const std::vector<Eigen::Vector3f>& b, const Eigen::Isometry3d& world_T_b,
                            double min_z = -1e9, double voxel = 0.2, double max_range = 30.0) {
  const auto counts = [&](const Eigen::Vector3f& p) { return p.norm() < max_range && p.z() > min_z; };
  std::set<VoxelKey> occupied;
  for (const auto& p : a) {
    if (counts(p)) occupied.insert(voxel_of(world_T_a * p.cast<double>(), voxel));
  }
  std::size_t hits = 0, total = 0;
  for (const auto& p : b) {
    if (!counts(p)) continue;
    ++total;
    hits += occupied.count(voxel_of(world_T_b * p.cast<double>(), voxel));
  }
  return total == 0 ? 0.0 : static_cast<double>(hits) / static_cast<double>(total);
}

}  // namespace eco::test
