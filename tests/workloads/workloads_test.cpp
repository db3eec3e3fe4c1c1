// The paper's workloads: the static map (voxel centroids) and its index against brute force,
// static frames against a scan of the whole map, dynamic frames against the reader.

#include <eco/eco.hpp>
#include <eco/sim/simulator.hpp>
#include <eco/workloads/dynamic_workload.hpp>
#include <eco/workloads/static_map.hpp>
#include <eco/workloads/static_workload.hpp>

#include "support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

namespace eco::workloads {
namespace {

using Points = std::vector<Eigen::Vector3d>;

Points sorted(Points p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) {
    return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
  });
  return p;
}

// Frames given in memory.
class ListWorkload final : public Workload {
 public:
  explicit ListWorkload(std::vector<WorkloadFrame> frames) : frames_(std::move(frames)) {}
  std::size_t size() const override { return frames_.size(); }
  WorkloadFrame frame(std::size_t i) const override { return frames_.at(i); }
  Eigen::Isometry3d pose(std::size_t i) const override { return frames_.at(i).world_T_sensor; }
  std::string name() const override { return "list"; }

 private:
  std::vector<WorkloadFrame> frames_;
};

std::vector<WorkloadFrame> random_frames(unsigned seed, std::size_t frames, std::size_t points) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-12.0f, 12.0f);
  std::vector<WorkloadFrame> out;
  for (std::size_t f = 0; f < frames; ++f) {
    WorkloadFrame frame;
    frame.index = f;
    frame.world_T_sensor.linear() = Eigen::AngleAxisd(0.3 * static_cast<double>(f), Eigen::Vector3d(0.1, 0.2, 1).normalized()).toRotationMatrix();
    frame.world_T_sensor.translation() = Eigen::Vector3d(1.5 * static_cast<double>(f), -0.5, 0.25);
    for (std::size_t i = 0; i < points; ++i) frame.points.emplace_back(coord(rng), coord(rng), coord(rng) / 4.0f);
    frame.points.emplace_back(std::nanf(""), 0.0f, 0.0f);  // skipped, like ECO's update does
    out.push_back(std::move(frame));
  }
  return out;
}

TEST(StaticMap, AggregateKeepsTheCentroidOfEveryOccupiedVoxel) {
  const ListWorkload scans(random_frames(1, 4, 20000));
  for (const double resolution : {0.1, 0.5, 2.0}) {
    // Brute force: every finite point into its voxel, in the same order, summed the same way.
    std::map<std::tuple<long, long, long>, std::pair<Eigen::Vector3d, double>> voxels;
    for (std::size_t f = 0; f < scans.size(); ++f) {
      const WorkloadFrame frame = scans.frame(f);
      for (const auto& p : frame.points) {
        if (!p.allFinite()) continue;
        const Eigen::Vector3d w = frame.world_T_sensor * p.cast<double>();
        auto& [sum, count] = voxels[{std::lround(std::floor(w.x() / resolution)),
                                     std::lround(std::floor(w.y() / resolution)),
                                     std::lround(std::floor(w.z() / resolution))}];
        if (count == 0) sum.setZero();
        sum += w;
        count += 1;
      }
    }
    Points expected;
    for (const auto& [key, acc] : voxels) expected.push_back(acc.first / acc.second);
    const StaticMap map = StaticMap::aggregate(scans, resolution);
    EXPECT_EQ(sorted(map.points()), sorted(expected)) << resolution;
  }
}

TEST(StaticMap, BoxQueriesMatchAScanOfEveryPoint) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> coord(-30.0, 30.0);
  Points points;
  for (int i = 0; i < 30000; ++i) points.emplace_back(coord(rng), coord(rng), coord(rng) / 5.0);
  for (double v = -6.0; v <= 6.0; v += 2.0) points.emplace_back(v, -v, 0.0);  // on bucket walls
  for (const double bucket : {0.7, 2.0, 5.0}) {
    const StaticMap map(points, bucket);
    ASSERT_EQ(sorted(map.points()), sorted(points));
    for (int q = 0; q < 60; ++q) {
      Eigen::Vector3d lo(coord(rng), coord(rng), coord(rng) / 5.0);
      Eigen::Vector3d hi = lo + Eigen::Vector3d(coord(rng) + 30.0, coord(rng) + 30.0, coord(rng) / 8.0 + 4.0) / 2.0;
      if (q % 10 == 0) lo = points[static_cast<std::size_t>(q)], hi = lo + Eigen::Vector3d::Constant(4.0);  // a point on lo
      if (q % 10 == 1) hi = points[static_cast<std::size_t>(q)], lo = hi - Eigen::Vector3d::Constant(4.0);  // a point on hi
      if (q == 59) lo = Eigen::Vector3d::Constant(-1e9), hi = Eigen::Vector3d::Constant(1e9);  // the whole map
      Points expected, got;
      for (const auto& p : points) {
        if ((p.array() >= lo.array()).all() && (p.array() < hi.array()).all()) expected.push_back(p);
      }
      map.for_each_in_box(lo, hi, [&](const Eigen::Vector3d& p) { got.push_back(p); });
      ASSERT_EQ(sorted(got), sorted(expected)) << "bucket " << bucket << " query " << q;
    }
  }
}

