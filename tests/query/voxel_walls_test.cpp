// Voxel maps where the walls decide: scan points stored exactly on a voxel wall or on the float just
// below it, in leaves from one to many levels coarser than the voxels (the node walk marks such a
// leaf's voxels against the walls inside it). Keys must equal the brute force's at every lattice
// resolution.

#include "support/compare.hpp"
#include "support/float_walls.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace eco::test {
namespace {

TEST(VoxelWalls, PointsOnAndJustBelowWallsInLeavesOfEveryCoarseness) {
  // The sensor sits on the precision origin with no rotation, so a scan point is stored as given:
  // stored coordinates can be put on the walls i * 0.1 - origin exactly.
  const Eigen::Vector3d at(1024.0, 2048.0, -1024.0);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = at;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> inside(-9.0, 9.0);
  std::vector<Eigen::Vector3f> scan;
  for (int i = -89; i <= 89; ++i) {
    for (int a = 0; a < 3; ++a) {
      const float wall = first_float_at_or_above((std::floor(at[a] / 0.1) + i) * 0.1 - at[a]);
      for (const float v : {wall, std::nextafter(wall, -std::numeric_limits<float>::infinity())}) {
        Eigen::Vector3f p(float(inside(rng)), float(inside(rng)), float(inside(rng)));
        p[a] = v;
        scan.push_back(p);
      }
    }
  }
  for (const std::uint32_t leaf_capacity : {16u, 64u, 256u, 4096u}) {
    Config cfg;
    cfg.leaf_capacity = leaf_capacity;
    cfg.voxel_size = 0.1;
    EgoOctree tree(cfg);
    Oracle oracle(cfg);
    tree.update(pose, scan);
    oracle.update(pose, scan, tree.precision_origin());
    ASSERT_EQ(tree.precision_origin(), at);
    ASSERT_EQ(tree.size(), scan.size());
    for (const double res : {0.1, 0.2, 0.4, 0.8, 1.6}) {
      const std::vector<VoxelKey> keys = tree.voxel_keys(res);
      ASSERT_EQ(sorted_keys(keys), oracle.voxel_keys(res)) << "N_max " << leaf_capacity << ", voxels of " << res;
      ASSERT_EQ(keys.size(), oracle.voxel_keys(res).size()) << "repeated keys: N_max " << leaf_capacity;
    }
  }
}

}  // namespace
}  // namespace eco::test
