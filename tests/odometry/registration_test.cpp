// The odometry recovers exactly known motions on synthetic scenes — a room of planes, a corner
// of three, a corridor with an end wall and pillars — to 1 mm and 0.01°, on every exact map; and
// refuses bad input by name, skipping and counting bad points and empty scans.

#include <eco/odometry/odometry.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace eco::odometry {
namespace {

/// A scene: surfaces sampled uniformly, `n` points at a time, in the world frame.
using Scene = std::function<std::vector<Eigen::Vector3d>(std::mt19937&, std::size_t n)>;

/// Points on the axis-aligned rectangle at `fixed` on axis `axis`, spanning [lo, hi] on the others.
Eigen::Vector3d on_rectangle(std::mt19937& rng, int axis, double fixed, const Eigen::Vector3d& lo,
                             const Eigen::Vector3d& hi) {
  Eigen::Vector3d p;
  for (int a = 0; a < 3; ++a) p[a] = std::uniform_real_distribution<double>(lo[a], hi[a])(rng);
  p[axis] = fixed;
  return p;
}

struct Rectangle {
  int axis;
  double fixed;
  Eigen::Vector3d lo, hi;
};

Scene scene_of(std::vector<Rectangle> faces) {
  return [faces](std::mt19937& rng, std::size_t n) {
    std::vector<Eigen::Vector3d> points;
    std::uniform_int_distribution<std::size_t> pick(0, faces.size() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const Rectangle& f = faces[pick(rng)];
      points.push_back(on_rectangle(rng, f.axis, f.fixed, f.lo, f.hi));
    }
    return points;
  };
}

/// A closed room, 12 x 9 x 4 m.
Scene room() {
  const Eigen::Vector3d lo(-6, -4, -1.5), hi(6, 5, 2.5);
  return scene_of({{0, lo.x(), lo, hi}, {0, hi.x(), lo, hi}, {1, lo.y(), lo, hi}, {1, hi.y(), lo, hi},
                   {2, lo.z(), lo, hi}, {2, hi.z(), lo, hi}});
}

/// Three planes meeting at a corner: the floor and two walls.
Scene corner() {
  const Eigen::Vector3d lo(-3, -3, -1.5), hi(8, 8, 4);
  return scene_of({{0, lo.x(), lo, hi}, {1, lo.y(), lo, hi}, {2, lo.z(), lo, hi}});
}

/// A corridor 2.4 m wide along x, closed at its far end, with two square pillars along one wall.
Scene corridor() {
  const Eigen::Vector3d lo(-4, -1.2, -1.2), hi(14, 1.2, 1.5);
  std::vector<Rectangle> faces{{1, lo.y(), lo, hi}, {1, hi.y(), lo, hi}, {2, lo.z(), lo, hi},
                               {2, hi.z(), lo, hi}, {0, hi.x(), lo, hi}};
  for (double x : {3.0, 8.0}) {  // pillars 0.4 m square against the wall at y = -1.2
    const Eigen::Vector3d plo(x, -1.2, -1.2), phi(x + 0.4, -0.8, 1.5);
    faces.push_back({0, plo.x(), plo, phi});
    faces.push_back({0, phi.x(), plo, phi});
    faces.push_back({1, phi.y(), plo, phi});
  }
  return scene_of(faces);
}

/// The scene as a sensor at `pose` sees it: fresh samples, in the sensor frame.
std::vector<Eigen::Vector3f> scan_of(const Scene& scene, const Eigen::Isometry3d& pose, std::mt19937& rng) {
  std::vector<Eigen::Vector3f> scan;
  for (const Eigen::Vector3d& p : scene(rng, 60000)) scan.push_back((pose.inverse() * p).cast<float>());
  return scan;
}

OdometryConfig indoor() {
  OdometryConfig c;
  c.max_range = 30.0;
  c.min_range = 0.2;
  c.voxel_size = 0.2;
  c.plane_reach = 3.0;  // planes from k points within 0.6 m: past the 0.4 m first step
  c.box_side = 60.0;
  c.plane_tolerance = 0.01;  // exact planes: five points across an edge are no plane
  return c;
}

Eigen::Isometry3d pose_of(const Eigen::Vector3d& t, double degrees, const Eigen::Vector3d& axis) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis.normalized()).toRotationMatrix();
  pose.translation() = t;
  return pose;
}

void expect_near(const Eigen::Isometry3d& got, const Eigen::Isometry3d& want, const std::string& what) {
  const Eigen::Isometry3d error = want.inverse() * got;
  EXPECT_LT(error.translation().norm(), 1e-3) << what;
  EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle() * 180.0 / std::numbers::pi, 0.01) << what;
}

struct SceneCase {
  const char* name;
  Scene scene;
};

class KnownMotion : public ::testing::TestWithParam<std::string> {};