TEST(StaticMap, RejectsBadArguments) {
  const ListWorkload scans(random_frames(3, 1, 10));
  EXPECT_THROW((void)StaticMap::aggregate(scans, 0.0), std::invalid_argument);
  EXPECT_THROW((void)StaticMap::aggregate(scans, std::nan("")), std::invalid_argument);
  EXPECT_THROW((void)StaticMap::aggregate(scans, 1e-9), std::invalid_argument);  // 2^20 voxels too few
  EXPECT_THROW(StaticMap(Points{}, -1.0), std::invalid_argument);
  const auto map = std::make_shared<const StaticMap>(Points{});
  const std::vector<Eigen::Isometry3d> poses(2, Eigen::Isometry3d::Identity());
  EXPECT_THROW(StaticWorkload(nullptr, poses), std::invalid_argument);
  EXPECT_THROW(StaticWorkload(map, poses, 0.0), std::invalid_argument);
  EXPECT_THROW((void)StaticWorkload(map, poses).frame(2), std::out_of_range);
}

TEST(StaticWorkload, FramesHoldTheMapInsideTheBoxInTheSensorFrame) {
  const ListWorkload scans(random_frames(4, 6, 20000));
  const auto map = std::make_shared<const StaticMap>(StaticMap::aggregate(scans, 0.2));
  std::vector<Eigen::Isometry3d> poses;
  for (std::size_t f = 0; f < scans.size(); ++f) poses.push_back(scans.frame(f).world_T_sensor);
  const double side = 8.0;
  const StaticWorkload workload(map, poses, side);
  ASSERT_EQ(workload.size(), poses.size());
  for (std::size_t f = 0; f < workload.size(); ++f) {
    const WorkloadFrame frame = workload.frame(f);
    EXPECT_EQ(frame.world_T_sensor.matrix(), poses[f].matrix());
    const Eigen::Vector3d c = poses[f].translation();
    std::vector<Eigen::Vector3f> expected;
    for (const auto& p : map->points()) {
      if (((p - c).array() >= -side / 2).all() && ((p - c).array() < side / 2).all()) {
        expected.push_back((poses[f].inverse() * p).cast<float>());
      }
    }
    ASSERT_GT(expected.size(), 100u);
    auto less = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
      return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
    };
    auto got = frame.points;
    std::sort(got.begin(), got.end(), less);
    std::sort(expected.begin(), expected.end(), less);
    EXPECT_EQ(got, expected) << f;
  }
}

TEST(Workloads, FromASimulatedSequenceIntoEco) {
  sim::SimConfig config;
  config.frames = 6;
  config.lidar.columns = 500;  // a lighter scan keeps this test quick under sanitizers
  test::TempDir dir;
  sim::Simulator(config).write_kitti(dir.path());

  const DynamicWorkload dynamic{io::KittiSequence(dir.path())};
  ASSERT_EQ(dynamic.size(), 6u);
  ASSERT_EQ(dynamic.sequence().times().size(), 6u);
  for (std::size_t f = 0; f < dynamic.size(); ++f) {  // the raw scans, as the reader gives them
    const WorkloadFrame frame = dynamic.frame(f);
    const io::KittiFrame read = dynamic.sequence().read(f);
    EXPECT_EQ(frame.points, read.cloud.points);
    EXPECT_EQ(frame.intensities, read.cloud.intensity);
    EXPECT_EQ(frame.time, dynamic.sequence().times()[f]);
    EXPECT_EQ(frame.world_T_sensor.matrix(), read.world_T_lidar.matrix());

    // as a scan with attributes: ids from the first given, the intensities, the frame's time
    const AttributedScan scan(frame, 1000u * std::uint32_t(f));
    ASSERT_EQ(scan.view.count, frame.points.size());
    ASSERT_EQ(scan.view.data, frame.points.front().data());
    for (std::size_t i = 0; i < frame.points.size(); i += 97) {
      EXPECT_EQ(scan.view.ids[i], 1000u * f + i);
      EXPECT_EQ(scan.view.intensities[i], frame.intensities[i]);
      EXPECT_EQ(scan.view.times[i], frame.time);
    }
  }
  WorkloadFrame bare = dynamic.frame(0);
  bare.intensities.clear();  // a source without intensities: zeros
  const AttributedScan zeros(bare, 0);
  EXPECT_TRUE(std::all_of(zeros.intensities.begin(), zeros.intensities.end(), [](float v) { return v == 0.0f; }));
  EXPECT_EQ(zeros.intensities.size(), bare.points.size());

  const auto map = std::make_shared<const StaticMap>(StaticMap::aggregate(dynamic, 0.1));
  const StaticWorkload stat(map, dynamic.sequence().poses());
  Config cfg;
  cfg.insert_policy = InsertPolicy::ShiftInOnly;  // a static map's frames repeat what is held
  EgoOctree tree(cfg);
  for (std::size_t f = 0; f < stat.size(); ++f) {
    const WorkloadFrame frame = stat.frame(f);
    tree.update(frame.world_T_sensor, frame.points);
    // The box's content, less the few points a float round trip moves across its faces.
    EXPECT_NEAR(static_cast<double>(tree.size()), static_cast<double>(frame.points.size()),
                1e-3 * static_cast<double>(frame.points.size()) + 5.0) << f;
  }
  EXPECT_EQ(tree.check_invariants(), "");
}

}  // namespace
}  // namespace eco::workloads
