// Config::region, the region held about the sensor inside the cube: a ball, a box turned with the
// sensor's heading, a box turned with its whole orientation. Against the brute force after every
// frame of spins in place, U-turns, tumbling drives and a drive a million metres out, in both
// re-centring modes, with the density cap, ages, attributes and free-space clearing; the regions
// that do not fit the cube, or that ShiftInOnly cannot feed, refused by name; a map holding a
// region saved and loaded.

#include "support/compare.hpp"
#include "support/streams.hpp"
#include "support/rejected.hpp"
#include "support/temp_dir.hpp"

#include <eco/config_fields.hpp>

#include <random>
#include <tuple>

namespace eco::test {
namespace {

enum class Kind { Ball, YawBox, FullBox };
enum class Drive { Spin, UTurn, Tumble, FarOut };
enum class Extras { None, CapAgesAttributes, Clearing };

Region region_of(Kind kind) {
  Region r;
  if (kind == Kind::Ball) {
    r.shape = RegionShape::Ball;
    r.radius = 8.5;
    return r;
  }
  r.shape = RegionShape::OrientedBox;
  r.turn_with = kind == Kind::YawBox ? TurnWith::Yaw : TurnWith::Full;
  r.ahead = 7.0, r.behind = 2.0, r.left = 3.0, r.right = 4.0, r.up = 2.5, r.down = 1.5;
  return r;
}

/// Frame t's pose: each drive turns the region through what a box of the world's axes never sees.
Eigen::Isometry3d pose_of(Drive drive, int t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  switch (drive) {
    case Drive::Spin:  // in place, 20 degrees a frame, drifting a little
      pose.linear() = Eigen::AngleAxisd(0.35 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      pose.translation() = Eigen::Vector3d(0.01 * t, -0.02 * t, 0.0);
      break;
    case Drive::UTurn: {  // 12 frames on, a half circle of radius 4 m in 8 frames, then back
      const double s = std::min(t, 12) * 1.0;
      const double a = std::clamp(t - 12, 0, 8) * M_PI / 8;
      const double back = std::max(t - 20, 0) * 1.0;
      pose.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      pose.translation() = Eigen::Vector3d(s + 4.0 * std::sin(a) - back, 4.0 - 4.0 * std::cos(a), 0.0);
      break;
    }
    case Drive::Tumble:  // a hand-held sensor: every axis turning
      pose.linear() = (Eigen::AngleAxisd(0.3 * t, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.45 * t, Eigen::Vector3d::UnitY()) *
                       Eigen::AngleAxisd(0.2 * t, Eigen::Vector3d::UnitX()))
                          .toRotationMatrix();
      pose.translation() = Eigen::Vector3d(0.4 * t, 0.3 * std::sin(0.5 * t), 0.2 * t);
      break;
    case Drive::FarOut:  // a million metres out, turning as it goes: precision-origin moves
      pose.linear() = Eigen::AngleAxisd(0.25 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      pose.translation() = Eigen::Vector3d(1e6 + 1.7 * t, -2e6 + 900.0 * (t / 7), 12.0);
      break;
  }
  return pose;
}

/// A scan reaching past the cube, some points not finite.
AttributedScan scan_of(int t, std::mt19937& rng) {
  AttributedScan scan;
  std::uniform_real_distribution<double> u(-14.0, 14.0);
  for (int i = 0; i < 400; ++i) {
    scan.points.emplace_back(float(u(rng)), float(u(rng)), float(u(rng) / 3));
    scan.attributes.ids.push_back(std::uint32_t(t * 1000 + i));
    scan.attributes.intensities.push_back(float(i % 50));
    scan.attributes.times.push_back(1.7e9 + 0.1 * t + 1e-4 * i);
  }
  if (t % 3 == 0) scan.points[7] = {std::numeric_limits<float>::quiet_NaN(), 0.f, 0.f};
  return scan;
}

using Params = std::tuple<Recentring, Kind, Drive, Extras>;
class RegionOracle : public ::testing::TestWithParam<Params> {};

TEST_P(RegionOracle, HeldSetAndQueriesMatchBruteForceEveryFrame) {
  const auto [recentring, kind, drive, extras] = GetParam();
  Config cfg;
  cfg.recentring = recentring;
  cfg.leaf_capacity = 8;
  cfg.region = region_of(kind);
  if (extras == Extras::CapAgesAttributes) {
    cfg.density_cap = {0.5, 2};
    cfg.max_age_frames = 6;
    cfg.attributes = {true, true, true};
  }
  if (extras == Extras::Clearing) cfg.clearing.enabled = true;
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  std::mt19937 rng(17), queries(3);
  std::size_t pruned = 0, refused = 0;
  for (int t = 0; t < 28; ++t) {
    SCOPED_TRACE("frame " + std::to_string(t));
    const AttributedScan scan = scan_of(t, rng);
    const Eigen::Isometry3d pose = pose_of(drive, t);
    const UpdateStats& st = extras == Extras::CapAgesAttributes ? tree.update(pose, scan.view()) : tree.update(pose, scan.points);
    oracle.update(pose, scan.points, tree.precision_origin(), scan.attributes, tree.time_origin());
    pruned += st.pruned;
    refused += st.skipped_by_policy;
    ASSERT_EQ(st.inserted + st.skipped_nonfinite + st.skipped_by_policy + st.skipped_by_density + st.skipped_by_age,
              scan.points.size());
    if (extras == Extras::CapAgesAttributes) {
      expect_same_held_attributes(tree, oracle);
      if (HasFatalFailure()) return;
    }
    expect_same_answers(tree, oracle, queries, "frame " + std::to_string(t));
    if (HasFatalFailure()) return;
  }
  // a ball spinning in place drops only what its drift leaves behind; the others turn their walls
  EXPECT_GT(pruned, kind == Kind::Ball && drive == Drive::Spin ? 0u : 100u) << "the region's moves never dropped a point";
  EXPECT_GT(refused, 1000u) << "the region never refused a scan point the cube holds";
}

std::string param_name(const ::testing::TestParamInfo<Params>& info) {
  const auto [recentring, kind, drive, extras] = info.param;
  const char* kinds[] = {"Ball", "YawBox", "FullBox"};
  const char* drives[] = {"Spin", "UTurn", "Tumble", "FarOut"};
  const char* more[] = {"", "_CapAgesAttributes", "_Clearing"};
  return name(recentring) + "_" + kinds[int(kind)] + "_" + drives[int(drive)] + more[int(extras)];
}

INSTANTIATE_TEST_SUITE_P(Streams, RegionOracle,
                         ::testing::Combine(::testing::Values(Recentring::Quantised, Recentring::Exact),
                                            ::testing::Values(Kind::Ball, Kind::YawBox, Kind::FullBox),
                                            ::testing::Values(Drive::Spin, Drive::UTurn, Drive::Tumble, Drive::FarOut),
                                            ::testing::Values(Extras::None, Extras::CapAgesAttributes, Extras::Clearing)),
                         param_name);

TEST(RegionWork, SpinningInPlaceABallTouchesNoPointAndABoxOnlyWhatItsWallsSweep) {
  for (const Kind kind : {Kind::Ball, Kind::YawBox}) {
    Config cfg;
    cfg.region = region_of(kind);
    EgoOctree tree(cfg);
    Oracle oracle(cfg);
    std::mt19937 rng(4), queries(5);
    std::size_t tested = 0, pruned = 0, held = 0;
    for (int t = 0; t < 24; ++t) {
      SCOPED_TRACE("frame " + std::to_string(t));
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::AngleAxisd(1.75 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();  // 1,000 degrees/s at 10 Hz
      pose.translation() = Eigen::Vector3d(3.25, -1.5, 0.5);
      const AttributedScan scan = scan_of(t, rng);
      const UpdateStats& st = tree.update(pose, scan.points);
      oracle.update(pose, scan.points, tree.precision_origin());
      if (t > 0) {
        tested += st.region_tested;
        pruned += st.pruned;
      }
      held += tree.size();
      expect_same_answers(tree, oracle, queries, "frame " + std::to_string(t));
      if (HasFatalFailure()) return;
    }
    if (kind == Kind::Ball) {
      EXPECT_EQ(tested, 0u) << "a ball turning about its centre is the same ball";
      EXPECT_EQ(pruned, 0u);
    } else {
      EXPECT_GT(pruned, 0u) << "the box's walls swept nothing";
      EXPECT_GT(tested, 0u);
      EXPECT_LT(tested, held) << "every held point tested: the walk did not keep the box's inside whole";
    }
  }
}

TEST(RegionConfig, RegionsTheCubeCannotHoldAreRefusedNamingBoth) {
  Config c;
  c.region.shape = RegionShape::Ball;
  c.region.radius = 10.5;  // the cube's half side is 10
  expect_rejected([&] { c.validate(); }, {"region.radius = 10.5", "reaches 10.5 m", "box_side / 2 = 10 m"});
  c.region.radius = 0.0;
  expect_rejected([&] { c.validate(); }, {"region.radius = 0", "empty region"});
  c.region = region_of(Kind::YawBox);
  c.region.ahead = 9.5;  // hypot(9.5, 4) = 10.3: the corner sweeps past the cube as it turns
  expect_rejected([&] { c.validate(); }, {"region.ahead = 9.5", "reaches 10.3", "box_side / 2 = 10 m"});
  c.region.ahead = 9.0;  // hypot(9, 4) = 9.85 fits turning about the vertical ...
  EXPECT_NO_THROW(c.validate());
  c.region.turn_with = TurnWith::Full;  // ... but not turning freely: |(9, 4, 2.5)| = 10.16
  expect_rejected([&] { c.validate(); }, {"region.ahead = 9", "reaches 10.16", "the cube must hold the region"});
  c.region = region_of(Kind::Ball);
  c.insert_policy = InsertPolicy::ShiftInOnly;
  expect_rejected([&] { c.validate(); }, {"insert_policy = ShiftInOnly", "needs AllInBox"});
  EXPECT_THROW(EgoOctree{c}, std::invalid_argument);
}

TEST(RegionConfig, TheFieldsReadAsTheCommandLineSpellsThem) {
  Config c;
  config_field("region.shape").parse(c, "oriented_box");
  config_field("region.turn_with").parse(c, "FULL");
  config_field("region.ahead").parse(c, "6");
  EXPECT_EQ(c.region.shape, RegionShape::OrientedBox);
  EXPECT_EQ(c.region.turn_with, TurnWith::Full);
  EXPECT_EQ(c.region.ahead, 6.0);
  EXPECT_EQ(config_field("region.shape").format(c), "oriented_box");
  expect_rejected([&] { config_field("region.shape").parse(c, "sphere"); }, {"region.shape", "sphere"});
}

TEST(RegionSaveLoad, AMapHoldingARegionGoesOnAfterLoadingAsOneRun) {
  Config cfg;
  cfg.region = region_of(Kind::YawBox);
  cfg.density_cap = {0.5, 2};
  EgoOctree straight(cfg), first(cfg);
  std::mt19937 rng_a(8), rng_b(8);
  TempDir dir("eco-region");
  for (int t = 0; t < 20; ++t) {
    const AttributedScan a = scan_of(t, rng_a), b = scan_of(t, rng_b);
    (void)straight.update(pose_of(Drive::UTurn, t), a.points);
    if (t < 10) (void)first.update(pose_of(Drive::UTurn, t), b.points);
    if (t == 9) first.save((dir / "region.eco").string());
    if (t == 9) first = EgoOctree::load((dir / "region.eco").string());
    if (t >= 10) (void)first.update(pose_of(Drive::UTurn, t), b.points);
  }
  EXPECT_EQ(first.config().region.shape, RegionShape::OrientedBox);
  EXPECT_EQ(first.config().region.left, 3.0);
  EXPECT_EQ(sorted(straight.points()), sorted(first.points()));
}

}  // namespace
}  // namespace eco::test
