// The update's working buffers between updates (Tree::trim_buffers): a map that takes in a few
// thousand points a frame keeps none that grow with them, whatever their element, since buffers
// that small come from the heap's free lists; one that takes in many keeps its point batches, so
// that no frame pays for fresh pages.

#include "core/tree.hpp"
#include "update/stages.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace eco::detail {
namespace {

/// `n` points spread through the box around a sensor at the origin (sensor frame).
std::vector<Eigen::Vector3f> scan_of(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<float> across(-9.9f, 9.9f), up(-2.0f, 2.0f);
  std::vector<Eigen::Vector3f> points;
  for (std::size_t i = 0; i < n; ++i) points.emplace_back(across(rng), across(rng), up(rng));
  return points;
}

TEST(WorkingBuffers, AMapTakingInAFewThousandPointsAFrameKeepsNoneBetweenUpdates) {
  Config config;
  config.density_cap = {0.1, 2};
  Tree tree(config);
  std::mt19937 rng(5);
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  // 200 k points first: a thirty-second of their pools (~90 KB) is more than an index array of a
  // batch (64 KB at most), which was kept when buffers were counted in elements
  for (int t = 0; t < 5; ++t) {
    SCOPED_TRACE("frame " + std::to_string(t));
    const std::vector<Eigen::Vector3f> scan = scan_of(t == 0 ? 200000 : 8000, rng);
    const UpdateStats stats = run_update(tree, pose, ScanView(scan));
    ASSERT_GT(stats.inserted, scan.size() * 9 / 10);
    // the start table's group bounds stay (a few KB, one per start cell); no buffer of points or
    // of their indices (32 KB and more here) does
    EXPECT_LT(tree.buffer_bytes(), std::size_t{16} << 10);
  }
}

TEST(WorkingBuffers, AMapTakingInManyPointsAFrameKeepsItsBatches) {
  Tree tree(Config{});
  std::mt19937 rng(6);
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int t = 0; t < 3; ++t) {
    const std::vector<Eigen::Vector3f> scan = scan_of(200000, rng);
    run_update(tree, pose, ScanView(scan));
  }
  EXPECT_GE(tree.buffer_bytes(), Tree::kInsertChunk * sizeof(BarePoint)) << "a batch of points is kept";
  EXPECT_LT(tree.buffer_bytes(), tree.points().bytes() / 8) << "each kept buffer is under a 32nd of the pools";
}

}  // namespace
}  // namespace eco::detail
