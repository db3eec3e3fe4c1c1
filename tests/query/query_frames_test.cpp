// Queries in the sensor's frame (Frame::Sensor: origin at the sensor, axes turned with it) and
// the oriented box query, against the brute force after every frame of a drive that turns and
// tilts: the oriented box exactly, in every frame; knn, radius, box and voxels in the sensor's
// frame as the world's answers turned into it. Bad boxes refused by name.

#include "support/compare.hpp"
#include "support/rejected.hpp"

#include <random>

namespace eco::test {
namespace {

Eigen::Isometry3d pose_at(int t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(0.4 * t, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.1 * std::sin(t), Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(1.3 * t, 0.4 * t, 0.05 * t);
  return pose;
}

std::vector<Eigen::Vector3f> scan_at(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-12.0, 12.0);
  std::vector<Eigen::Vector3f> scan;
  for (int i = 0; i < 500; ++i) scan.emplace_back(float(u(rng)), float(u(rng)), float(u(rng) / 3));
  return scan;
}

/// `got` (points in the sensor's frame) turned back into the world: `expected`, to rounding.
void expect_same_turned_back(std::vector<Eigen::Vector3d> got, const Eigen::Isometry3d& pose,
                             const std::vector<Eigen::Vector3d>& expected, const char* what) {
  // in the order of their coordinates to 1e-7 m, so that rounding does not reorder equal ones
  auto order = [](std::vector<Eigen::Vector3d> v) {
    std::sort(v.begin(), v.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      const Eigen::Vector3d ra = (a * 1e7).array().round(), rb = (b * 1e7).array().round();
      return std::lexicographical_compare(ra.data(), ra.data() + 3, rb.data(), rb.data() + 3);
    });
    return v;
  };
  for (Eigen::Vector3d& p : got) p = pose * p;
  got = order(got);
  const std::vector<Eigen::Vector3d> want = order(expected);
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) ASSERT_LT((got[i] - want[i]).norm(), 1e-9) << what << " point " << i;
}

TEST(QueryFrames, SensorFrameAndOrientedBoxesMatchBruteForceEveryFrame) {
  for (const Recentring recentring : {Recentring::Quantised, Recentring::Exact}) {
    Config cfg;
    cfg.recentring = recentring;
    cfg.leaf_capacity = 8;
    EgoOctree tree(cfg);
    Oracle oracle(cfg);
    std::mt19937 rng(5), queries(9);
    std::uniform_real_distribution<double> u(-8.0, 8.0), angle(-3.0, 3.0);
    std::size_t boxed = 0;
    for (int t = 0; t < 16; ++t) {
      SCOPED_TRACE("frame " + std::to_string(t));
      const Eigen::Isometry3d pose = pose_at(t);
      const std::vector<Eigen::Vector3f> scan = scan_at(rng);
      (void)tree.update(pose, scan);
      oracle.update(pose, scan, tree.precision_origin());
      for (int j = 0; j < 6; ++j) {
        // a box turned any way, placed in the world
        Eigen::Isometry3d box_pose = Eigen::Isometry3d::Identity();
        box_pose.linear() = (Eigen::AngleAxisd(angle(queries), Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(angle(queries) / 3, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
        box_pose.translation() = pose.translation() + Eigen::Vector3d(u(queries), u(queries), u(queries) / 4);
        const Eigen::Vector3d lo(-std::abs(u(queries)) / 2 - 1, -3, -2), hi(4, 2.5, 1);
        const std::vector<Eigen::Vector3d> expected = oracle.oriented_box(box_pose, lo, hi);
        ASSERT_EQ(sorted(tree.oriented_box(box_pose, lo, hi)), expected) << "oriented box";
        boxed += expected.size();
        // the same box asked in the sensor's frame (its pose there) and in the ego frame
        expect_same_turned_back(tree.oriented_box(pose.inverse() * box_pose, lo, hi, Frame::Sensor), pose, expected,
                                "oriented box, sensor frame");
        Eigen::Isometry3d ego_pose = box_pose;
        ego_pose.translation() -= pose.translation();
        const std::vector<HeldPoint> with = tree.oriented_box_with_attributes(ego_pose, lo, hi, Frame::Ego);
        ASSERT_EQ(with.size(), expected.size()) << "oriented box, ego frame";
        // the box in the sensor's own axes: the oriented box at the sensor's pose
        const std::vector<Eigen::Vector3d> ahead = oracle.oriented_box(pose, lo, hi);
        expect_same_turned_back(tree.box(lo, hi, Frame::Sensor), pose, ahead, "box, sensor frame");
      }
      for (int j = 0; j < 6; ++j) {
        const Eigen::Vector3d q(u(queries), u(queries), u(queries) / 4);  // in the sensor's frame
        const Eigen::Vector3d world = pose * q;
        const std::size_t k = std::size_t(1 + j * 7);
        const std::vector<double> expected = oracle.knn_sq_dists(world, k);
        const std::vector<Neighbor> got = tree.knn(q, k, Frame::Sensor);
        ASSERT_EQ(got.size(), expected.size());
        for (std::size_t r = 0; r < got.size(); ++r) {
          ASSERT_EQ(got[r].sq_dist, expected[r]) << "knn rank " << r;  // measured in the world: exact
          ASSERT_NEAR((got[r].point - q).squaredNorm(), got[r].sq_dist, 1e-9) << "knn point in the sensor's frame";
        }
        std::vector<Eigen::Vector3d> near;
        for (const Neighbor& n : tree.radius(q, 3.0, Frame::Sensor)) near.push_back(n.point);
        expect_same_turned_back(near, pose, oracle.radius(world, 3.0), "radius, sensor frame");
      }
      std::vector<Eigen::Vector3d> centres;
      for (const VoxelKey& key : oracle.voxel_keys(0.5)) {
        centres.push_back((Eigen::Vector3d(double(key.x), double(key.y), double(key.z)).array() + 0.5).matrix() * 0.5);
      }
      expect_same_turned_back(tree.voxelize(0.5, Frame::Sensor), pose, sorted(centres), "voxels, sensor frame");
      if (HasFatalFailure()) return;
    }
    EXPECT_GT(boxed, 500u) << "the oriented boxes held almost nothing";
  }
}

TEST(QueryFrames, BadOrientedBoxesAreRefusedNamingTheArgument) {
  EgoOctree tree;
  (void)tree.update(Eigen::Isometry3d::Identity(), std::vector<Eigen::Vector3f>{Eigen::Vector3f(1, 1, 1)});
  Eigen::Isometry3d skewed = Eigen::Isometry3d::Identity();
  skewed.linear()(0, 1) = 0.5;
  expect_rejected([&] { (void)tree.oriented_box(skewed, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()); },
                  {"box_pose", "not orthonormal"});
  Eigen::Isometry3d nan = Eigen::Isometry3d::Identity();
  nan.translation().x() = std::numeric_limits<double>::quiet_NaN();
  expect_rejected([&] { (void)tree.oriented_box(nan, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()); },
                  {"box_pose", "not finite"});
  expect_rejected([&] { (void)tree.box(Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero(), Frame::Sensor); },
                  {"lo = [1 1 1]", "exceeds hi"});
  EXPECT_EQ(tree.size(), 1u);
}

}  // namespace
}  // namespace eco::test
