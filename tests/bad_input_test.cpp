// Bad input: a clear error naming the value, and nothing lost — the tree is unchanged after a
// rejected call. Non-finite scan points are skipped and counted, never thrown on.

#include "support/compare.hpp"
#include "support/rejected.hpp"
#include "support/streams.hpp"

#include <limits>

namespace eco::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(BadConfig, EachInvalidFieldIsRejectedByName) {
  auto with = [](auto edit) {
    Config c;
    edit(c);
    return c;
  };
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.box_side = 0.0; })); }, {"box_side", "0"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.box_side = -20.0; })); }, {"box_side", "-20"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.box_side = kNaN; })); }, {"box_side", "nan"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.leaf_capacity = 0; })); }, {"leaf_capacity", "0"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.min_cell_size = -0.5; })); },
                  {"min_cell_size", "-0.5"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.min_cell_size = 5.0; })); },
                  {"min_cell_size", "5", "quantum"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.min_cell_size = 1e-9; })); },
                  {"min_cell_size", "24 levels"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.min_cell_size = 4.9e-324; })); },
                  {"min_cell_size", "24 levels"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.box_side = 1.5e-323; })); }, {"min_cell_size"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.quantum_levels = 0; })); }, {"quantum_levels", "0"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.quantum_levels = 9; })); }, {"quantum_levels", "9"});
  expect_rejected(
      [&] {
        EgoOctree t(with([](Config& c) {
          c.density_cap.max_points = 2;
          c.density_cap.cell_size = 0.0;
        }));
      },
      {"density_cap.cell_size", "0"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.recentring = Recentring(7); })); },
                  {"recentring", "7"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.voxel_size = -0.1; })); }, {"voxel_size", "-0.1"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.voxel_size = kNaN; })); }, {"voxel_size", "nan"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.voxel_size = 25.0; })); }, {"voxel_size", "25"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.density_cap = {kNaN, 2}; })); },
                  {"density_cap.cell_size", "nan"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.density_cap = {30.0, 2}; })); },
                  {"density_cap.cell_size", "30", "box_side"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.density_cap = {1e-5, 2}; })); },
                  {"density_cap.cell_size", "1e-05"});
  // a box too large for the cap's cells names both values, whichever of them the user gave
  expect_rejected([&] {
    EgoOctree t(with([](Config& c) {
      c.box_side = 1e5;
      c.density_cap = {0.1, 2};
    }));
  }, {"density_cap.cell_size = 0.1", "box_side = 100000", "conflict"});
  expect_rejected([&] { EgoOctree t(with([](Config& c) { c.density_cap = {0.1, 5000}; })); },
                  {"density_cap.max_points", "5000"});
  // Exact mode has no quantum: a coarse min cell is fine there.
  EXPECT_NO_THROW(EgoOctree(with([](Config& c) {
    c.recentring = Recentring::Exact;
    c.min_cell_size = 5.0;
  })));
}

class BadCalls : public ::testing::Test {
 protected:
  static Config all_in_box() {
    Config c;
    c.insert_policy = InsertPolicy::AllInBox;
    return c;
  }
  void SetUp() override {
    Stream stream(Motion::Smooth, Cloud::Surfaces, cfg_.box_side, 3u);
    for (int t = 0; t < 5; ++t) {
      const auto scan = stream.scan(t);
      tree_.update(stream.pose(t), scan);
      oracle_.update(stream.pose(t), scan, tree_.precision_origin());
    }
    before_ = sorted(tree_.points());
    frames_ = tree_.frame_count();
    pose_ = tree_.pose();
  }
  void expect_unchanged() {
    EXPECT_EQ(sorted(tree_.points()), before_);
    EXPECT_EQ(tree_.frame_count(), frames_);
    EXPECT_TRUE(tree_.pose().isApprox(pose_, 0.0));
    EXPECT_EQ(tree_.check_invariants(), "");
    std::mt19937 rng(1);
    expect_same_answers(tree_, oracle_, rng, "after a rejected call");
  }

