// The tree's structural operations on their own (src/core/tree/tree.hpp), beyond what the update's
// oracle tests reach through the stages: taking every point out, detaching and re-attaching the
// depth-k subtrees (Quantised re-linking), and growing the root (i-Octree). After each, the held
// points are exactly those inserted and check_tree() finds every invariant intact.

#include "core/tree/invariants.hpp"
#include "core/tree/tree.hpp"
#include "core/tree/tree_parts.hpp"
#include "query/frames.hpp"
#include "update/stages.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

using Points = std::vector<std::array<float, 3>>;

/// A tree on `config` placed at `position`, holding `n` random points of its box.
class TreeOpsTest : public ::testing::Test {
 protected:
  void fill(const Config& config, std::size_t n) {
    tree_ = std::make_unique<Tree>(config);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(3.2, -4.1, 0.7);
    const Motion motion = next_motion(pose, Motion{}, config.box_side);
    tree_->set_motion(motion);
    UpdateStats stats;
    EXPECT_TRUE(refine_overlap(*tree_, motion, {}, stats).empty());  // places the first root
    place_start_table(*tree_, motion);
    std::mt19937 rng(11);
    std::vector<StoredPoint> batch;
    for (std::size_t i = 0; i < n; ++i) {
      StoredPoint s{};
      for (int a = 0; a < 3; ++a) {
        // clustered like surfaces, so that subtrees of every size appear
        std::uniform_real_distribution<double> u(motion.box.lo[a], motion.box.hi[a]);
        const double v = i % 3 == 0 ? u(rng) : std::fmod(std::abs(u(rng)), 2.0) + motion.box.lo[a];
        s.p[std::size_t(a)] = float(v);
      }
      if (!motion.box.contains(s.p[0], s.p[1], s.p[2])) continue;
      inserted_.push_back(s.p);
      batch.push_back(s);
    }
    tree_->insert_batch(batch);
    std::sort(inserted_.begin(), inserted_.end());
    ASSERT_EQ(tree_->size(), inserted_.size());
    ASSERT_EQ(check_tree(*tree_), "");
  }

  [[nodiscard]] Points held() const {
    Points out;
    if (tree_->root() != kNone) {
      walk_leaves(
          *tree_, tree_->root(), [](const Aabb&) { return 2; }, [&](const StoredPoint& s, bool) { out.push_back(s.p); });
    }
    std::sort(out.begin(), out.end());
    return out;
  }

  std::unique_ptr<Tree> tree_;
  Points inserted_;
};

/// A tree's layout written out as a file's coordinate columns (the tree keeps no other), and the
/// parts that read them.
struct FileColumns {
  std::vector<float> x, y, z;
  explicit FileColumns(const TreeLayout& layout) {
    for (const PointSpan& leaf : layout.leaves) {
      EXPECT_EQ(leaf.stamps, nullptr);
      EXPECT_EQ(leaf.ids, nullptr);
      EXPECT_EQ(leaf.intensities, nullptr);
      EXPECT_EQ(leaf.times, nullptr);
      if (leaf.size == 0) continue;
      x.insert(x.end(), leaf.x, leaf.x + leaf.size);
      y.insert(y.end(), leaf.y, leaf.y + leaf.size);
      z.insert(z.end(), leaf.z, leaf.z + leaf.size);
    }
  }
  [[nodiscard]] TreeParts parts_of(const TreeLayout& layout) const {
    TreeParts parts{layout.motion, layout.nodes, x.size(), {}};
    parts.points.x = reinterpret_cast<const std::byte*>(x.data());
    parts.points.y = reinterpret_cast<const std::byte*>(y.data());
    parts.points.z = reinterpret_cast<const std::byte*>(z.data());
    return parts;
  }
};

