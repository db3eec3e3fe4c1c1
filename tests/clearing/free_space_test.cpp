// Free-space clearing (Config::clearing): against a brute-force copy of the rule after every frame
// of a simulated drive with moving cars (both re-centring modes, with and without a density cap,
// arrivals and an age limit, across precision-origin moves), and on scripted scenes: a car crossing
// in front of a wall, a car coming toward the sensor.

#include "support/compare.hpp"
#include "support/streams.hpp"

#include <eco/io/kitti.hpp>
#include <eco/sim/simulator.hpp>

#include <tuple>

namespace eco::test {
namespace {

/// The simulator's sensor, coarsened so that the brute force stays quick.
sim::SimConfig small_drive(std::size_t frames, std::uint64_t seed) {
  sim::SimConfig s;
  s.seed = seed;
  s.frames = frames;
  s.lidar.beams = 16;
  s.lidar.columns = 360;
  s.city.cars_per_intersection = 8.0;  // cars in view most frames
  return s;
}

/// The same sensor as clearing's model: 16 beams over [-24.9, 2] degrees, 1 degree columns.
SensorModel model_of(const sim::LidarModel& lidar) {
  SensorModel m;
  m.vertical_fov_min = lidar.fov_down_deg - 0.5;
  m.vertical_fov_max = lidar.fov_up_deg + 0.5;
  m.vertical_resolution = (lidar.fov_up_deg - lidar.fov_down_deg) / (lidar.beams - 1);
  m.horizontal_resolution = 2.0 * 360.0 / lidar.columns;
  m.max_range = 60.0;
  return m;
}

using Params = std::tuple<Recentring, bool, bool, bool>;  // re-centring, capped, arrivals, age limit

class ClearingOracle : public ::testing::TestWithParam<Params> {};

TEST_P(ClearingOracle, HeldSetMatchesTheRuleRayByRayEveryFrame) {
  const auto [recentring, capped, arrivals, aged] = GetParam();
  const sim::Simulator drive(small_drive(30, 4));
  Config cfg;
  cfg.recentring = recentring;
  cfg.box_side = 40.0;
  cfg.clearing.enabled = true;
  cfg.clearing.margin = 0.3;
  cfg.clearing.arrivals = arrivals;
  cfg.sensor = model_of(drive.config().lidar);
  if (capped) cfg.density_cap = {0.5, 2};
  if (aged) cfg.max_age_frames = 4;  // points age out while arrivals wait to leave (stamps kept)
  EgoOctree tree(cfg);
  Oracle oracle(cfg);
  Config rays_only = cfg;
  rays_only.clearing.arrivals = false;
  EgoOctree without_arrivals(rays_only);
  std::size_t cleared_without = 0;
  std::mt19937 rng(3);
  std::size_t cleared = 0, aged_out = 0;
  const double x10 = drive.pose(10).translation().x();
  bool rebased = false;
  for (std::size_t t = 0; t < drive.size(); ++t) {
    sim::SimFrame frame = drive.frame(t);
    // From frame 10 on, the drive is carried 2 km out and drifts 3 m a frame: the precision origin
    // moves (at 2048 m) while the box still holds points, which are handed on re-expressed.
    if (t >= 10) frame.world_T_lidar.translation().x() += 2040.0 - x10 + 3.0 * double(t - 10);
    const UpdateStats& u = tree.update(frame.world_T_lidar, frame.cloud.points);
    oracle.update(frame.world_T_lidar, frame.cloud.points, tree.precision_origin());
    cleared += u.cleared;
    aged_out += u.aged_out;
    cleared_without += without_arrivals.update(frame.world_T_lidar, frame.cloud.points).cleared;
    rebased = rebased || (u.rebased && t > 10);
    expect_same_answers(tree, oracle, rng, "frame " + std::to_string(t));
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(cleared, 100u) << "clearing never bit";
  if (arrivals) {
    EXPECT_GT(cleared, cleared_without + 100) << "no arrival was cleared";
  }
  EXPECT_EQ(aged_out > 0, aged) << "points aged out only under the age limit";
  EXPECT_TRUE(rebased) << "the precision origin never moved under held points";
}

INSTANTIATE_TEST_SUITE_P(Modes, ClearingOracle,
                         ::testing::Combine(::testing::Values(Recentring::Quantised, Recentring::Exact),
                                            ::testing::Bool(), ::testing::Bool(), ::testing::Bool()),
                         [](const ::testing::TestParamInfo<Params>& p) {
                           return name(std::get<0>(p.param)) + (std::get<1>(p.param) ? "_Capped" : "") +
                                  (std::get<2>(p.param) ? "_Arrivals" : "") + (std::get<3>(p.param) ? "_Aged" : "");
                         });

/// Arrivals leave one update after they came, found by every column: with ids, intensities and
/// times kept, repeated points (equal coordinates, their own ids), the precision origin moving
/// and the time origin moving (7.3 s a frame) while arrivals wait to leave.
TEST(Clearing, ArrivalsLeaveWithTheirAttributesAcrossOriginMoves) {
  const sim::Simulator drive(small_drive(24, 5));
  Config cfg;
  cfg.box_side = 40.0;
  cfg.clearing.enabled = true;
  cfg.clearing.margin = 0.3;
  cfg.clearing.arrivals = true;
  cfg.sensor = model_of(drive.config().lidar);
  cfg.attributes = {true, true, true};
  Config rays_only = cfg;
  rays_only.clearing.arrivals = false;
  EgoOctree tree(cfg), without_arrivals(rays_only);
  Oracle oracle(cfg);
  std::size_t cleared = 0, cleared_without = 0;
  int rebases = 0, clock_moves = 0;
  double time_origin = tree.time_origin();
  const double x10 = drive.pose(10).translation().x();
  for (std::size_t t = 0; t < drive.size(); ++t) {
    SCOPED_TRACE("frame " + std::to_string(t));
    sim::SimFrame frame = drive.frame(t);
    if (t >= 10) frame.world_T_lidar.translation().x() += 2040.0 - x10 + 3.0 * double(t - 10);
    std::vector<Eigen::Vector3f> points = frame.cloud.points;
    ScanAttributes attributes;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (i % 13 == 7) points[i] = points[i - 1];  // a repeated point with an id of its own
      attributes.ids.push_back(std::uint32_t(t * 1000000 + i));
      attributes.intensities.push_back(float(i % 97) / 7.0f);
      attributes.times.push_back(1.7e9 + 7.3 * double(t) + 1e-5 * double(i));
    }
    ScanView scan(points);
    scan.ids = attributes.ids.data();
    scan.intensities = attributes.intensities.data();
    scan.times = attributes.times.data();
    const UpdateStats& u = tree.update(frame.world_T_lidar, scan);
    oracle.update(frame.world_T_lidar, points, tree.precision_origin(), attributes, tree.time_origin());
    cleared += u.cleared;
    cleared_without += without_arrivals.update(frame.world_T_lidar, scan).cleared;
    rebases += u.rebased ? 1 : 0;
    clock_moves += t > 0 && tree.time_origin() != time_origin ? 1 : 0;
    time_origin = tree.time_origin();
    ASSERT_EQ(tree.check_invariants(), "");
    expect_same_held_attributes(tree, oracle);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(cleared, cleared_without + 100) << "no arrival was cleared";
  EXPECT_GE(rebases, 1) << "the precision origin never moved";
  EXPECT_GE(clock_moves, 1) << "the time origin never moved";
}

TEST(Clearing, OffChangesNothing) {
  const sim::Simulator drive(small_drive(12, 6));
  Config on;
  on.clearing.enabled = true;
  on.sensor = model_of(drive.config().lidar);
  Config off = on;
  off.clearing.enabled = false;
  EgoOctree with(on), without(off), plain{Config{}};
  std::size_t cleared = 0;
  for (std::size_t t = 0; t < drive.size(); ++t) {
    const sim::SimFrame frame = drive.frame(t);
    cleared += with.update(frame.world_T_lidar, frame.cloud.points).cleared;
    EXPECT_EQ(without.update(frame.world_T_lidar, frame.cloud.points).cleared, 0u);
    plain.update(frame.world_T_lidar, frame.cloud.points);
  }
  EXPECT_EQ(sorted(without.points()), sorted(plain.points()));
  EXPECT_GT(cleared, 0u);
  EXPECT_LT(with.size(), without.size());
}

// --- the scripted scene ------------------------------------------------------------------------

/// A flat world seen by a sensor 1.73 m above the ground at the origin: the ground (z = 0), a wall
/// (x = 15 m, |y| <= 20 m, up to 4 m high) and a car 2 m deep and 4 m long, 0.3 m to 1.5 m above
/// the ground, centred at (car_x, car_y).
struct Scene {
  static constexpr double kHeight = 1.73;
  static constexpr double kWallX = 15.0;
  static constexpr double kWallHalfWidth = 20.0;  // past the scan's 45 degrees: every ray above the ground returns

  SensorModel sensor;

  /// One return per pixel centre within 45 degrees of +x (sensor frame = world axes, shifted up).
  [[nodiscard]] std::vector<Eigen::Vector3f> scan(double car_y, bool with_car, double car_x = 8.5) const {
    std::vector<Eigen::Vector3f> out;
    const int rows = sensor.rows();
    const int columns = sensor.columns();
    for (int r = 0; r < rows; ++r) {
      const double elevation = (sensor.vertical_fov_min + (r + 0.5) * sensor.vertical_resolution) * M_PI / 180.0;
      for (int c = 0; c < columns; ++c) {
        const double azimuth = (-180.0 + (c + 0.5) * sensor.horizontal_resolution) * M_PI / 180.0;
        if (std::abs(azimuth) > M_PI / 4) continue;
        const Eigen::Vector3d d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                std::sin(elevation));
        double best = std::numeric_limits<double>::infinity();
        if (d.z() < 0) best = kHeight / -d.z();  // the ground
        const double to_wall = kWallX / d.x();    // the wall
        const Eigen::Vector3d w = to_wall * d;
        const bool on_wall = std::abs(w.y()) <= kWallHalfWidth && w.z() + kHeight <= 4.0 && w.z() + kHeight >= 0.0;
        if (on_wall) best = std::min(best, to_wall);
        if (with_car) best = std::min(best, hit_car(d, car_x, car_y));
        if (best < 50.0) out.push_back((best * d).cast<float>());
      }
    }
    return out;
  }

  /// The distance along unit direction d to the car's box (slab test), infinity on a miss.
  static double hit_car(const Eigen::Vector3d& d, double car_x, double car_y) {
    const Eigen::Vector3d lo(car_x - 1.0, car_y - 2.0, 0.3 - kHeight), hi(car_x + 1.0, car_y + 2.0, 1.5 - kHeight);
    double near = 0.0, far = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0.0) {
        if (0.0 < lo[a] || 0.0 > hi[a]) return std::numeric_limits<double>::infinity();
        continue;
      }
      double t0 = lo[a] / d[a], t1 = hi[a] / d[a];
      if (t0 > t1) std::swap(t0, t1);
      near = std::max(near, t0);
      far = std::min(far, t1);
    }
    return near <= far ? near : std::numeric_limits<double>::infinity();
  }
};