  Config cfg_ = all_in_box();
  EgoOctree tree_{cfg_};
  Oracle oracle_{cfg_};
  std::vector<Eigen::Vector3d> before_;
  std::uint32_t frames_ = 0;
  Eigen::Isometry3d pose_;
  std::vector<Eigen::Vector3f> scan_{{1.f, 2.f, 3.f}, {-4.f, 0.5f, 1.f}};
};

TEST_F(BadCalls, NonFinitePoseIsRejectedAndTreeUnchanged) {
  for (double bad : {kNaN, kInf, -kInf}) {
    Eigen::Isometry3d pose = pose_;
    pose.translation().x() = bad;
    expect_rejected([&] { tree_.update(pose, scan_); }, {"world_T_sensor", "not finite"});
    pose = pose_;
    pose.linear()(1, 2) = bad;
    expect_rejected([&] { tree_.update(pose, scan_); }, {"world_T_sensor"});
    Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
    delta.translation().z() = bad;
    expect_rejected([&] { tree_.update_relative(delta, scan_); }, {"previous_T_current"});
  }
  expect_unchanged();
}

/// A pose farther out than any drive, where the root cell's integer lattice indices would near
/// their limits (2^38 quanta: 7.9e11 m at the default quantum), is refused naming it.
TEST_F(BadCalls, APoseFartherThan2To38QuantaIsRejected) {
  Eigen::Isometry3d far = pose_;
  far.translation().y() = -1e12;
  expect_rejected([&] { tree_.update(far, scan_); }, {"world_T_sensor", "farther than 2^38 quanta"});
  far.translation().y() = 1e18;
  expect_rejected([&] { tree_.update(far, scan_); }, {"world_T_sensor", "farther than 2^38 quanta"});
  expect_unchanged();
}

TEST_F(BadCalls, NonOrthonormalRotationIsRejected) {
  Eigen::Isometry3d scaled = pose_;
  scaled.linear() *= 1.01;
  expect_rejected([&] { tree_.update(scaled, scan_); }, {"world_T_sensor", "orthonormal"});
  Eigen::Isometry3d mirrored = pose_;
  mirrored.linear().col(0) *= -1.0;
  expect_rejected([&] { tree_.update(mirrored, scan_); }, {"orthonormal"});
  expect_unchanged();
}

TEST_F(BadCalls, MalformedScanViewIsRejected) {
  expect_rejected([&] { tree_.update(pose_, ScanView(nullptr, 10)); }, {"scan.data", "10"});
  expect_rejected([&] { tree_.update(pose_, ScanView(scan_.front().data(), 2, 2)); }, {"scan.stride = 2"});
  // more points than 32-bit indices name: refused before any is read
  expect_rejected([&] { tree_.update(pose_, ScanView(scan_.front().data(), std::size_t{1} << 32)); },
                  {"scan.count = 4294967296", "4294967295"});
  expect_unchanged();
}

TEST_F(BadCalls, BadQueryArgumentsAreRejected) {
  const Eigen::Vector3d nan_query(kNaN, 0, 0);
  expect_rejected([&] { (void)tree_.knn(nan_query, 3); }, {"knn", "query", "nan"});
  expect_rejected([&] { (void)tree_.radius(Eigen::Vector3d::Zero(), -1.0); }, {"radius = -1"});
  expect_rejected([&] { (void)tree_.radius(Eigen::Vector3d::Zero(), kInf); }, {"radius = inf"});
  expect_rejected([&] { (void)tree_.radius(nan_query, 1.0); }, {"radius", "query"});
  expect_rejected([&] { (void)tree_.box(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 1)); },
                  {"box", "lo", "exceeds hi"});
  expect_rejected([&] { (void)tree_.box(nan_query, Eigen::Vector3d::Ones()); }, {"box", "lo", "nan"});
  expect_rejected([&] { (void)tree_.voxelize(-0.1); }, {"resolution = -0.1"});
  expect_rejected([&] { (void)tree_.voxel_keys(0.0); }, {"resolution = 0"});
  expect_rejected([&] { (void)tree_.voxel_keys(kNaN); }, {"resolution = nan"});
  expect_unchanged();
}

