// Snapshots (EgoOctree::snapshot()): a snapshot answers as its frame did whatever the tree does
// after it, publishing changes nothing the tree does, and what only snapshots hold goes back when
// their last handle goes.

#include "support/map_answers.hpp"
#include "support/temp_dir.hpp"

#include <eco/ego_octree.hpp>
#include <eco/sim/simulator.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace eco::test {
namespace {

using Params = std::tuple<Recentring, bool>;  // re-centring; clearing, density cap, attributes and age limit

class Snapshots : public ::testing::TestWithParam<Params> {
 protected:
  Config config(const sim::Simulator& drive) const {
    const auto [recentring, everything] = GetParam();
    Config cfg;
    cfg.recentring = recentring;
    cfg.box_side = 40.0;
    cfg.leaf_capacity = 16;  // small leaves: splits and collapses every frame
    if (everything) with_everything(cfg, drive);
    return cfg;
  }
};

/// The frame of a drive carried 2 km out from frame 10 on, so that the precision origin moves
/// under held points.
sim::SimFrame far_frame(const sim::Simulator& drive, std::size_t t) {
  sim::SimFrame frame = drive.frame(t);
  const double x10 = drive.pose(10).translation().x();
  if (t >= 10) frame.world_T_lidar.translation().x() += 2040.0 - x10 + 3.0 * double(t - 10);
  return frame;
}

/// A snapshot published after every frame answers, every frame after, as a copy of the map of its
/// frame does (saved and loaded then: tests/persist/save_load_test.cpp proves the copy exact):
/// splits, collapses, re-centring, precision-origin moves, clearing and ageing after it change
/// nothing it says. The tree that publishes stays identical to one that never does.
TEST_P(Snapshots, AnswerAsTheirFrameDidWhateverTheTreeDoesAfter) {
  const sim::Simulator drive(small_drive(24));
  const Config cfg = config(drive);
  TempDir dir("eco-snapshot");
  EgoOctree tree(cfg), twin(cfg);
  struct Published {
    std::shared_ptr<const Snapshot> snapshot;
    EgoOctree copy;  // the map as of the snapshot's frame
  };
  std::vector<Published> published;
  std::mt19937 rng(3);
  std::vector<std::uint32_t> ids;
  std::vector<float> intensities;
  std::vector<double> times;
  bool rebased = false;
  std::size_t relinked = 0, rebuilt = 0, cleared = 0, aged = 0;
  for (std::size_t t = 0; t < drive.size(); ++t) {
    const sim::SimFrame frame = far_frame(drive, t);
    ScanView scan(frame.cloud.points);
    if (cfg.attributes.ids) add_attributes(scan, t, ids, intensities, times);
    const UpdateStats& s = tree.update(frame.world_T_lidar, scan);
    rebased = rebased || s.rebased;
    relinked += s.relinked_subtrees;
    rebuilt += s.rebuilt_subtrees;
    cleared += s.cleared;
    aged += s.aged_out;
    twin.update(frame.world_T_lidar, scan);
    expect_identical(twin, tree, rng, "frame " + std::to_string(t) + ": the publishing tree against its twin");
    for (const Published& p : published) {
      expect_identical(p.copy, *p.snapshot, rng,
                       "frame " + std::to_string(t) + ": the snapshot of frame " + std::to_string(p.copy.frame_count()));
      if (HasFatalFailure()) return;
    }
    const std::string path = (dir / "map.eco").string();
    tree.save(path);
    published.push_back({tree.snapshot(), EgoOctree::load(path)});
    EXPECT_EQ(published.back().snapshot->frame_count(), t + 1);
    EXPECT_TRUE(published.back().snapshot->pose().isApprox(frame.world_T_lidar, 0.0));
    if (published.size() > 8) published.erase(published.begin() + 1);  // the first stays to the end
  }
  EXPECT_TRUE(rebased) << "the precision origin never moved under held points";
  EXPECT_GT(relinked + rebuilt, 0u) << "the box never re-centred";
  if (cfg.clearing.enabled) {
    EXPECT_GT(cleared, 0u);
    EXPECT_GT(aged, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, Snapshots,
                         ::testing::Combine(::testing::Values(Recentring::Quantised, Recentring::Exact),
                                            ::testing::Bool()),
                         [](const ::testing::TestParamInfo<Params>& p) {
                           return std::string(std::get<0>(p.param) == Recentring::Exact ? "Exact" : "Quantised") +
                                  (std::get<1>(p.param) ? "_ClearingCapAttributesAge" : "");
                         });

/// While a snapshot is held, the pages the tree has since written are kept twice and counted in
/// Stats::snapshot_bytes (by the tree and the snapshot alike); once the last handle goes and the
/// tree has updated once more (it keeps spare what it may copy again), the tree holds no more than
/// a tree that never published, but for the free blocks compaction leaves it.
TEST(SnapshotMemory, ReturnsToTheLevelOfATreeThatNeverPublished) {
  const sim::Simulator drive(small_drive(16));
  EgoOctree tree, twin;
  std::shared_ptr<const Snapshot> first, copy;
  for (std::size_t t = 0; t < drive.size(); ++t) {
    const sim::SimFrame frame = drive.frame(t);
    tree.update(frame.world_T_lidar, ScanView(frame.cloud.points));
    twin.update(frame.world_T_lidar, ScanView(frame.cloud.points));
    if (t == 3) first = tree.snapshot();
    if (t == 8) copy = first;  // a second handle to the same snapshot
    if (t > 3) {
      EXPECT_GT(tree.stats().snapshot_bytes, 0u) << "frame " << t;
      EXPECT_EQ(first->stats().snapshot_bytes, tree.stats().snapshot_bytes) << "frame " << t;
    }
    EXPECT_EQ(twin.stats().snapshot_bytes, 0u);
  }
  const std::size_t held = tree.stats().snapshot_bytes;
  EXPECT_GT(held, 0u);
  first.reset();
  EXPECT_EQ(tree.stats().snapshot_bytes, held) << "a handle is left";
  copy.reset();  // its pages are spare now, kept for the copies of one more update
  const sim::SimFrame frame = drive.frame(drive.size() - 1);
  tree.update(frame.world_T_lidar, ScanView(frame.cloud.points));
  twin.update(frame.world_T_lidar, ScanView(frame.cloud.points));
  EXPECT_EQ(tree.stats().snapshot_bytes, 0u);
  // while the snapshot kept the blocks let go of, the tree took fresh ones; those kept are free now,
  // and compaction gives free blocks back past an eighth of the pools and four pages
  const std::size_t published = tree.stats().bytes, never = twin.stats().bytes;
  EXPECT_LE(published, never + published / 8 + (std::size_t{1} << 14));
  EXPECT_EQ(tree.points(), twin.points());
}

/// A snapshot outlives its tree: it holds what it reads.
TEST(SnapshotLifetime, OutlivesItsTree) {
  const sim::Simulator drive(small_drive(4));
  std::shared_ptr<const Snapshot> snapshot;
  std::vector<Eigen::Vector3d> points;
  {
    EgoOctree tree;
    for (std::size_t t = 0; t < drive.size(); ++t) {
      const sim::SimFrame frame = drive.frame(t);
      tree.update(frame.world_T_lidar, ScanView(frame.cloud.points));
    }
    snapshot = tree.snapshot();
    points = tree.points();
  }
  EXPECT_EQ(snapshot->points(), points);
  EXPECT_EQ(snapshot->check_invariants(), "");
  // with the tree gone, all it holds is held by snapshots only
  EXPECT_GT(snapshot->stats().snapshot_bytes, snapshot->stats().bytes / 2);
  EXPECT_LE(snapshot->stats().snapshot_bytes, snapshot->stats().bytes);
}

/// A snapshot of a tree that has taken no frame is an empty map of frame 0.
TEST(SnapshotLifetime, OfAnEmptyTree) {
  EgoOctree tree;
  const std::shared_ptr<const Snapshot> snapshot = tree.snapshot();
  EXPECT_EQ(snapshot->size(), 0u);
  EXPECT_EQ(snapshot->frame_count(), 0u);
  EXPECT_TRUE(snapshot->knn(Eigen::Vector3d::Zero(), 3).empty());
  EXPECT_TRUE(snapshot->voxel_keys(0.5).empty());
  EXPECT_TRUE(snapshot->ego_box().isEmpty());
}

}  // namespace
}  // namespace eco::test