/// A tree taken apart and put back is the same tree; a point moved past its leaf's cell (by the
/// float just past a wall), out of the box, or made NaN is refused naming its leaf.
TEST_F(TreeOpsTest, PartsPutBackMakeTheSameTreeAndAStrayPointIsRefused) {
  Config config;
  config.leaf_capacity = 8;
  fill(config, 3000);
  const TreeLayout layout = layout_of(*tree_);
  const FileColumns columns(layout);
  ASSERT_EQ(columns.x.size(), tree_->size());
  const Tree again(config, columns.parts_of(layout));
  EXPECT_EQ(check_tree(again), "");
  ASSERT_EQ(again.size(), tree_->size());
  const TreeLayout back = layout_of(again);
  const FileColumns back_columns(back);
  EXPECT_EQ(back_columns.x, columns.x);
  EXPECT_EQ(back_columns.y, columns.y);
  EXPECT_EQ(back_columns.z, columns.z);
  ASSERT_EQ(back.nodes.size(), layout.nodes.size());
  for (std::size_t i = 0; i < layout.nodes.size(); ++i) {
    EXPECT_EQ(back.nodes[i].leaf, layout.nodes[i].leaf);
    EXPECT_EQ(back.nodes[i].children, layout.nodes[i].children);
    EXPECT_EQ(back.nodes[i].count, layout.nodes[i].count);
  }
  // the first leaf's cell, found by walking the pre-order entries to it
  const Cell root = tree_->root_cell();
  Cell cell = root;
  std::uint32_t id = tree_->root();
  while (!tree_->nodes()[id].leaf) {
    std::uint32_t first = kNone;
    int first_octant = 0;
    tree_->nodes().for_each_child(id, [&](int o, std::uint32_t ch) {
      if (first == kNone) first = ch, first_octant = o;
    });
    cell = tree_->lattice().child(cell, first_octant);
    id = first;
  }
  ASSERT_GT(tree_->nodes()[id].count, 0u);
  const double lower = tree_->lattice().wall(0, cell.lo[0]);
  const double upper = tree_->lattice().wall(0, cell.lo[0] + tree_->lattice().side(cell.depth));
  float at_upper = float(upper);  // the least float on or past the upper wall: the next cell's
  if (double(at_upper) < upper) at_upper = std::nextafter(at_upper, std::numeric_limits<float>::infinity());
  float below_lower = float(lower);  // the greatest float below the lower wall
  if (double(below_lower) >= lower) below_lower = std::nextafter(below_lower, -std::numeric_limits<float>::infinity());
  for (const float stray : {at_upper, below_lower,
                            std::numeric_limits<float>::quiet_NaN(), float(tree_->motion().box.hi[0]) + 1.0f}) {
    FileColumns bad = columns;
    bad.x[0] = stray;
    try {
      (void)Tree(config, bad.parts_of(layout));
      ADD_FAILURE() << "a point at x = " << stray << " was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("lies outside its leaf's cell or the ego box"), std::string::npos)
          << e.what();
    }
  }
}

TEST_F(TreeOpsTest, TakePointsHandsBackEveryPointAndLeavesNoRoot) {
  fill(Config{}, 5000);
  std::vector<StoredPoint> out;
  tree_->take_points(out);
  EXPECT_EQ(tree_->root(), kNone);
  EXPECT_EQ(tree_->size(), 0u);
  EXPECT_EQ(tree_->nodes().live(), 0u);
  Points taken;
  for (const StoredPoint& s : out) taken.push_back(s.p);
  std::sort(taken.begin(), taken.end());
  EXPECT_EQ(taken, inserted_);
}

TEST_F(TreeOpsTest, RelinkingTheTopKeepsEverySubtreeAndEveryPoint) {
  const Config config;  // Quantised, k = 3
  fill(config, 20000);
  const int k = int(config.quantum_levels);
  const std::size_t live = tree_->nodes().live();
  std::vector<StoredPoint> displaced;
  UpdateStats stats;
  tree_->relink_top(tree_->root_cell(), k, displaced, stats);  // the same root: every subtree fits
  EXPECT_TRUE(displaced.empty());
  EXPECT_GT(stats.relinked_subtrees, 0u);
  EXPECT_EQ(stats.rebuilt_subtrees, 0u);
  EXPECT_EQ(check_tree(*tree_), "");
  EXPECT_EQ(held(), inserted_);
  EXPECT_EQ(tree_->nodes().live(), live);  // the same top levels, made afresh
}

