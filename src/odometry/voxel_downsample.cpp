#include "odometry/voxel_downsample.hpp"

#include <unordered_set>

namespace eco::odometry {

std::vector<Eigen::Vector3f> voxel_downsample(std::span<const Eigen::Vector3f> points, double side) {
  std::unordered_set<VoxelKey> seen;
  seen.reserve(points.size());
  std::vector<Eigen::Vector3f> kept;
  kept.reserve(points.size());
  for (const Eigen::Vector3f& p : points) {
    if (seen.insert(voxel_of(p, side)).second) kept.push_back(p);
  }
  return kept;
}

}  // namespace eco::odometry
