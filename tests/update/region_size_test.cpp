// Config::region's size: the lookahead (ahead, or a ball's radius, grown by the smoothed speed
// times region.lookahead, with hysteresis, up to what the cube holds) and the budget
// (region.max_points: the region shrinks about the sensor, in steps of 1 %, until the held points
// fit, and starts whole again each frame). Against the brute force after every frame, in both
// re-centring modes, with the density cap and free-space clearing; never over the budget; the
// size reported in UpdateStats::region; saved and loaded mid-drive.

#include "support/compare.hpp"
#include "support/rejected.hpp"
#include "support/streams.hpp"
#include "support/temp_dir.hpp"

#include <random>
#include <tuple>

namespace eco::test {
namespace {

enum class Shape { Ball, YawBox, FullBox };
enum class Extras { None, Cap, Clearing };

Region region_of(Shape shape) {
  Region r;
  if (shape == Shape::Ball) {
    r.shape = RegionShape::Ball;
    r.radius = 5.0;
    return r;
  }
  r.shape = RegionShape::OrientedBox;
  r.turn_with = shape == Shape::YawBox ? TurnWith::Yaw : TurnWith::Full;
  r.ahead = 4.0, r.behind = 2.0, r.left = 3.0, r.right = 3.0, r.up = 2.0, r.down = 1.5;
  return r;
}

/// A drive that speeds up from standing to 6 m/s, brakes, turns about and stands: the lookahead
/// grows, holds and shrinks back. 10 Hz, so the speed is the step x 10.
Eigen::Isometry3d pose_at(int t) {
  static const std::vector<double> steps = [] {
    std::vector<double> s;
    for (int i = 0; i < 40; ++i) {
      const double v = i < 12 ? 0.05 * i : i < 22 ? 0.6 + 0.02 * (i % 2 ? 1 : -1) : i < 30 ? 0.6 - 0.07 * (i - 22) : 0.0;
      s.push_back(std::max(v, 0.0));
    }
    return s;
  }();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  double heading = 0.0;
  Eigen::Vector2d p(0.0, 0.0);
  for (int i = 0; i <= t && i < int(steps.size()); ++i) {
    heading = i > 24 ? 0.4 * (i - 24) : 0.0;
    p += steps[std::size_t(i)] * Eigen::Vector2d(std::cos(heading), std::sin(heading));
  }
  pose.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(p.x(), p.y(), 0.0);
  return pose;
}

/// A scan of `n` points reaching past the cube, with times 0.1 s apart frame to frame.
AttributedScan scan_of(int t, std::size_t n, std::mt19937& rng) {
  AttributedScan scan;
  std::uniform_real_distribution<double> u(-12.0, 12.0);
  for (std::size_t i = 0; i < n; ++i) {
    scan.points.emplace_back(float(u(rng)), float(u(rng)), float(u(rng) / 4));
    scan.attributes.times.push_back(100.0 + 0.1 * t + 1e-5 * double(i));
  }
  return scan;
}

using Params = std::tuple<Recentring, Shape, Extras>;
class RegionSizeOracle : public ::testing::TestWithParam<Params> {};

TEST_P(RegionSizeOracle, LookaheadAndBudgetMatchBruteForceAndTheBudgetHoldsEveryFrame) {
  const auto [recentring, shape, extras] = GetParam();
  Config cfg;
  cfg.recentring = recentring;
  cfg.leaf_capacity = 8;
  cfg.region = region_of(shape);
  cfg.region.lookahead = 1.0;
  cfg.region.max_points = shape == Shape::Ball ? 260 : 50;
  if (extras == Extras::Cap) cfg.density_cap = {0.5, 2};
  if (extras == Extras::Clearing) cfg.clearing.enabled = true;
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  std::mt19937 rng(31), queries(7);
  double largest_growth = 0.0, smallest_scale = 1.0;
  int whole_after_shrinking = 0;
  for (int t = 0; t < 40; ++t) {
    SCOPED_TRACE("frame " + std::to_string(t));
    // dense, then thin, then dense again: the budget shrinks the region and lets it grow back
    const AttributedScan scan = scan_of(t, t >= 18 && t < 26 ? 3 : 500, rng);
    ScanView view(scan.points);
    view.times = scan.attributes.times.data();  // the speed from the scans' times
    const UpdateStats& st = tree.update(pose_at(t), view);
    oracle.update(pose_at(t), scan.points, tree.precision_origin(), scan.attributes);
    ASSERT_LE(tree.size(), cfg.region.max_points) << "over the budget";
    EXPECT_EQ(st.region.scale, oracle.region_scale());
    const Region grown = cfg.region.sized(oracle.region_growth(), oracle.region_scale());
    EXPECT_EQ(st.region.radius, grown.radius);
    EXPECT_EQ(st.region.ahead, grown.ahead);
    EXPECT_EQ(st.region.left, grown.left);
    largest_growth = std::max(largest_growth, oracle.region_growth());
    if (st.region.scale == 1.0 && smallest_scale < 1.0) ++whole_after_shrinking;
    smallest_scale = std::min(smallest_scale, st.region.scale);
    expect_same_answers(tree, oracle, queries, "frame " + std::to_string(t));
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(largest_growth, 2.0) << "at 6 m/s a 1 s lookahead grew the region by little";
  EXPECT_LT(smallest_scale, 0.8) << "the budget never shrank the region";
  EXPECT_GT(whole_after_shrinking, 0) << "the region never grew back as the scans thinned";
  EXPECT_LT(oracle.region_growth(), 0.1 * largest_growth) << "standing still, the lookahead did not come back";
}

std::string param_name(const ::testing::TestParamInfo<Params>& info) {
  const auto [recentring, shape, extras] = info.param;
  const char* shapes[] = {"Ball", "YawBox", "FullBox"};
  const char* more[] = {"", "_Cap", "_Clearing"};
  return name(recentring) + "_" + shapes[int(shape)] + more[int(extras)];
}

INSTANTIATE_TEST_SUITE_P(Streams, RegionSizeOracle,
                         ::testing::Combine(::testing::Values(Recentring::Quantised, Recentring::Exact),
                                            ::testing::Values(Shape::Ball, Shape::YawBox, Shape::FullBox),
                                            ::testing::Values(Extras::None, Extras::Cap, Extras::Clearing)),
                         param_name);

TEST(RegionLookahead, ASpeedNearAThresholdDoesNotMakeTheRegionBreathe) {
  Config cfg;
  cfg.region = region_of(Shape::YawBox);
  cfg.region.lookahead = 0.5;
  EgoOctree tree(cfg);
  double x = 0.0, last_ahead = 0.0;
  int changes = 0;
  for (int t = 0; t < 80; ++t) {
    x += t % 2 ? 0.42 : 0.38;  // 4 m/s, +-5 % frame to frame
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation().x() = x;
    const UpdateStats& st = tree.update(pose, std::vector<Eigen::Vector3f>{});
    if (t >= 20 && st.region.ahead != last_ahead) ++changes;
    last_ahead = st.region.ahead;
  }
  EXPECT_EQ(changes, 0) << "the region breathed with the speed's noise";
  const UpdateStats& last = tree.last_update();
  EXPECT_NEAR(last.region.speed, 4.0, 0.2);
  EXPECT_GE(last_ahead, 4.0 + last.region.speed * 0.5) << "ahead does not cover what 0.5 s at its speed reaches";
}

TEST(RegionLookahead, TheGrowthStopsWhereTheCubeIsFull) {
  for (const Shape shape : {Shape::Ball, Shape::YawBox, Shape::FullBox}) {
    Region r = region_of(shape);
    const double most = r.max_growth(10.0);
    EXPECT_LE(r.sized(most, 1.0).reach(), 10.0);
    EXPECT_GT(r.sized(most + 1e-6, 1.0).reach(), 10.0);
    EXPECT_GT(most, 0.0);
  }
  Config cfg;
  cfg.region = region_of(Shape::Ball);
  cfg.region.lookahead = 10.0;  // at 30 m/s it would ask for 300 m
  EgoOctree tree(cfg);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int t = 0; t < 20; ++t) {
    pose.translation().x() += 3.0;
    const UpdateStats& st = tree.update(pose, std::vector<Eigen::Vector3f>{});
    EXPECT_LE(st.region.radius, cfg.box_side / 2);
  }
  EXPECT_EQ(tree.last_update().region.radius, cfg.region.sized(cfg.region.max_growth(10.0), 1.0).radius);
  EXPECT_NEAR(tree.last_update().region.speed, 30.0, 1.0);
}

TEST(RegionBudget, ABudgetBelowWhatOnePercentHoldsEmptiesTheMap) {
  Config cfg;
  cfg.region = region_of(Shape::Ball);
  cfg.region.max_points = 2;
  EgoOctree tree(cfg);
  // five points at the sensor itself: no scale keeps fewer than five
  const std::vector<Eigen::Vector3f> scan(5, Eigen::Vector3f::Zero());
  const UpdateStats& st = tree.update(Eigen::Isometry3d::Identity(), scan);
  EXPECT_EQ(tree.size(), 0u);
  EXPECT_EQ(st.over_budget, 5u);
  EXPECT_EQ(st.region.scale, 0.0);
  EXPECT_EQ(st.region.radius, 0.0);
  (void)tree.update(Eigen::Isometry3d::Identity(), std::vector<Eigen::Vector3f>{Eigen::Vector3f(1, 0, 0)});
  EXPECT_EQ(tree.size(), 1u) << "the next frame starts from the whole region again";
  EXPECT_EQ(tree.last_update().region.scale, 1.0);
}

TEST(RegionSizeConfig, LookaheadAndBudgetNeedARegionThatCanGrowOrShrink) {
  Config c;
  c.region.lookahead = 1.0;
  expect_rejected([&] { c.validate(); }, {"region.lookahead = 1", "ball or oriented_box"});
  c.region.lookahead = 0.0;
  c.region.max_points = 1000;
  expect_rejected([&] { c.validate(); }, {"region.max_points = 1000", "ball or oriented_box"});
  c.region = region_of(Shape::Ball);
  c.region.lookahead = -1.0;
  expect_rejected([&] { c.validate(); }, {"region.lookahead = -1"});
  c.region.lookahead = 1.0;
  c.region.frame_period = 0.0;
  expect_rejected([&] { c.validate(); }, {"region.frame_period = 0"});
}

TEST(RegionSizeSaveLoad, AMapWithLookaheadAndBudgetGoesOnAfterLoadingAsOneRun) {
  Config cfg;
  cfg.region = region_of(Shape::YawBox);
  cfg.region.lookahead = 1.0;
  cfg.region.max_points = 300;
  EgoOctree straight(cfg), first(cfg);
  std::mt19937 rng_a(8), rng_b(8);
  TempDir dir("eco-region-size");
  for (int t = 0; t < 30; ++t) {
    const AttributedScan a = scan_of(t, 400, rng_a), b = scan_of(t, 400, rng_b);
    ScanView va(a.points), vb(b.points);
    va.times = a.attributes.times.data();
    vb.times = b.attributes.times.data();
    const UpdateStats& st = straight.update(pose_at(t), va);
    if (t == 12) {
      first.save((dir / "sized.eco").string());
      first = EgoOctree::load((dir / "sized.eco").string());
    }
    const UpdateStats& again = first.update(pose_at(t), vb);
    EXPECT_EQ(again.region.ahead, st.region.ahead) << "frame " << t;
    EXPECT_EQ(again.region.scale, st.region.scale) << "frame " << t;
    EXPECT_EQ(sorted(straight.points()), sorted(first.points())) << "frame " << t;
  }
}

TEST(RegionSizeSaveLoad, AVersionTwoFileStillLoadsAndGoesOnAsVersionThree) {
  // written at b51d9aa by `eco run --frames 3 --box_side 12 --region.shape ball --region.radius 6
  // --density_cap.cell_size 1 --density_cap.max_points 1`, before the region had a size to keep
  const std::string v2 = std::string(ECO_SOURCE_DIR) + "/tests/persist/data/region-v2.eco";
  EgoOctree tree = EgoOctree::load(v2);
  EXPECT_EQ(tree.config().region.shape, RegionShape::Ball);
  EXPECT_EQ(tree.config().region.radius, 6.0);
  EXPECT_EQ(tree.config().region.lookahead, 0.0);
  EXPECT_EQ(tree.frame_count(), 3u);
  EXPECT_EQ(tree.check_invariants(), "");
  ASSERT_GT(tree.size(), 50u);
  for (const Eigen::Vector3d& p : tree.points()) ASSERT_LE((p - tree.pose().translation()).norm(), 6.0 + 1e-5);
  TempDir dir("eco-region-v2");
  const std::string v3 = (dir / "v3.eco").string();
  tree.save(v3);
  EgoOctree again = EgoOctree::load(v3);
  EXPECT_EQ(sorted(again.points()), sorted(tree.points()));
  const std::vector<Eigen::Vector3f> scan{Eigen::Vector3f(2, 0, 0), Eigen::Vector3f(7, 0, 0)};
  (void)tree.update(tree.pose(), scan);
  (void)again.update(again.pose(), scan);
  EXPECT_EQ(sorted(again.points()), sorted(tree.points()));
}

}  // namespace
}  // namespace eco::test