TEST_F(TreeOpsTest, RelinkingToAMovedRootPutsOutWhatItNoLongerEnclosesAndLinksNothingGone) {
  const Config config;  // Quantised, k = 3
  fill(config, 20000);
  const int k = int(config.quantum_levels);
  Cell moved = tree_->root_cell();
  moved.lo[0] += tree_->lattice().side(k);  // one depth-k cell along x: a slab of subtrees left behind
  std::vector<StoredPoint> displaced;
  UpdateStats stats;
  tree_->relink_top(moved, k, displaced, stats);
  EXPECT_GT(stats.relinked_subtrees, 0u);
  EXPECT_GT(stats.rebuilt_subtrees, 0u);
  EXPECT_FALSE(displaced.empty());
  EXPECT_EQ(check_tree(*tree_), "");  // no link to a node the dissolved subtrees released
  Points all = held();
  for (const StoredPoint& s : displaced) {
    EXPECT_LT(s.p[0], tree_->lattice().wall(0, moved.lo[0])) << "a point the moved root encloses was put out";
    all.push_back(s.p);
  }
  std::sort(all.begin(), all.end());
  EXPECT_EQ(all, inserted_);
}

TEST_F(TreeOpsTest, ARootPlacedAnewTakesPointsFromTheRootUntilItsStartTableIsRebuilt) {
  fill(Config{}, 5000);  // the start table filled at depth k, its slots naming the nodes there
  tree_->place_root(tree_->root_cell(), tree_->lattice());  // every node released
  std::vector<StoredPoint> batch;
  for (std::size_t i = 0; i < inserted_.size(); i += 3) batch.push_back(StoredPoint{inserted_[i]});
  Points want;
  for (const StoredPoint& s : batch) want.push_back(s.p);
  std::sort(want.begin(), want.end());
  tree_->insert_batch(batch);
  EXPECT_EQ(held(), want);
  EXPECT_EQ(check_tree(*tree_), "");
}

TEST_F(TreeOpsTest, GrowingTheRootKeepsEveryPointAndDeepensTheLattice) {
  Config config;
  config.recentring = Recentring::Exact;
  fill(config, 3000);
  for (const int octant : {0, 7, 2, 5}) {
    const Cell before = tree_->root_cell();
    const std::int64_t side = tree_->lattice().side(0);
    const int depth = tree_->lattice().max_depth;
    tree_->grow_root(octant);
    EXPECT_EQ(tree_->lattice().max_depth, depth + 1);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(tree_->root_cell().lo[a], before.lo[a] - (octant >> a & 1 ? side : 0)) << "axis " << a;
    }
    EXPECT_EQ(tree_->nodes().child(tree_->root(), octant) != kNone, true);
    EXPECT_EQ(check_tree(*tree_), "") << "after growing toward octant " << octant;
    EXPECT_EQ(held(), inserted_);
  }
}