/// The scene in coarse pixels, a config that clears free space for its sensor in a 40 m box, and
/// where the sensor stands.
struct Staged {
  Scene scene;
  Config cfg;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};
Staged staged() {
  Staged s;
  s.scene.sensor.vertical_resolution = 1.0;
  s.scene.sensor.horizontal_resolution = 0.5;
  s.cfg.box_side = 40.0;
  s.cfg.sensor = s.scene.sensor;
  s.cfg.clearing.enabled = true;
  s.pose.translation().z() = Scene::kHeight;
  return s;
}

TEST(Clearing, ACarCrossingInFrontOfAWallLeavesNoTrailAndTheWallStays) {
  const auto [scene, cfg, pose] = staged();
  Config keeping = cfg;
  keeping.clearing.enabled = false;
  EgoOctree clearing(cfg), trails(keeping);
  for (int t = 0; t <= 20; ++t) {
    const std::vector<Eigen::Vector3f> scan = scene.scan(-10.0 + t, /*with_car=*/true);
    clearing.update(pose, scan);
    trails.update(pose, scan);
  }
  // the car has left the field of view; the wall is seen whole again
  const std::vector<Eigen::Vector3f> last = scene.scan(0.0, /*with_car=*/false);
  clearing.update(pose, last);
  trails.update(pose, last);
  auto on_car_path = [](const Eigen::Vector3d& p) { return p.x() > 7.4 && p.x() < 9.6 && p.z() > 0.25; };
  auto static_points = [&](const EgoOctree& tree) {
    std::vector<Eigen::Vector3d> out;
    for (const Eigen::Vector3d& p : tree.points()) {
      if (!on_car_path(p)) out.push_back(p);
    }
    return sorted(out);
  };
  std::size_t trail = 0;
  for (const Eigen::Vector3d& p : trails.points()) trail += on_car_path(p) ? 1 : 0;
  ASSERT_GT(trail, 500u) << "the car left no trail to clear";
  for (const Eigen::Vector3d& p : clearing.points()) EXPECT_FALSE(on_car_path(p)) << p.transpose();
  const std::vector<Eigen::Vector3d> kept = static_points(clearing);
  EXPECT_EQ(kept, static_points(trails));  // every wall and ground point stays
  std::size_t wall = 0;
  for (const Eigen::Vector3d& p : kept) wall += std::abs(p.x() - Scene::kWallX) < 1e-3 ? 1 : 0;
  EXPECT_GT(wall, 1000u);
}

