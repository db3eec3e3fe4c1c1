// Every map the odometry can run on answers its queries as brute force over the points it holds
// (the voxel-hash map: as brute force over the 27 voxels around the query, its documented
// approximation, and exactly wherever the nearest point lies within a voxel's side); the exact
// maps hold the same points as ECO, eco_ball points within its ball only.

#include "odometry/baseline_maps.hpp"
#include <eco/sim/simulator.hpp>

#include "odometry/voxel_downsample.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace eco::odometry {
namespace {

MapSettings small_settings() {
  MapSettings s;
  s.box_side = 40.0;
  s.cell_size = 0.5;
  s.max_points = 6;
  s.ball_radius = 12.0;
  return s;
}

std::vector<Eigen::Vector3d> sorted(std::vector<Eigen::Vector3d> points) {
  std::ranges::sort(points, [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return points;
}

/// Queries near held points (the registration's case) and anywhere in the box.
std::vector<Eigen::Vector3d> queries_near(const std::vector<Eigen::Vector3d>& held, const Eigen::Vector3d& centre) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::size_t> pick(0, held.size() - 1);
  std::normal_distribution<double> jitter(0.0, 0.3);
  std::uniform_real_distribution<double> anywhere(-20.0, 20.0);
  std::vector<Eigen::Vector3d> q;
  for (int i = 0; i < 300; ++i) q.push_back(held[pick(rng)] + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng)));
  for (int i = 0; i < 60; ++i) q.push_back(centre + Eigen::Vector3d(anywhere(rng), anywhere(rng), anywhere(rng) / 4));
  return q;
}

/// The k nearest of `candidates` to `q` by brute force: their squared distances, ascending.
std::vector<double> brute_force(const std::vector<Eigen::Vector3d>& candidates, const Eigen::Vector3d& q, std::size_t k) {
  std::vector<double> d;
  d.reserve(candidates.size());
  for (const Eigen::Vector3d& p : candidates) d.push_back((p - q).squaredNorm());
  const std::size_t n = std::min(k, d.size());
  std::partial_sort(d.begin(), d.begin() + std::ptrdiff_t(n), d.end());
  d.resize(n);
  return d;
}

void expect_distances(std::span<const Neighbor> got, const std::vector<double>& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t j = 0; j < want.size(); ++j) {
    EXPECT_NEAR(got[j].sq_dist, want[j], 1e-9 * (1.0 + want[j])) << what << ", neighbour " << j;
  }
}

TEST(LocalMaps, EveryMapAnswersAsBruteForceOverWhatItHoldsAlongADrive) {
  sim::SimConfig drive;
  drive.frames = 12;
  drive.lidar.columns = 500;
  drive.lidar.beams = 32;
  const sim::Simulator sim(drive);
  const std::size_t k = 5;
  std::vector<std::unique_ptr<LocalMap>> maps;
  for (const std::string& name : all_local_map_names()) maps.push_back(make_any_local_map(name, small_settings()));
  for (std::size_t t = 0; t < sim.size(); ++t) {
    const sim::SimFrame frame = sim.frame(t);
    for (auto& map : maps) map->update(frame.world_T_lidar, frame.cloud.view());
    if (t % 4 != 3) continue;
    const std::vector<Eigen::Vector3d> eco_points = sorted(maps.front()->points());
    ASSERT_GT(eco_points.size(), 1000u);
    const std::vector<Eigen::Vector3d> queries = queries_near(eco_points, frame.world_T_lidar.translation());
    for (auto& map : maps) {
      SCOPED_TRACE(map->name() + ", frame " + std::to_string(t));
      const std::vector<Eigen::Vector3d> held = map->points();
      EXPECT_EQ(map->size(), held.size());
      if (map->name() == "eco_ball") {  // within its ball; which points a cell keeps is its own history's
        const Eigen::Vector3d sensor = frame.world_T_lidar.translation();
        for (const Eigen::Vector3d& p : held) ASSERT_LE((p - sensor).norm(), small_settings().ball_radius + 1e-5);
        EXPECT_GT(held.size(), 1000u);
        EXPECT_LT(held.size(), eco_points.size()) << "the ball held all the cube holds";
      } else if (map->exact()) {
        EXPECT_EQ(sorted(held), eco_points);  // the same capped set as ECO's
      }
      std::vector<Neighbor> out(queries.size() * k);
      std::vector<std::size_t> found(queries.size());
      map->knn(queries, k, out, found);
      const double side = small_settings().cell_size;
      std::vector<VoxelKey> held_voxels;
      for (const Eigen::Vector3d& p : held) held_voxels.push_back(voxel_of(p, side));
      for (std::size_t i = 0; i < queries.size(); ++i) {
        const std::span<const Neighbor> got(out.data() + i * k, found[i]);
        const std::string what = "query " + std::to_string(i);
        for (std::size_t j = 0; j < got.size(); ++j) {  // every answer is a held point at its distance
          EXPECT_NEAR(got[j].sq_dist, (got[j].point - queries[i]).squaredNorm(), 1e-6) << what;
        }
        if (map->exact()) {
          expect_distances(got, brute_force(held, queries[i], k), what);
          continue;
        }
        // voxel_hash: brute force over the 27 voxels around the query's
        const VoxelKey at = voxel_of(queries[i], side);
        std::vector<Eigen::Vector3d> around;
        for (std::size_t j = 0; j < held.size(); ++j) {
          const VoxelKey& v = held_voxels[j];
          if (std::abs(v.x - at.x) <= 1 && std::abs(v.y - at.y) <= 1 && std::abs(v.z - at.z) <= 1) around.push_back(held[j]);
        }
        expect_distances(got, brute_force(around, queries[i], k), what);
        const std::vector<double> nearest = brute_force(held, queries[i], 1);
        if (!nearest.empty() && nearest[0] < side * side) {  // within a side: in a neighbouring voxel
          ASSERT_FALSE(got.empty()) << what;
          EXPECT_NEAR(got[0].sq_dist, nearest[0], 1e-12) << what;
        }
      }
    }
  }
}

TEST(LocalMaps, UnknownNamesAndBadSettingsAreRefusedByName) {
  try {
    (void)make_any_local_map("kdtree", MapSettings{});
    ADD_FAILURE() << "kdtree accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pcl_octree"), std::string::npos) << e.what();  // the known names
  }
  MapSettings bad;
  bad.cell_size = 0.0;
  EXPECT_THROW((void)make_any_local_map("eco", bad), std::invalid_argument);
  bad = {};
  bad.box_side = -3;
  EXPECT_THROW((void)make_any_local_map("voxel_hash", bad), std::invalid_argument);
}

}  // namespace
}  // namespace eco::odometry