TEST_F(BadCalls, NonFinitePointsAreSkippedAndCounted) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::vector<Eigen::Vector3f> scan = {{nan, 0, 0}, {1, 1, 1}, {0, inf, 0}, {0, 0, -inf}, {2, -1, 0.5f}, {nan, nan, nan}};
  Eigen::Isometry3d pose = pose_;
  pose.translation().x() += 0.5;
  const UpdateStats& st = tree_.update(pose, scan);
  oracle_.update(pose, scan, tree_.precision_origin());
  EXPECT_EQ(st.skipped_nonfinite, 4u);
  EXPECT_EQ(st.inserted, 2u);
  std::mt19937 rng(2);
  expect_same_answers(tree_, oracle_, rng, "after NaN points");
}

/// Grid indices are 64-bit: a voxel or density cell too small for how far the points lie from the
/// world origin is refused by name, never wrapped silently.
/// The smallest positive voxel_size rounds the quantum up from 2^-1074 m without overflowing an
/// int on the way (found by fuzzing the map file's loader, which validates the file's Config).
TEST(BadConfig, ATinyVoxelSizeStillGivesTheQuantum) {
  Config c;
  c.voxel_size = 4.9e-324;
  EXPECT_NO_THROW(c.validate());
  const double least = c.box_side / 7.0;
  EXPECT_GE(c.quantum(), least);
  EXPECT_LT(c.quantum(), 2.0 * least);
}

TEST(GridKeys, UnrepresentableVoxelOrDensityCellIsRejected) {
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() = Eigen::Vector3d(4e9, -3e9, 0.0);  // 4 * 10^9 m from the start
  const std::vector<Eigen::Vector3f> scan{{1, 2, 0.5f}, {-3, 1, 0}};
  EgoOctree tree;
  tree.update(far, scan);
  expect_rejected([&] { (void)tree.voxel_keys(1e-10); }, {"resolution = 1e-10"});
  const std::vector<VoxelKey> keys = tree.voxel_keys(0.25);  // representable: exact keys
  ASSERT_EQ(keys.size(), 2u);
  for (const VoxelKey& k : keys) EXPECT_GT(std::abs(double(k.x) * 0.25 - 4e9), -1.0) << k.x;
  EXPECT_EQ(sorted_keys(keys)[0].x, std::int64_t((4e9 - 3) / 0.25));

  Config capped;
  capped.density_cap = {1e-4, 1};
  EgoOctree tight(capped);
  const Eigen::Isometry3d near = Eigen::Isometry3d::Identity();
  tight.update(near, scan);
  Eigen::Isometry3d farther = far;
  farther.translation().x() = 4e11;  // 4e15 cells of 0.1 mm from the origin: past 2^50
  expect_rejected([&] { tight.update(farther, scan); }, {"density_cap.cell_size", "0.0001"});
  EXPECT_EQ(tight.size(), 2u);  // unchanged
  EXPECT_EQ(tight.frame_count(), 1u);
  EXPECT_EQ(tight.pose().translation(), near.translation());
}

TEST(EmptyTree, QueriesAnswerNothing) {
  EgoOctree tree;
  EXPECT_TRUE(tree.knn(Eigen::Vector3d::Zero(), 3).empty());
  EXPECT_TRUE(tree.radius(Eigen::Vector3d::Zero(), 5.0).empty());
  EXPECT_TRUE(tree.box(-Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones()).empty());
  EXPECT_TRUE(tree.voxel_keys(0.5).empty());
  EXPECT_TRUE(tree.points().empty());
  EXPECT_EQ(tree.size(), 0u);
  EXPECT_TRUE(tree.ego_box().isEmpty());
  EXPECT_EQ(tree.check_invariants(), "");
  tree.update(Eigen::Isometry3d::Identity(), ScanView());  // an empty scan is fine
  EXPECT_EQ(tree.size(), 0u);
  EXPECT_TRUE(tree.knn(Eigen::Vector3d::Zero(), 3).empty());
}

}  // namespace
}  // namespace eco::test