TEST(Clearing, ACarComingTowardTheSensorLeavesNoTrailBehindItWithArrivals) {
  auto [scene, cfg, pose] = staged();
  cfg.clearing.arrivals = true;
  Config rays_only = cfg;
  rays_only.clearing.arrivals = false;
  EgoOctree arrivals(cfg), hidden(rays_only);
  const auto on_car_path = [](const Eigen::Vector3d& p) {
    return p.x() > 2.9 && p.x() < 13.1 && std::abs(p.y()) < 2.1 && p.z() > 0.25;
  };
  for (int t = 0; t <= 8; ++t) {  // the car comes from x = 12 m to x = 4 m, a metre a frame
    const double car_x = 12.0 - t;
    const std::vector<Eigen::Vector3f> scan = scene.scan(0.0, /*with_car=*/true, car_x);
    arrivals.update(pose, scan);
    hidden.update(pose, scan);
    // the car's earlier fronts behind it (below its roof, where its own front hides them), but the
    // first scan's (x = 11 m): no update judged that one's arrivals, there was no scan before it
    const auto trail = [&](const EgoOctree& tree) {
      std::size_t n = 0;
      for (const Eigen::Vector3d& p : tree.points()) {
        n += on_car_path(p) && p.z() < 1.3 && p.x() > car_x + 1.01 && p.x() < 10.99 ? 1 : 0;
      }
      return n;
    };
    EXPECT_EQ(trail(arrivals), 0u) << "frame " << t;
    if (t == 8) {
      EXPECT_GT(trail(hidden), 100u) << "the car hid no trail of its own";
    }
  }
  const auto static_points = [&](const EgoOctree& tree) {
    std::vector<Eigen::Vector3d> out;
    for (const Eigen::Vector3d& p : tree.points()) {
      if (!on_car_path(p)) out.push_back(p);
    }
    return sorted(out);
  };
  EXPECT_EQ(static_points(arrivals), static_points(hidden));  // the wall and the ground stay
}

