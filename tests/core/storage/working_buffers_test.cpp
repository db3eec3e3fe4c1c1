// The update's memory between updates (src/core/storage/working_buffers.hpp, src/core/storage/mapped_memory.hpp):
// the working buffers stay at what recent updates used, so that no frame pays for fresh pages,
// and shrink once a whole window of updates needed far less; and in steady state the update takes
// nothing of a page or more from the process's heap, where it would split the free space its
// caller reuses each frame.

#include "core/storage/mapped_memory.hpp"
#include "core/tree/tree.hpp"
#include "update/stages.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <cstdlib>
#include <new>
#include <random>
#include <string>
#include <vector>

namespace {

/// Heap allocations of a page or more made while counting (replacing the global operator new).
std::atomic<bool> counting{false};
std::atomic<std::size_t> large_allocations{0};

}  // namespace

void* operator new(std::size_t bytes) {
  if (counting.load(std::memory_order_relaxed) && bytes >= eco::detail::kMappedFrom) {
    large_allocations.fetch_add(1, std::memory_order_relaxed);
  }
  if (void* p = std::malloc(bytes == 0 ? 1 : bytes)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace eco::detail {
namespace {

/// `n` points spread through the box around a sensor at the origin (sensor frame).
std::vector<Eigen::Vector3f> scan_of(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<float> across(-9.9f, 9.9f), up(-2.0f, 2.0f);
  std::vector<Eigen::Vector3f> points;
  for (std::size_t i = 0; i < n; ++i) points.emplace_back(across(rng), across(rng), up(rng));
  return points;
}

/// The pose of frame t of a drive at 1 m a frame.
Eigen::Isometry3d pose_at(int t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(1.0 * t, 0.2 * t, 0.0);
  return pose;
}

TEST(WorkingBuffers, AreKeptBetweenUpdatesAtWhatTheUpdatesUse) {
  Config config;
  config.density_cap = {0.1, 2};
  Tree tree(config);
  const std::unique_ptr<DensityCells> density = density_cells_for(config);
  std::mt19937 rng(5);
  std::size_t kept = 0, skipped = 0;
  for (int t = 0; t < 40; ++t) {
    SCOPED_TRACE("frame " + std::to_string(t));
    const std::vector<Eigen::Vector3f> scan = scan_of(8000, rng);
    const UpdateStats stats = run_update(tree, nullptr, density.get(), pose_at(t), ScanView(scan));
    ASSERT_GT(stats.inserted, 1000u);
    skipped += stats.skipped_by_density;
    if (t == 2) kept = tree.memory().buffer_bytes;
    // neither given back nor grown again: every frame finds its buffers where the last left them
    if (t > 2) {
      EXPECT_EQ(tree.memory().buffer_bytes, kept);
    }
  }
  EXPECT_GE(kept, 1000 * sizeof(BarePoint)) << "a frame's batch is kept";
  EXPECT_GT(skipped, 0u) << "the cap refused points";
}

TEST(WorkingBuffers, ShrinkOnceEachOfTheLastUpdatesNeededFarLess) {
  Tree tree(Config{});
  std::mt19937 rng(6);
  run_update(tree, nullptr, nullptr, pose_at(0), ScanView(scan_of(200000, rng)));
  const std::size_t burst = tree.memory().buffer_bytes;
  EXPECT_GE(burst, Tree::kInsertChunk * sizeof(BarePoint)) << "a whole batch of points is held after the burst";
  const std::size_t window = WorkingBuffers::kWindow;
  for (std::size_t t = 1; t <= window; ++t) {
    run_update(tree, nullptr, nullptr, pose_at(0), ScanView(scan_of(500, rng)));
    if (t < window) {
      EXPECT_EQ(tree.memory().buffer_bytes, burst) << "frame " << t << ": kept while the burst is among the last updates";
    }
  }
  EXPECT_LT(tree.memory().buffer_bytes, burst / 8) << "given back once a window of small frames followed it";
}

TEST(WorkingBuffers, SteadyUpdatesTakeNoPageFromTheHeap) {
  if (!allocations_are_mapped()) GTEST_SKIP() << "under AddressSanitizer every allocation comes from the heap";
  for (const bool capped : {false, true}) {
    SCOPED_TRACE(capped ? "capped" : "uncapped");
    Config config;
    if (capped) config.density_cap = {0.2, 1};
    Tree tree(config);
    const std::unique_ptr<DensityCells> density = density_cells_for(config);
    std::mt19937 rng(7);
    std::vector<std::vector<Eigen::Vector3f>> scans;
    for (int t = 0; t < 30; ++t) scans.push_back(scan_of(20000, rng));
    std::size_t large = 0;
    for (int t = 0; t < 30; ++t) {
      counting = t >= 20;  // the map has come to its size: blocks and buffers are reused
      large_allocations = 0;
      run_update(tree, nullptr, density.get(), pose_at(t), ScanView(scans[std::size_t(t)]));
      counting = false;
      large += large_allocations;
    }
    EXPECT_EQ(large, 0u) << "allocations of a page or more from the heap over 10 steady updates";
  }
}

}  // namespace
}  // namespace eco::detail
