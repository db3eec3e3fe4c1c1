// A long drive: 5,000 frames at ~1 m per frame through an endless static world.
//
// The bounds checked, and why:
// * points held <= 2 x 21 x 21 x 6: the box (20 m) meets at most 21 x 21 cells of the world's
//   1 m grid across, 6 cells of its slab high, each with at most 2 points; the content invariant
//   keeps nothing else.
// * bytes used after frame 500 never exceed twice the most used in frames 1-500: nodes and
//   chunks come from pools whose free lists recycle every slot, so they grow only past the
//   high-water mark of a working set that is stationary once the box has turned over
//   (20 frames); twice allows one doubling of a std::vector.
// * leaf depth: max <= Config::max_depth() by construction; the mean stays within ±1 of the
//   first frames' (docs/design.md, "Geometry that does not drift"), because the root follows
//   the sensor.
// The held set is also compared with the brute-force oracle every frame by size, every 250
// frames in full. Under AddressSanitizer the drive stops after 600 frames (the memory it checks
// there is the recycled slots', reused from frame 20 on); the release build drives all 5,000.

#include "support/compare.hpp"
#include "support/streams.hpp"
#include "support/hashed_world.hpp"
#include "support/sanitizers.hpp"

#include <cstdio>

namespace eco::test {
namespace {

class LongDrive : public ::testing::TestWithParam<Recentring> {};

TEST_P(LongDrive, MemoryAndDepthStayBoundedOverFiveThousandFrames) {
  Config cfg;
  cfg.recentring = GetParam();
  cfg.leaf_capacity = 8;
  cfg.insert_policy = InsertPolicy::ShiftInOnly;  // the paper's: each frame adds only what entered
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  HashedWorld world;
  std::mt19937 rng(3);
  const std::size_t max_points = 2 * 21 * 21 * 6;
  std::size_t warm_bytes = 0;
  double first_mean_depth = 0.0;
  const int frames = kAddressSanitizer ? 600 : 5000;
  for (int t = 0; t < frames; ++t) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    const double x = 1.0 * t, y = 40.0 * std::sin(t / 150.0);
    const double heading = std::atan2(40.0 / 150.0 * std::cos(t / 150.0), 1.0);
    pose.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(x, y, 0.3 * std::sin(t / 40.0));
    const std::vector<Eigen::Vector3f> scan = world.scan(pose, cfg.box_side);
    tree.update(pose, scan);
    oracle.update(pose, scan, tree.precision_origin());
    ASSERT_EQ(tree.size(), oracle.size()) << "frame " << t;

    const Stats s = tree.stats();
    ASSERT_LE(s.points, max_points) << "frame " << t;
    ASSERT_LE(s.max_leaf_depth, cfg.max_depth());
    if (t < 500) {
      warm_bytes = std::max(warm_bytes, s.bytes);
    } else {
      ASSERT_LE(s.bytes, 2 * warm_bytes) << "memory grew at frame " << t;
    }
    if (t == 20) first_mean_depth = s.mean_leaf_depth;
    if (t > 20) {
      ASSERT_NEAR(s.mean_leaf_depth, first_mean_depth, 1.0) << "frame " << t;
    }
    if (t % 1000 == 0) {
      RecordProperty("points_at_" + std::to_string(t), int(s.points));
      std::printf("frame %d: %zu points, %zu nodes, mean depth %.2f, max depth %d, %zu bytes\n", t,
                  s.points, s.nodes, s.mean_leaf_depth, s.max_leaf_depth, s.bytes);
    }
    if (t % 250 == 0 || t == frames - 1) {
      expect_same_answers(tree, oracle, rng, "frame " + std::to_string(t));
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(tree.size(), 1000u);  // the drive really kept a populated map
}

INSTANTIATE_TEST_SUITE_P(Modes, LongDrive, ::testing::Values(Recentring::Quantised, Recentring::Exact),
                         mode_name);

}  // namespace
}  // namespace eco::test