TEST_P(KnownMotion, EveryFrameOfAThreeFrameMoveIsRecoveredOnEveryScene) {
  const std::vector<SceneCase> scenes{{"room", room()}, {"corner", corner()}, {"corridor", corridor()}};
  // two steps: the first from a standing start (no velocity to predict with), the second predicted
  const Eigen::Isometry3d step = pose_of({0.35, -0.15, 0.05}, 2.5, {0.2, 0.3, 1.0});
  const Eigen::Isometry3d start = pose_of({0.2, 0.1, 0.0}, 10.0, {0, 0, 1});
  for (const SceneCase& s : scenes) {
    SCOPED_TRACE(std::string(s.name) + " on " + GetParam());
    std::mt19937 rng(3);
    const OdometryConfig config = indoor();
    Odometry odo(config, make_local_map(GetParam(), config.map_settings()));
    odo.set_start(start);
    Eigen::Isometry3d truth = start;
    for (int frame = 0; frame < 3; ++frame) {
      const FrameReport report = odo.register_frame(ScanView(scan_of(s.scene, truth, rng)));
      EXPECT_EQ(report.registered, frame > 0);
      expect_near(report.pose, truth, "frame " + std::to_string(frame));
      truth = truth * step;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Maps, KnownMotion, ::testing::Values("eco", "voxel_hash"));

TEST(Odometry, PointsThatAreNotFiniteOrOutOfRangeAreSkippedAndCounted) {
  const OdometryConfig config = indoor();
  Odometry odo(config, make_local_map("eco", config.map_settings()));
  std::mt19937 rng(4);
  std::vector<Eigen::Vector3f> scan = scan_of(room(), Eigen::Isometry3d::Identity(), rng);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  scan.push_back({nan, 0, 0});
  scan.push_back({0, std::numeric_limits<float>::infinity(), 1});
  scan.push_back({0.05f, 0.0f, 0.0f});  // under min_range
  scan.push_back({40.0f, 0.0f, 0.0f});  // past max_range
  const FrameReport first = odo.register_frame(ScanView(scan));
  EXPECT_EQ(first.dropped_invalid, 2u);
  EXPECT_EQ(first.dropped_range, 2u);
  const FrameReport second = odo.register_frame(ScanView(scan));
  EXPECT_TRUE(second.registered);
  expect_near(second.pose, Eigen::Isometry3d::Identity(), "the same scan again");
}

TEST(Odometry, AnEmptyScanIsPredictedNotRegisteredAndTheRunGoesOn) {
  const OdometryConfig config = indoor();
  Odometry odo(config, make_local_map("eco", config.map_settings()));
  std::mt19937 rng(5);
  const Eigen::Isometry3d step = pose_of({0.2, 0, 0}, 0.0, {0, 0, 1});
  (void)odo.register_frame(ScanView(scan_of(room(), Eigen::Isometry3d::Identity(), rng)));
  (void)odo.register_frame(ScanView(scan_of(room(), step, rng)));
  const FrameReport empty = odo.register_frame(ScanView());
  EXPECT_FALSE(empty.registered);
  EXPECT_EQ(empty.source, 0u);
  expect_near(empty.pose, step * step, "constant velocity");
  const std::vector<Eigen::Vector3f> all_nan(100, Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  const FrameReport nans = odo.register_frame(ScanView(all_nan));
  EXPECT_FALSE(nans.registered);
  EXPECT_EQ(nans.dropped_invalid, 100u);
  EXPECT_EQ(odo.poses().size(), 4u);
}

TEST(Odometry, BadSettingsAreRefusedByName) {
  const auto refused = [](const std::function<void(OdometryConfig&)>& change, const std::string& field) {
    OdometryConfig c;
    change(c);
    try {
      Odometry odo(c, make_local_map("eco", MapSettings{}));
      ADD_FAILURE() << field << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  refused([](OdometryConfig& c) { c.max_range = -1; }, "max_range");
  refused([](OdometryConfig& c) { c.min_range = 200; }, "min_range");
  refused([](OdometryConfig& c) { c.voxel_size = std::nan(""); }, "voxel_size");
  refused([](OdometryConfig& c) { c.neighbours = 2; }, "neighbours");
  refused([](OdometryConfig& c) { c.max_iterations = 0; }, "max_iterations");
  refused([](OdometryConfig& c) { c.max_points_per_voxel = 0; }, "max_points");
  refused([](OdometryConfig& c) { c.threads = 0; }, "threads");
  EXPECT_THROW(Odometry(OdometryConfig{}, nullptr), std::invalid_argument);
  EXPECT_THROW((void)make_local_map("kdtree", MapSettings{}), std::invalid_argument);

  const OdometryConfig config = indoor();
  Odometry odo(config, make_local_map("eco", config.map_settings()));
  (void)odo.register_frame(ScanView());
  EXPECT_THROW(odo.set_start(Eigen::Isometry3d::Identity()), std::invalid_argument);  // only before the first frame
}

}  // namespace
}  // namespace eco::odometry
