// The API's conveniences agree with its core: relative updates, strided scans, caller-owned
// buffers, statistics, iteration, the points copied as floats, and the ego box.

#include "support/compare.hpp"
#include "support/streams.hpp"

namespace eco::test {
namespace {

TEST(Api, RelativeUpdatesEqualAbsoluteOnes) {
  Config cfg;
  cfg.insert_policy = InsertPolicy::AllInBox;
  EgoOctree absolute(cfg), relative(cfg);
  Stream stream(Motion::Smooth, Cloud::Surfaces, cfg.box_side, 4u);
  Eigen::Isometry3d previous = Eigen::Isometry3d::Identity();
  for (int t = 0; t < 20; ++t) {
    const Eigen::Isometry3d pose = stream.pose(t);
    const auto scan = stream.scan(t);
    absolute.update(pose, scan);
    relative.update_relative(previous.inverse() * pose, scan);
    previous = pose;
    ASSERT_TRUE(relative.pose().isApprox(pose, 1e-12));
    ASSERT_EQ(relative.size(), absolute.size());
  }
  // Composition rounds differently from the absolute pose, so compare to a micrometre.
  const auto a = sorted(absolute.points()), b = sorted(relative.points());
  for (const Eigen::Vector3d& p : b) EXPECT_LT(std::sqrt(absolute.knn(p, 1)[0].sq_dist), 1e-6);
  EXPECT_EQ(a.size(), b.size());
}

TEST(Api, StridedKittiRecordsReadLikePackedPoints) {
  std::vector<float> kitti;  // x, y, z, reflectance
  std::vector<Eigen::Vector3f> packed;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-9.f, 9.f);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3f p(u(rng), u(rng), u(rng));
    packed.push_back(p);
    kitti.insert(kitti.end(), {p.x(), p.y(), p.z(), 0.5f});
  }
  EgoOctree a, b;
  a.update(Eigen::Isometry3d::Identity(), packed);
  b.update(Eigen::Isometry3d::Identity(), ScanView(kitti.data(), packed.size(), 4));
  EXPECT_EQ(sorted(a.points()), sorted(b.points()));
  EXPECT_EQ(a.size(), 500u);
}

TEST(Api, CopiedPointsAreTheHeldPointsAsFloats) {
  Config cfg;
  cfg.insert_policy = InsertPolicy::AllInBox;
  cfg.leaf_capacity = 4;
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  // far from the world's origin, where a float of the world coordinate rounds (the precision
  // origin is not zero), and through updates that move, split and empty leaves
  Stream stream(Motion::Diagonal, Cloud::Uniform, cfg.box_side, 9u);
  const Eigen::Isometry3d far(Eigen::Translation3d(5000.0, -3000.0, 20.0));
  std::shared_ptr<const Snapshot> before;
  for (int t = 0; t < 8; ++t) {
    const auto scan = stream.scan(t);
    tree.update(far * stream.pose(t), scan);
    oracle.update(far * stream.pose(t), scan, tree.precision_origin());
    if (t == 4) before = tree.snapshot();
    for (const Eigen::Vector3d& origin : std::array<Eigen::Vector3d, 2>{Eigen::Vector3d::Zero(), tree.pose().translation()}) {
      std::vector<float> xyz(3 * tree.size());
      tree.copy_points(xyz, origin);
      const std::vector<Eigen::Vector3d> held = tree.points();  // the same order
      ASSERT_EQ(held.size(), oracle.size());
      for (std::size_t i = 0; i < held.size(); ++i) {
        for (int a = 0; a < 3; ++a) ASSERT_EQ(xyz[3 * i + std::size_t(a)], float(held[i][a] - origin[a])) << i;
      }
    }
  }
  std::vector<float> xyz(3 * before->size());  // a snapshot copies its own frame's
  before->copy_points(xyz);
  const std::vector<Eigen::Vector3d> held = before->points();
  for (std::size_t i = 0; i < held.size(); ++i) ASSERT_EQ(xyz[3 * i + 1], float(held[i].y()));
  std::vector<float> short_by_one(3 * tree.size() - 1);
  EXPECT_THROW(tree.copy_points(short_by_one), std::invalid_argument);
  EgoOctree empty;
  empty.copy_points({});  // nothing to copy
}

