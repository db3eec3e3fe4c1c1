#pragma once
// Drives and comparisons shared by the tests of whole maps (save and load, snapshots): a small
// simulated drive with moving cars, a configuration that keeps everything, per-point attributes,
// and the check that two maps answer every query alike.

#include <eco/ego_octree.hpp>
#include <eco/sim/simulator.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace eco::test {

inline sim::SimConfig small_drive(std::size_t frames) {
  sim::SimConfig s;
  s.seed = 8;
  s.frames = frames;
  s.lidar.beams = 16;
  s.lidar.columns = 360;
  s.city.cars_per_intersection = 8.0;
  return s;
}

/// Gives `scan` ids numbered per frame, intensities, and times 7.3 s apart a frame (the time
/// origin moves every ~9 frames), kept in the three vectors.
inline void add_attributes(ScanView& scan, std::size_t t, std::vector<std::uint32_t>& ids, std::vector<float>& intensities,
                    std::vector<double>& times) {
  const std::size_t n = scan.count;
  ids.resize(n);
  intensities.resize(n);
  times.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    ids[i] = std::uint32_t(t * 100000 + i);
    intensities[i] = float(i % 97);
    times[i] = 1.7e9 + 7.3 * double(t) + 1e-5 * double(i);
  }
  scan.ids = ids.data();
  scan.intensities = intensities.data();
  scan.times = times.data();
}

inline void expect_same_neighbors(const std::vector<Neighbor>& a, const std::vector<Neighbor>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].point, b[i].point) << what << ", neighbour " << i;
    EXPECT_EQ(a[i].sq_dist, b[i].sq_dist) << what << ", neighbour " << i;
    EXPECT_EQ(a[i].attributes, b[i].attributes) << what << ", neighbour " << i;
  }
}

/// Every answer of `loaded` equals `saved`'s, in the same order: the held points, KNN, radius
/// and box queries, voxel maps, the frame, pose and origins (a loaded map's against the saved
/// one's, a snapshot's against its frame's).
inline void expect_identical(const MapReader& saved, const MapReader& loaded, std::mt19937& rng, const std::string& when) {
  SCOPED_TRACE(when);
  ASSERT_EQ(loaded.check_invariants(), "");
  ASSERT_EQ(loaded.size(), saved.size());
  EXPECT_EQ(loaded.frame_count(), saved.frame_count());
  EXPECT_TRUE(loaded.pose().isApprox(saved.pose(), 0.0));
  EXPECT_EQ(loaded.precision_origin(), saved.precision_origin());
  EXPECT_EQ(loaded.time_origin(), saved.time_origin());
  EXPECT_EQ(loaded.stats().points, saved.stats().points);
  EXPECT_EQ(loaded.stats().nodes, saved.stats().nodes);
  const std::vector<HeldPoint> a = saved.points_with_attributes(), b = loaded.points_with_attributes();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].point, b[i].point) << "held point " << i;
    ASSERT_EQ(a[i].attributes, b[i].attributes) << "held point " << i;
  }
  if (a.empty()) return;
  std::uniform_int_distribution<std::size_t> pick(0, a.size() - 1);
  std::normal_distribution<double> jitter(0.0, 0.3);
  for (int q = 0; q < 20; ++q) {
    const Eigen::Vector3d p = a[pick(rng)].point + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    for (const std::size_t k : {1, 5, 40}) {
      expect_same_neighbors(saved.knn(p, k), loaded.knn(p, k), "knn, k = " + std::to_string(k));
    }
    expect_same_neighbors(saved.radius(p, 1.5), loaded.radius(p, 1.5), "radius");
    const Eigen::Vector3d lo = p - Eigen::Vector3d(2, 2, 1), hi = p + Eigen::Vector3d(2, 2, 1);
    EXPECT_EQ(saved.box(lo, hi), loaded.box(lo, hi)) << "box";
  }
  for (const double res : {0.1, 0.35}) EXPECT_EQ(saved.voxel_keys(res), loaded.voxel_keys(res)) << "voxels " << res;
}

/// Feeds `tree` frame `t` of a drive with attributes (add_attributes) whether it keeps them or not.
inline const UpdateStats& update_with_attributes(EgoOctree& tree, const sim::SimFrame& frame, std::size_t t) {
  ScanView scan(frame.cloud.points);
  std::vector<std::uint32_t> ids;
  std::vector<float> intensities;
  std::vector<double> times;
  add_attributes(scan, t, ids, intensities, times);
  return tree.update(frame.world_T_lidar, scan);
}

/// Turns on in `cfg` all a map can keep beside its points: free-space clearing with `drive`'s
/// sensor, a density cap, ids, intensities, times and an age limit in seconds.
inline void with_everything(Config& cfg, const sim::Simulator& drive) {
  cfg.clearing.enabled = true;
  cfg.sensor.vertical_fov_min = drive.config().lidar.fov_down_deg - 0.5;
  cfg.sensor.vertical_fov_max = drive.config().lidar.fov_up_deg + 0.5;
  cfg.sensor.vertical_resolution =
      (drive.config().lidar.fov_up_deg - drive.config().lidar.fov_down_deg) / (drive.config().lidar.beams - 1);
  cfg.sensor.horizontal_resolution = 2.0;
  cfg.sensor.max_range = 60.0;
  cfg.density_cap = {0.3, 2};
  cfg.attributes = {true, true, true};
  cfg.max_age_seconds = 20.0;
}

}  // namespace eco::test
