#pragma once
// Voxel downsampling as a registration client does it each frame: the first point of every voxel,
// in the points' order, found through a hash set built for the call (it allocates, as a client's
// does: the odometry's own work, which the map must not slow).

#include <eco/types.hpp>

#include <Eigen/Core>

#include <span>
#include <vector>

namespace eco::odometry {

/// The first of `points` in each voxel of side `side`, in their order.
[[nodiscard]] std::vector<Eigen::Vector3f> voxel_downsample(std::span<const Eigen::Vector3f> points, double side);

}  // namespace eco::odometry
