#pragma once
// Voxel downsampling as a registration client does it each frame: the first point of every voxel,
// in the points' order, found through a hash set built for the call (it allocates, as a client's
// does: the odometry's own work, which the map must not slow).

#include <eco/types.hpp>

#include <Eigen/Core>

#include <cmath>
#include <span>
#include <vector>

namespace eco::odometry {

/// The world-aligned voxel of side `side` holding `p`.
template <class Vector>
VoxelKey voxel_of(const Vector& p, double side) {
  return {std::int64_t(std::floor(double(p.x()) / side)), std::int64_t(std::floor(double(p.y()) / side)),
          std::int64_t(std::floor(double(p.z()) / side))};
}

/// The first of `points` in each voxel of side `side`, in their order.
[[nodiscard]] std::vector<Eigen::Vector3f> voxel_downsample(std::span<const Eigen::Vector3f> points, double side);

}  // namespace eco::odometry
