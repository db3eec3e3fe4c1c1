#pragma once
// Chamfer distance between two voxel maps, as the paper compares each method's voxel map with
// Octree_base's.

#include <eco/types.hpp>

#include <vector>

namespace eco::bench {

/// Symmetric Chamfer distance [m] between the voxel centres of `a` and `b` (sorted unique keys
/// of voxels of side `resolution`): the mean over a of the distance to the nearest voxel of b,
/// plus the same from b to a, halved. 0 when the maps are equal; infinite when exactly one is
/// empty.
double chamfer_distance(const std::vector<VoxelKey>& a, const std::vector<VoxelKey>& b, double resolution);

/// The keys of voxels that meet the box [lo, hi) (world): how a global map is clipped to the ego
/// box before it is compared.
std::vector<VoxelKey> clip_to_box(const std::vector<VoxelKey>& keys, const Eigen::Vector3d& lo,
                                  const Eigen::Vector3d& hi, double resolution);

}  // namespace eco::bench
