// Snapshots read on other threads while their tree updates (built under ThreadSanitizer in
// `make test`): one writer streams a drive with moving cars, free-space clearing and a density cap,
// publishing a snapshot every frame; readers query random live snapshots without pause, and every
// answer equals the brute-force answer over the points held at the frame the snapshot names.

#include "support/map_answers.hpp"

#include <eco/ego_octree.hpp>
#include <eco/sim/simulator.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

namespace eco::test {
namespace {

/// A snapshot and the points its tree held when it was published.
struct Published {
  std::shared_ptr<const Snapshot> snapshot;
  std::shared_ptr<const std::vector<Eigen::Vector3d>> held;
  std::uint32_t frame = 0;
};

/// The live snapshots: the writer adds one a frame and drops the oldest; readers take any.
class Board {
 public:
  void publish(Published p) {
    const std::lock_guard lock(mutex_);
    live_.push_back(std::move(p));
    if (live_.size() > kLive) live_.pop_front();  // its last handle may go on a reader's thread
  }
  std::optional<Published> pick(std::mt19937& rng) const {
    const std::lock_guard lock(mutex_);
    if (live_.empty()) return std::nullopt;
    return live_[std::uniform_int_distribution<std::size_t>(0, live_.size() - 1)(rng)];
  }

 private:
  static constexpr std::size_t kLive = 4;
  mutable std::mutex mutex_;
  std::deque<Published> live_;
};

std::vector<double> sorted_sq_dists(const std::vector<Neighbor>& found) {
  std::vector<double> d;
  for (const Neighbor& n : found) d.push_back(n.sq_dist);
  std::sort(d.begin(), d.end());
  return d;
}

/// One reader's checks of one snapshot against brute force over `p.held`: KNN (k = 1, 8), a
/// radius, a box and the point count. Returns how many answers it checked.
std::size_t check_against_brute_force(const Published& p, std::mt19937& rng) {
  const Snapshot& s = *p.snapshot;
  const std::vector<Eigen::Vector3d>& held = *p.held;
  EXPECT_EQ(s.frame_count(), p.frame);
  EXPECT_EQ(s.size(), held.size());
  if (held.empty()) return 0;
  std::uniform_int_distribution<std::size_t> pick(0, held.size() - 1);
  std::normal_distribution<double> jitter(0.0, 0.5);
  const Eigen::Vector3d q = held[pick(rng)] + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
  std::vector<double> all;
  all.reserve(held.size());
  for (const Eigen::Vector3d& h : held) all.push_back((h - q).squaredNorm());
  std::sort(all.begin(), all.end());
  for (const std::size_t k : {1, 8}) {
    const std::vector<double> want(all.begin(), all.begin() + std::ptrdiff_t(std::min(k, all.size())));
    EXPECT_EQ(sorted_sq_dists(s.knn(q, k)), want) << "knn, k = " << k << ", frame " << p.frame;
  }
  const double r = 1.5;
  const auto within = std::size_t(std::upper_bound(all.begin(), all.end(), r * r) - all.begin());
  EXPECT_EQ(s.radius(q, r).size(), within) << "radius, frame " << p.frame;
  const Eigen::Vector3d lo = q - Eigen::Vector3d(3, 3, 1), hi = q + Eigen::Vector3d(3, 3, 1);
  std::vector<Eigen::Vector3d> want_box;
  for (const Eigen::Vector3d& h : held) {
    if ((h.array() >= lo.array()).all() && (h.array() <= hi.array()).all()) want_box.push_back(h);
  }
  std::vector<Eigen::Vector3d> got_box = s.box(lo, hi);
  const auto by_xyz = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
  };
  std::sort(want_box.begin(), want_box.end(), by_xyz);
  std::sort(got_box.begin(), got_box.end(), by_xyz);
  EXPECT_EQ(got_box, want_box) << "box, frame " << p.frame;
  return 4;
}

TEST(SnapshotThreads, ReadersOfLiveSnapshotsSeeTheirFrameExactly) {
  const sim::Simulator drive(small_drive(40));
  Config cfg;
  cfg.box_side = 40.0;
  cfg.leaf_capacity = 16;
  with_everything(cfg, drive);
  EgoOctree tree(cfg);
  Board board;
  std::atomic<bool> done{false};
  std::atomic<std::size_t> checked{0};
  std::vector<std::thread> readers;
  for (int r = 0; r < 3; ++r) {
    readers.emplace_back([&, r] {
      std::mt19937 rng(std::uint32_t(100 + r));
      while (!done.load()) {
        if (const std::optional<Published> p = board.pick(rng)) checked += check_against_brute_force(*p, rng);
      }
    });
  }
  std::vector<std::uint32_t> ids;
  std::vector<float> intensities;
  std::vector<double> times;
  std::size_t cleared = 0, refused = 0;
  for (std::size_t t = 0; t < drive.size(); ++t) {
    const sim::SimFrame frame = drive.frame(t);
    ScanView scan(frame.cloud.points);
    add_attributes(scan, t, ids, intensities, times);
    const UpdateStats& s = tree.update(frame.world_T_lidar, scan);
    cleared += s.cleared;
    refused += s.skipped_by_density;
    board.publish({tree.snapshot(), std::make_shared<const std::vector<Eigen::Vector3d>>(tree.points()),
                   tree.frame_count()});
  }
  // the last snapshots stay a while under the readers, with no update beside them
  const std::size_t before = checked.load();
  while (checked.load() < before + 40) std::this_thread::yield();
  done = true;
  for (std::thread& r : readers) r.join();
  EXPECT_GT(cleared, 0u) << "clearing never took a point";
  EXPECT_GT(refused, 0u) << "the density cap never refused a point";
  EXPECT_GT(checked.load(), 3 * drive.size()) << "the readers hardly ran beside the updates";
}

}  // namespace
}  // namespace eco::test
