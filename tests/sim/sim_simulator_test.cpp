// The simulator: deterministic, the same world for a seed whatever the drive's length, HDL-64E-like
// scans, a drive with straights and turns, each manoeuvre moving as named, labels that mark exactly the returns from moving cars,
// and KITTI output the reader reads back.

#include <eco/io/kitti_sequence.hpp>
#include <eco/sim/simulator.hpp>

#include "support/overlap.hpp"
#include "support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <numbers>
#include <set>

namespace eco::sim {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

void expect_same_frame(const SimFrame& a, const SimFrame& b) {
  ASSERT_EQ(a.cloud.size(), b.cloud.size());
  EXPECT_EQ(a.world_T_lidar.matrix(), b.world_T_lidar.matrix());
  EXPECT_EQ(0, std::memcmp(a.cloud.points.data(), b.cloud.points.data(), a.cloud.size() * 12));
  EXPECT_EQ(a.cloud.intensity, b.cloud.intensity);
  EXPECT_EQ(a.labels, b.labels);
}

std::vector<Eigen::Vector3f> select(const SimFrame& f, bool moving) {
  std::vector<Eigen::Vector3f> out;
  for (std::size_t i = 0; i < f.cloud.size(); ++i) {
    if (io::label::is_moving(f.labels[i]) == moving) out.push_back(f.cloud.points[i]);
  }
  return out;
}

TEST(Simulator, SameSeedSameBytesInAnyOrder) {
  SimConfig config;
  config.frames = 20;
  const Simulator a(config), b(config);
  const SimFrame late = b.frame(13);
  expect_same_frame(a.frame(0), b.frame(0));
  expect_same_frame(a.frame(13), late);
  config.seed = 2;
  const Simulator other(config);
  EXPECT_NE(other.frame(0).cloud.size(), a.frame(0).cloud.size());
}

TEST(Simulator, TheWorldDependsOnTheSeedAloneNotOnTheDrivesLength) {
  // a 40-frame drive is the first 40 frames of a 400-frame one (save, load and go on can then
  // match one straight run), moving cars and all
  for (const std::uint64_t seed : {1u, 4u}) {
    SimConfig config;
    config.seed = seed;
    config.lidar.beams = 32;
    config.lidar.columns = 1024;
    config.frames = 40;
    const Simulator short_drive(config);
    config.frames = 400;
    const Simulator long_drive(config);
    std::size_t moving = 0;
    for (const std::size_t t : {0u, 17u, 39u}) {
      SCOPED_TRACE(std::to_string(seed) + " frame " + std::to_string(t));
      const SimFrame a = short_drive.frame(t);
      expect_same_frame(a, long_drive.frame(t));
      moving += select(a, true).size();
    }
    EXPECT_GT(moving, 100u) << "moving cars in view";
  }
}

TEST(Simulator, ScansLookLikeAnHdl64e) {
  const SimConfig config;
  const Simulator sim(config);
  const SimFrame f = sim.frame(3);
  EXPECT_GT(f.cloud.size(), 100000u);  // ~120 k returns of 128 k rays
  EXPECT_LT(f.cloud.size(), 128000u);
  ASSERT_EQ(f.labels.size(), f.cloud.size());
  ASSERT_EQ(f.cloud.intensity.size(), f.cloud.size());
  const LidarModel& l = config.lidar;
  std::set<long> beams;
  const std::set<std::uint32_t> known = {io::label::kCar, io::label::kRoad, io::label::kSidewalk,
                                         io::label::kBuilding, io::label::kVegetation, io::label::kTrunk,
                                         io::label::kPole, io::label::kMovingCar};
  for (std::size_t i = 0; i < f.cloud.size(); ++i) {
    const Eigen::Vector3d p = f.cloud.points[i].cast<double>();
    const double range = p.norm();
    ASSERT_GT(range, l.min_range - 6 * l.range_noise);
    ASSERT_LT(range, l.max_range + 6 * l.range_noise);
    const double elevation = std::asin(p.z() / range) / kDegree;
    ASSERT_GE(elevation, l.fov_down_deg - 1e-3);
    ASSERT_LE(elevation, l.fov_up_deg + 1e-3);
    beams.insert(std::lround((elevation - l.fov_down_deg) / (l.fov_up_deg - l.fov_down_deg) * (l.beams - 1)));
    ASSERT_GE(f.cloud.intensity[i], 0.0f);
    ASSERT_LE(f.cloud.intensity[i], 1.0f);
    ASSERT_TRUE(known.count(f.labels[i])) << f.labels[i];
  }
  EXPECT_EQ(beams.size(), 64u);  // every beam returns something
}

TEST(Simulator, DrivesAboutAMetreAFrameWithTurns) {
  SimConfig config;
  config.frames = 400;
  const Simulator sim(config);
  double turned = 0.0;
  for (std::size_t i = 1; i < sim.size(); ++i) {
    const Eigen::Isometry3d a = sim.pose(i - 1), b = sim.pose(i);
    const double step = (b.translation() - a.translation()).head<2>().norm();
    ASSERT_GT(step, 0.6) << i;  // 1 m on straights; tighter or wider on the corner arcs
    ASSERT_LT(step, 1.4) << i;
    EXPECT_NEAR(b.translation().z(), config.lidar.mount_height, 1e-12);
    EXPECT_LT((b.linear().transpose() * b.linear() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    const Eigen::Vector3d fa = a.linear().col(0), fb = b.linear().col(0);
    turned += std::abs(std::atan2(fa.x() * fb.y() - fa.y() * fb.x(), fa.head<2>().dot(fb.head<2>())));
  }
  EXPECT_GT(turned, 80.0 * kDegree);  // at least one corner in 400 m
}

/// The heading of `pose`: its x axis on the ground [rad].
double heading(const Eigen::Isometry3d& pose) { return std::atan2(pose.linear()(1, 0), pose.linear()(0, 0)); }
/// `a` - `b` in (-pi, pi].
double turn(double a, double b) { return std::remainder(a - b, 2.0 * std::numbers::pi); }

TEST(Simulator, EveryManoeuvreMovesAsNamed) {
  SimConfig config;
  config.frames = 200;
  config.sway_deg = 0.0;
  for (const auto& [name, manoeuvre] : manoeuvre_names()) {
    SCOPED_TRACE(name);
    config.manoeuvre = manoeuvre;
    const Simulator sim(config);
    double turned = 0.0;
    for (std::size_t i = 1; i < sim.size(); ++i) {
      const Eigen::Isometry3d a = sim.pose(i - 1), b = sim.pose(i);
      const double step = (b.translation() - a.translation()).norm();
      const double yaw = turn(heading(b), heading(a));
      turned += yaw;
      switch (manoeuvre) {
        case Manoeuvre::Route: break;  // DrivesAboutAMetreAFrameWithTurns
        case Manoeuvre::Straight:
          ASSERT_NEAR(step, 1.0, 1e-9) << i;
          ASSERT_NEAR(heading(b), 0.0, 1e-12) << i;
          ASSERT_NEAR(b.translation().y(), -config.city.lane_offset, 1e-9) << i;
          break;
        case Manoeuvre::UTurn:
        case Manoeuvre::Roundabout:  // the chord of a 1 m arc
          ASSERT_GT(step, 0.95) << i;
          ASSERT_LE(step, 1.0 + 1e-9) << i;
          if (manoeuvre == Manoeuvre::Roundabout) {
            ASSERT_NEAR(b.translation().head<2>().norm(), config.roundabout_radius, 1e-9) << i;
            ASSERT_NEAR(yaw, 1.0 / config.roundabout_radius, 1e-9) << i;  // anticlockwise, v / r
          }
          break;
        case Manoeuvre::Spin:
          ASSERT_EQ(b.translation(), a.translation()) << i;
          ASSERT_NEAR(yaw, turn(config.spin_rate_deg * kDegree / config.rate_hz, 0.0), 1e-9) << i;
          break;
        case Manoeuvre::Still: ASSERT_EQ(b.matrix(), a.matrix()) << i; break;
      }
    }
    if (manoeuvre == Manoeuvre::UTurn) {  // 199 m round a 95.7 m stadium: two laps, two U-turns each
      EXPECT_NEAR(turned, 4.0 * std::numbers::pi, 1e-6);
    }
  }
  config.manoeuvre = Manoeuvre::Spin;
  config.spin_rate_deg = 20000.0;
  EXPECT_THROW(Simulator{config}, std::invalid_argument);
  config.manoeuvre = Manoeuvre::Roundabout;
  config.spin_rate_deg = 1000.0;
  config.roundabout_radius = 9.0;  // past the road's half width: off the intersection
  EXPECT_THROW(Simulator{config}, std::invalid_argument);
}

TEST(Simulator, LabelsMarkExactlyTheReturnsThatMove) {
  SimConfig config;
  config.frames = 40;
  const Simulator sim(config);
  std::size_t moving_returns = 0;
  for (std::size_t i = 0; i + 5 < sim.size(); i += 7) {
    const SimFrame a = sim.frame(i), b = sim.frame(i + 5);
    const auto static_a = select(a, false), static_b = select(b, false);
    const auto moving_a = select(a, true), moving_b = select(b, true);
    moving_returns += moving_b.size();
    // Placed in the world half a second apart, static returns coincide and moving ones do not.
    const double still = test::voxel_overlap(static_a, a.world_T_lidar, static_b, b.world_T_lidar);
    const double moved = test::voxel_overlap(moving_a, a.world_T_lidar, moving_b, b.world_T_lidar);
    EXPECT_GT(still, 0.5) << i;
    EXPECT_LT(moved, still / 3.0) << i;
  }
  EXPECT_GT(moving_returns, 500u);
}

TEST(Simulator, WritesKittiThatTheReaderReadsBack) {
  SimConfig config;
  config.frames = 6;
  const Simulator sim(config);
  test::TempDir dir;
  sim.write_kitti(dir.path());
  const io::KittiSequence sequence(dir.path());
  ASSERT_EQ(sequence.size(), 6u);
  EXPECT_TRUE(sequence.poses_were_camera_frame());
  ASSERT_TRUE(sequence.has_labels());
  for (std::size_t i = 0; i < 6; i += 5) {
    const SimFrame expected = sim.frame(i);
    const io::KittiFrame read = sequence.read(i);
    SimFrame got{i, expected.time, read.world_T_lidar, read.cloud, sequence.read_labels(i), {}};
    EXPECT_LT((got.world_T_lidar.matrix() - expected.world_T_lidar.matrix()).cwiseAbs().maxCoeff(), 1e-12);
    got.world_T_lidar = expected.world_T_lidar;
    expect_same_frame(expected, got);
    EXPECT_NEAR(sequence.times()[i], expected.time, 1e-15);
  }
  // Registered with the poses read back, scans 5 m apart overlap far better than unregistered.
  const io::KittiFrame a = sequence.read(0), b = sequence.read(5);
  const Eigen::Isometry3d id = Eigen::Isometry3d::Identity();
  const double above_road = -1.3;
  const double posed = test::voxel_overlap(a.cloud.points, a.world_T_lidar, b.cloud.points, b.world_T_lidar, above_road);
  const double identity = test::voxel_overlap(a.cloud.points, id, b.cloud.points, id, above_road);
  std::cout << "simulated scans 0 and 5, overlap above the road: with poses " << posed << ", identity " << identity << "\n";
  EXPECT_GT(posed, 1.5 * identity);
}

TEST(Simulator, RejectsBadConfigurationNamingTheField) {
  const auto rejects = [](auto change, const std::string& field) {
    SimConfig config;
    change(config);
    try {
      Simulator sim(config);
      ADD_FAILURE() << field << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  rejects([](SimConfig& c) { c.frames = 0; }, "frames");
  rejects([](SimConfig& c) { c.rate_hz = std::nan(""); }, "rate_hz");
  rejects([](SimConfig& c) { c.lidar.fov_down_deg = 5.0; }, "lidar.fov_down_deg");
  rejects([](SimConfig& c) { c.lidar.max_range = 1.0; }, "lidar.max_range");
  rejects([](SimConfig& c) { c.lidar.dropout = 1.0; }, "lidar.dropout");
  rejects([](SimConfig& c) { c.lidar.columns = 0; }, "lidar.columns");
  rejects([](SimConfig& c) { c.city.lane_offset = 9.0; }, "city.lane_offset");
  rejects([](SimConfig& c) { c.city.block_pitch = 20.0; }, "city.block_pitch");
  const Simulator sim(SimConfig{});
  EXPECT_THROW((void)sim.frame(sim.size()), std::out_of_range);
}

}  // namespace
}  // namespace eco::sim
