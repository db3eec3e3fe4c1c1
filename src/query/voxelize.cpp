// Occupied voxels of a world-aligned grid.

#include "query/frames.hpp"
#include "query/queries.hpp"

#include <eco/ego_octree.hpp>

#include <algorithm>
#include <cmath>

namespace eco {
namespace detail {

std::vector<VoxelKey> voxel_keys_of(const Tree& t, double resolution) {
  require_positive(resolution, "voxelize", "resolution", false);
  std::vector<VoxelKey> keys;
  if (t.root == kNone) return keys;
  keys.reserve(t.nodes[t.root].count);
  auto index = [&](int a, float stored) { return world_grid_index(t.anchor[a], stored, resolution); };
  walk_leaves(
      t, t.root, [](const Aabb&) { return 2; },
      [&](const StoredPoint& s, bool) {
        const VoxelKey key{index(0, s.p[0]), index(1, s.p[1]), index(2, s.p[2])};
        if (keys.empty() || keys.back() != key) keys.push_back(key);  // neighbours often repeat
      });
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

}  // namespace detail

std::vector<VoxelKey> EgoOctree::voxel_keys(double resolution) const {
  return detail::voxel_keys_of(*tree_, resolution);
}

std::vector<Eigen::Vector3d> EgoOctree::voxelize(double resolution, Frame frame) const {
  const std::vector<VoxelKey> keys = voxel_keys(resolution);
  const Eigen::Vector3d shift =
      frame == Frame::Ego ? Eigen::Vector3d(tree_->pose.translation()) : Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> centres;
  centres.reserve(keys.size());
  for (const VoxelKey& k : keys) {
    centres.push_back(Eigen::Vector3d((double(k.x) + 0.5) * resolution, (double(k.y) + 0.5) * resolution,
                                      (double(k.z) + 0.5) * resolution) -
                      shift);
  }
  return centres;
}

}  // namespace eco