TEST(Api, CallerBufferKnnAndStatistics) {
  Config cfg;
  cfg.insert_policy = InsertPolicy::AllInBox;
  cfg.leaf_capacity = 4;
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  Stream stream(Motion::Diagonal, Cloud::Uniform, cfg.box_side, 6u);
  for (int t = 0; t < 6; ++t) {
    const auto scan = stream.scan(t);
    tree.update(stream.pose(t), scan);
    oracle.update(stream.pose(t), scan, tree.precision_origin());
  }
  std::array<Neighbor, 7> buffer;
  const Eigen::Vector3d q = tree.pose().translation();
  ASSERT_EQ(tree.knn(q, std::span<Neighbor>(buffer)), 7u);
  const auto expected = oracle.knn_sq_dists(q, 7);
  for (std::size_t i = 0; i < 7; ++i) EXPECT_EQ(buffer[i].sq_dist, expected[i]);
  EXPECT_EQ(tree.knn(q, 100000).size(), tree.size());  // k beyond the held count

  const Stats s = tree.stats();
  EXPECT_EQ(s.points, oracle.size());
  EXPECT_GT(s.leaves, s.points / cfg.leaf_capacity);
  EXPECT_LE(s.leaves, s.nodes);
  EXPECT_GE(s.max_leaf_depth, int(cfg.quantum_levels));
  EXPECT_LE(s.max_leaf_depth, cfg.max_depth());
  EXPECT_GE(s.mean_leaf_depth, double(cfg.quantum_levels));
  EXPECT_GT(s.bytes, s.points * 12);

  std::size_t visited = 0;
  tree.for_each_point([&](const Eigen::Vector3d& p) {
    ++visited;
    EXPECT_TRUE(tree.ego_box().contains(p));
  });
  EXPECT_EQ(visited, tree.size());
  const Eigen::AlignedBox3d box = tree.ego_box();
  EXPECT_NEAR(box.sizes().x(), cfg.box_side, 1e-9);
  EXPECT_TRUE(box.center().isApprox(tree.pose().translation(), 1e-12));
}

TEST(Api, UpdateStatsCountWhatHappened) {
  Config cfg;
  cfg.insert_policy = InsertPolicy::ShiftInOnly;
  EgoOctree tree(cfg);
  std::vector<Eigen::Vector3f> scan = {{0, 0, 0}, {9.5f, 0, 0}, {11, 0, 0}};
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  UpdateStats st = tree.update(pose, scan);
  EXPECT_EQ(st.inserted, 2u);           // (11, 0, 0) is outside [-10, 10)
  EXPECT_EQ(st.skipped_by_policy, 1u);
  // Box now [-5, 15) in x; both held points stay. The scan lands at x = 5, 14.5, 16 in the world:
  // only 14.5 is in R_in = [10, 15); 5 was in the old box, 16 is outside the new one.
  pose.translation().x() = 5.0;
  st = tree.update(pose, scan);
  EXPECT_EQ(st.pruned, 0u);
  EXPECT_EQ(st.inserted, 1u);
  EXPECT_EQ(st.skipped_by_policy, 2u);
  EXPECT_EQ(tree.size(), 3u);
  pose.translation().x() = 30.0;        // everything leaves
  st = tree.update(pose, {});
  EXPECT_EQ(st.pruned, 3u);
  EXPECT_EQ(tree.size(), 0u);
}

}  // namespace
}  // namespace eco::test

namespace eco::test {
namespace {

TEST(Api, SensorOnAQuantumTieKeepsEdgePointsInTheirCells) {
  for (std::uint32_t k : {1u, 2u, 3u, 4u}) {
    Config cfg;
    cfg.quantum_levels = k;
    cfg.min_cell_size = 0.01;
    cfg.insert_policy = InsertPolicy::AllInBox;
    EgoOctree tree(cfg);
    Oracle oracle(cfg);
    const double q = cfg.box_side / double((1u << k) - 1u);
    for (int t = 0; t < 6; ++t) {
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = Eigen::Vector3d::Constant((t + 0.5) * q);  // exactly between lattice steps
      std::vector<Eigen::Vector3f> scan;
      const float edge = float(-cfg.box_side / 2);
      for (float y : {edge, 0.f, -edge * 0.999f}) scan.push_back({edge, y, edge});
      tree.update(pose, scan);
      oracle.update(pose, scan, tree.precision_origin());
      ASSERT_EQ(tree.check_invariants(), "") << "k = " << k << ", frame " << t;
      ASSERT_EQ(sorted(tree.points()), oracle.points());
    }
  }
}

}  // namespace
}  // namespace eco::test