TEST_F(TreeOpsTest, PointsOnTheLatticesWallsGoWhereTheirOctantsLead) {
  // Batches large enough to be sorted by their cells (Tree::insert_sorted), most of their points
  // on a wall of the finest cells or the float below one, where the cells' guesses are unsure and
  // the walls decide; in clusters, so that start nodes receive hundreds of points at once.
  for (const std::uint32_t leaf_capacity : {4u, 32u}) {
    Config config;
    config.leaf_capacity = leaf_capacity;
    fill(config, 0);
    const Lattice& lattice = tree_->lattice();
    const Cell root = tree_->root_cell();
    const Box box = tree_->motion().box;
    std::mt19937 rng(leaf_capacity);
    std::uniform_int_distribution<std::int64_t> cluster(0, lattice.side(0) - 1), near(-40, 40);
    std::vector<StoredPoint> batch;
    for (int c = 0; c < 40; ++c) {
      std::array<std::int64_t, 3> centre{};
      for (std::size_t a = 0; a < 3; ++a) centre[a] = root.lo[a] + cluster(rng);
      for (int i = 0; i < 300; ++i) {
        StoredPoint s{};
        for (std::size_t a = 0; a < 3; ++a) {
          const double wall = lattice.wall(int(a), centre[a] + near(rng));
          float f = float(wall);
          if (double(f) < wall) f = std::nextafter(f, std::numeric_limits<float>::infinity());  // on the wall
          const int choice = int(rng() % 3);
          if (choice == 1) f = std::nextafter(f, -std::numeric_limits<float>::infinity());  // just below it
          if (choice == 2) f = float(wall + 0.3 * lattice.unit);  // inside a cell
          s.p[a] = f;
        }
        if (box.contains(s.p[0], s.p[1], s.p[2])) batch.push_back(s);
      }
    }
    std::vector<StoredPoint> copy = batch;
    tree_->insert_batch(copy);
    Points want;
    for (const StoredPoint& s : batch) want.push_back(s.p);
    std::sort(want.begin(), want.end());
    EXPECT_GT(want.size(), 5000u);
    EXPECT_EQ(held(), want) << "leaf capacity " << leaf_capacity;
    EXPECT_EQ(check_tree(*tree_), "") << "leaf capacity " << leaf_capacity;
  }
}

TEST_F(TreeOpsTest, DropAndFilterCountWhatLeaves) {
  fill(Config{}, 5000);
  UpdateStats stats;
  Motion motion = tree_->motion();
  Box& half = motion.box;
  half.hi[0] = (half.lo[0] + half.hi[0]) / 2;  // keep the lower half in x
  prune_shift_out(*tree_, nullptr, motion, stats);
  Points want;
  std::copy_if(inserted_.begin(), inserted_.end(), std::back_inserter(want),
               [&](const std::array<float, 3>& p) { return half.contains(p[0], p[1], p[2]); });
  EXPECT_EQ(held(), want);
  EXPECT_EQ(stats.pruned, inserted_.size() - want.size());
  EXPECT_EQ(stats.aged_out, 0u);
  EXPECT_EQ(check_tree(*tree_), "");
}

TEST_F(TreeOpsTest, GivingBackMemoryMovesNoPointAndFreesTheBlocksAShrunkMapHeld) {
  for (const Recentring recentring : {Recentring::Quantised, Recentring::Exact}) {
    SCOPED_TRACE(recentring == Recentring::Exact ? "Exact" : "Quantised");
    Config config;
    config.recentring = recentring;
    fill(config, 40000);
    const std::size_t full = tree_->points().bytes();
    UpdateStats stats;
    Motion motion = tree_->motion();
    Box& corner = motion.box;  // keep the far corner from the clusters: most points and nodes leave
    for (int a = 0; a < 3; ++a) corner.lo[a] = corner.hi[a] - 0.6 * (corner.hi[a] - corner.lo[a]);
    prune_shift_out(*tree_, nullptr, motion, stats);
    const Points want = held();
    ASSERT_LT(want.size(), inserted_.size() / 4);
    const std::size_t shrunk = tree_->points().bytes();
    EXPECT_GT(shrunk, full / 2) << "the pools keep what they held";

    tree_->give_back_memory(0);  // within one budget here
    EXPECT_EQ(held(), want);
    EXPECT_EQ(check_tree(*tree_), "") << "every leaf's block moved with its link";
    EXPECT_LT(tree_->points().bytes(), shrunk / 2);
    // and the tree goes on: what comes in is held beside what stayed
    std::vector<StoredPoint> more;
    Points expected = want;
    for (std::size_t i = 0; i < 3000; ++i) {
      const std::array<float, 3> p{float(corner.lo[0] + 0.001 * double(i)), float(corner.lo[1] + 0.5), float(corner.lo[2] + 0.25)};
      more.push_back(StoredPoint{p});
      expected.push_back(p);
    }
    tree_->insert_batch(more);
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(held(), expected);
    EXPECT_EQ(check_tree(*tree_), "");
    inserted_.clear();
  }
}

}  // namespace
}  // namespace eco::detail