TEST(Clearing, PointsBehindSurfacesOutsideTheViewOrBeyondRangeStay) {
  Config cfg;
  cfg.box_side = 60.0;
  cfg.clearing.enabled = true;
  cfg.sensor.vertical_fov_min = -10.0;
  cfg.sensor.vertical_fov_max = 10.0;
  cfg.sensor.vertical_resolution = 1.0;
  cfg.sensor.horizontal_resolution = 1.0;
  cfg.sensor.max_range = 20.0;
  EgoOctree tree(cfg);
  const std::vector<Eigen::Vector3f> first{
      {5.0f, 0.0f, 0.0f},    // in front: the next scan sees through it
      {25.0f, 0.0f, 0.0f},   // behind the next scan's return, and beyond max_range
      {12.0f, 0.1f, 0.0f},   // behind the next scan's return
      {5.0f, 0.0f, 3.0f},    // above the field of view (31 degrees)
      {0.0f, 5.0f, 0.0f}};   // a column where nothing comes back
  tree.update(Eigen::Isometry3d::Identity(), first);
  // a lone return 10 m ahead: the rows above and below got none, so it is no evidence
  EgoOctree lone(cfg);
  lone.update(Eigen::Isometry3d::Identity(), first);
  EXPECT_EQ(lone.update(Eigen::Isometry3d::Identity(), std::vector<Eigen::Vector3f>{{10.0f, 0.0f, 0.0f}}).cleared, 0u);
  // returns 10 m ahead in the rows below, at and above the horizon (elevations -0.5, 0.5, 1.5 degrees)
  std::vector<Eigen::Vector3f> second;
  for (const double elevation : {-0.5, 0.5, 1.5}) {
    const double e = elevation * 3.14159265358979323846 / 180.0;
    second.push_back(Eigen::Vector3f(float(10.0 * std::cos(e)), 0.0f, float(10.0 * std::sin(e))));
  }
  const UpdateStats& u = tree.update(Eigen::Isometry3d::Identity(), second);
  EXPECT_EQ(u.cleared, 1u);
  std::vector<Eigen::Vector3d> expected{{25, 0, 0}, {12, 0.1, 0}, {5, 0, 3}, {0, 5, 0}};
  for (Eigen::Vector3d& p : expected) p = p.cast<float>().cast<double>();
  for (const Eigen::Vector3f& p : second) expected.push_back(p.cast<double>());
  EXPECT_EQ(sorted(tree.points()), sorted(expected));
  EXPECT_EQ(tree.check_invariants(), "");
  // a return just within the margin clears nothing
  cfg.clearing.margin = 5.5;
  EgoOctree wide(cfg);
  wide.update(Eigen::Isometry3d::Identity(), first);
  EXPECT_EQ(wide.update(Eigen::Isometry3d::Identity(), second).cleared, 0u);
}

TEST(Clearing, ABadSensorModelIsRefusedByName) {
  auto refused = [](const Config& c, const std::string& field) {
    try {
      EgoOctree tree(c);
      ADD_FAILURE() << field << ": taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  Config c;
  c.sensor.vertical_resolution = 0.0;
  refused(c, "sensor.vertical_resolution");
  c = Config{};
  c.sensor.horizontal_resolution = -0.2;
  refused(c, "sensor.horizontal_resolution");
  c = Config{};
  c.sensor.vertical_fov_max = c.sensor.vertical_fov_min;
  refused(c, "sensor.vertical_fov_max");
  c = Config{};
  c.sensor.horizontal_resolution = 1e-4;  // 3.6 million columns
  refused(c, "sensor.horizontal_resolution");
  c = Config{};
  c.sensor.max_range = std::numeric_limits<double>::quiet_NaN();
  refused(c, "sensor.max_range");
  c = Config{};
  c.clearing.margin = 0.0;
  refused(c, "clearing.margin");
}

}  // namespace
}  // namespace eco::test
