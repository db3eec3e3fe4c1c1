#pragma once
// The state behind an EgoOctree, and the structural operations the update stages share:
// inserting a batch of points (core/batch_insertion.hpp), dissolving and collapsing subtrees,
// refitting bounds.

#include "core/age_limit.hpp"
#include "core/cell_counts.hpp"
#include "core/density_gate.hpp"
#include "core/geometry.hpp"
#include "core/node_store.hpp"
#include "core/point_store.hpp"
#include "core/motion.hpp"
#include "core/working_buffers.hpp"

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

namespace eco::detail {

class Subcells;
struct TreeParts;

/// Nodes at one depth, indexed by their cell: where insertion starts instead of the root
/// (the paper's movement-aware start depth; in Quantised mode depth k, a direct lattice lookup).
struct StartTable {
  int depth = 0;
  std::int64_t per_axis = 1;
  std::vector<std::uint32_t> slots;
};

/// The depth above which every node is inner: k in Quantised mode (the lattice-fixed levels), else 0.
inline int min_leaf_depth(const Config& config) {
  return config.recentring == Recentring::Quantised ? int(config.quantum_levels) : 0;
}

/// A tree's memory (Tree::memory()).
struct TreeMemory {
  std::size_t bytes = 0;           ///< nodes, leaf blocks, start table, working buffers, density counts
  std::size_t buffer_bytes = 0;    ///< of those, the working buffers' (core/working_buffers.hpp)
  std::size_t snapshot_bytes = 0;  ///< beside them, what only snapshots hold: their nodes, spare
                                   ///< pages, and the pages of points the tree replaced since
};

/// A filter's verdict on a subtree (Tree::filter): keep it whole, drop it whole, or look inside.
enum class Verdict { KeepAll, DropAll, LookInside };

class BatchInsertion;

/// The storage behind an EgoOctree (nodes, leaf blocks, lattice, density counts) and the
/// structural operations the update stages and the baselines compose. Everything it holds is
/// private: queries read it through the const accessors; stages change it through the operations,
/// and count what they do in the UpdateStats they are handed.
class Tree {
 public:
  explicit Tree(const Config& config);
  /// The tree `parts` describe (core/tree_parts.hpp), node for node and point for point, under
  /// `config`. Throws std::invalid_argument naming the first part that does not fit (a count past
  /// the points left, a point outside its leaf's cell, an empty node, a broken invariant).
  Tree(const Config& config, const TreeParts& parts);
  Tree(const Tree&) = delete;
  Tree& operator=(const Tree&) = delete;
  /// A snapshot's puts its nodes on the shelf for the next snapshot's copy.
  ~Tree();
  /// This tree as it is now, to be read only, from any thread, while this one goes on changing
  /// (a snapshot). It shares every page of points (core/shared_pages.hpp), a reference a page,
  /// and copies the nodes; this tree copies a page of points when it first writes it after the
  /// call. The copy holds no start table, density counts or working buffers: reading needs none.
  [[nodiscard]] std::unique_ptr<const Tree> share();

  // --- reading --------------------------------------------------------------------------------
  [[nodiscard]] const Config& config() const { return cfg_; }
  [[nodiscard]] const NodeStore& nodes() const { return nodes_; }
  [[nodiscard]] const PointStore& points() const { return points_; }
  [[nodiscard]] std::uint32_t root() const { return root_; }
  [[nodiscard]] const Cell& root_cell() const { return root_cell_; }
  [[nodiscard]] const Lattice& lattice() const { return lattice_; }
  [[nodiscard]] std::size_t size() const { return root_ == kNone ? 0 : nodes_[root_].count; }
  /// What it holds in memory, and what its snapshots do.
  [[nodiscard]] TreeMemory memory() const;
  /// The current frame's motion (set_motion): pose, precision origin, box, frame number, clock.
  [[nodiscard]] const Motion& motion() const { return motion_; }
  /// The current frame's age limit.
  [[nodiscard]] const AgeLimit& age_limit() const { return age_; }

  // --- the frame --------------------------------------------------------------------------------
  /// Enters a new frame (stage 1): its motion, the density grid seen from its anchor, its age
  /// limit, and the held times re-expressed in place when the clock's origin moved.
  void set_motion(const Motion& m);
  /// Counts the density cells of `held` anew (after the precision origin moved, their keys did).
  void recount_density(const std::vector<StoredPoint>& held);

  /// Gives back the memory a map that shrank holds in its point pools' free blocks, while it is
  /// at least a kFreeShare of them and `floor` bytes: the live blocks at the top of each pool move
  /// into free ones below, kCompactionBudget bytes an update at most, and the pages behind them
  /// are released. No point changes, only where it lies. Then lets go of the pages this update
  /// replaced by copies (a snapshot's, spare when its last holder goes), and gives back the spare
  /// pages beyond as many bytes as it copied (core/shared_pages.hpp).
  void give_back_memory(std::size_t floor = kMemoryFloor);

  // --- insertion --------------------------------------------------------------------------------
  /// Inserts every point of `batch` (each in the root cell), reordering it: the points are
  /// partitioned by octant top-down from the start table's depth, so each node on their way
  /// is visited once per batch, not once per point.
  void insert_batch(std::span<StoredPoint> batch) { insert_points(batch); }
  /// The same for points without columns (the store keeps none).
  void insert_batch(std::span<BarePoint> batch) { insert_points(batch); }
  /// Inserts the new points `collect(push)` hands to push(const Point&), in batches of at most
  /// kInsertChunk through the working buffers: the buffers stay small however many points a
  /// frame brings. Each batch is shown to `look(std::span<const Point>)` before it goes in.
  /// Returns how many.
  template <class Point, class Collect, class Look>
  std::size_t insert_collected(Collect&& collect, Look&& look) {
    MappedVector<Point>& batch = buffers_.batch<Point>();
    std::size_t n = 0;
    const auto insert = [&] {
      n += batch.size();
      look(std::span<const Point>(batch));
      insert_points(std::span<Point>(batch));
      batch.clear();
    };
    batch.clear();
    collect([&](const Point& s) {
      batch.push_back(s);
      if (batch.size() == kInsertChunk) insert();
    });
    insert();
    buffers_.end_update(std::min(n, kInsertChunk));
    return n;
  }
  /// Points per batch of insert_collected: large enough that a batch shares the walk down to most
  /// start nodes, small enough that its two copies (12 or 28 B a point each) stay near the cache.
  static constexpr std::size_t kInsertChunk = std::size_t(1) << 14;
  /// The density cap's verdicts on new points[0, n) (n <= kDensityGroup), in their order:
  /// passed[i] = 1 when point i's cell holds fewer points than the cap (it is counted there;
  /// every point passes while the cap is off). Returns how many it refused.
  std::size_t judge_density(const std::array<float, 3>* points, std::size_t n, std::uint8_t* passed) {
    return judge_group(density_, density_grid_, cfg_.density_cap, points, n, passed);
  }
  /// Fills the start table (where insertion starts) from the current tree at `depth`.
  void rebuild_start_table(int depth);

  // --- removal and repair -----------------------------------------------------------------------
  /// Keeps the points of leaf `id` for which keep(const StoredPoint&) is true, and refits it; the
  /// others leave the density counts.
  template <class Keep>
  void retain(std::uint32_t id, Keep&& keep) {
    Node& n = nodes_.edit(id);
    n.count = points_.retain(n.link, n.count, [&](const StoredPoint& s) {
      if (keep(s)) return true;
      forget(s);
      return false;
    });
    refit(id);
  }
  /// Takes a point that leaves the tree while outside it (handed on between stages) out of the
  /// density counts.
  void forget(const StoredPoint& s) {
    if (cfg_.density_cap.enabled()) density_.remove(density_key(s.p));
  }
  /// Takes points out in place as `filter` judges each subtree by its node and each leaf it looks
  /// into (the interface: core/subtree_filter.hpp); a subtree judged DropAll leaves whole, counted
  /// in `stats` as pruned. Refits what changed, collapses inner nodes left with few points,
  /// releases emptied ones, and gives a tree left empty a fresh root.
  template <class Filter>
  void filter(Filter& filter, UpdateStats& stats);
  /// Appends every held point to `out` and leaves the tree without a root; the density counts
  /// stay (the points are meant to come back).
  void take_points(std::vector<StoredPoint>& out);

  // --- the root ---------------------------------------------------------------------------------
  /// Makes an empty root for `cell` under `lattice` (inner in Quantised mode, a leaf in Exact
  /// mode); the tree must be empty or hold nothing worth keeping (its root is released).
  void place_root(const Cell& cell, const Lattice& lattice);
  /// Exact re-centring: moves the lattice's walls (the nodes keep their cells' indices), keeps
  /// every subtree whose bounds still fit its moved cell, and dissolves the others into
  /// `displaced` (counted in `stats`: relinked below the root, rebuilt).
  void move_lattice(const Lattice& lattice, std::vector<StoredPoint>& displaced, UpdateStats& stats);
  /// Quantised re-centring: the root moves to `new_root` (under the same lattice); the subtrees at
  /// depth `depth` (the lattice-fixed cells) are re-linked under new top levels, counted in
  /// `stats` as relinked; one that `new_root` does not enclose (it can hold no point after
  /// shift-out) is dissolved into `displaced`, counted as rebuilt.
  void relink_top(const Cell& new_root, int depth, std::vector<StoredPoint>& displaced, UpdateStats& stats);
  /// Doubles the root's cell: a new root whose child `octant` is the old root (i-Octree's growth
  /// toward points outside). Every depth moves one down and the lattice gains a level.
  void grow_root(int octant);

 private:
  struct Sharing {};
  Tree(Tree& live, Sharing);

  static constexpr std::size_t kFreeShare = 8;
  static constexpr std::size_t kMemoryFloor = std::size_t{1} << 14;   // below, not worth it (four pages)
  static constexpr std::size_t kCompactionBudget = std::size_t{1} << 20;
  /// give_back_memory's first part: the point pools' free blocks.
  void compact_points(std::size_t floor);
  /// Calls f(const StoredPoint&) for every point below `id`.
  template <class F>
  void walk_points(std::uint32_t id, F&& f) const {
    const Node& n = nodes_[id];
    if (n.leaf) {
      points_.for_each(n.link, n.count, f);
      return;
    }
    nodes_.for_each_child(id, [&](int, std::uint32_t ch) { walk_points(ch, f); });
  }
  /// Re-expresses every held time against a time origin moved by -`shift` [s] (old origin - new
  /// origin), in place, and refits the nodes' age keys when they are read from the times.
  void shift_times(double shift);
  /// Releases the subtree at `id` whose points leave the tree (counted as pruned).
  void drop(std::uint32_t id, UpdateStats& stats);
  /// Recomputes bounds, oldest stamp and (Quantised mode) subcells of leaf `id` from its points,
  /// `quarters` being its cell's.
  void fit_leaf(std::uint32_t id, const Subcells& quarters);
  [[nodiscard]] bool should_collapse(std::uint32_t id) const;
  /// Turns inner node `id` into one leaf holding all the points below it.
  void collapse(std::uint32_t id);
  /// relink_top's parts: releases the nodes above `depth` and lists the subtrees at `depth` with
  /// their cells (the tree is left without a root); links one under the root, creating the inner
  /// nodes on its way; refits every node above `depth`, bottom up.
  const MappedVector<std::pair<std::uint32_t, Cell>>& detach_subtrees(int depth);
  void attach_subtree(std::uint32_t id, const Cell& cell);
  void refit_above(int depth);
  /// move_lattice's walk: node `id` fits `cell` under the moved lattice.
  void refit_moved(std::uint32_t id, const Cell& cell, std::vector<StoredPoint>& displaced, UpdateStats& stats);
  /// Releases the subtree at `id` (and the node itself; the root leaves the tree without one);
  /// appends its points to `out` if given.
  void dissolve(std::uint32_t id, std::vector<StoredPoint>* out);
  /// Unlinks child `octant` of inner node `id` (released, or handed on by dissolve/drop).
  void unlink_child(std::uint32_t id, int octant) { nodes_.edit_child(id, octant) = kNone; }
  /// Recomputes count, bounds and oldest stamp of `id` from its points or children.
  void refit(std::uint32_t id);
  /// Turns inner node `id` into one leaf holding all the points below it when they are so few that
  /// it should be one (at most N_max, below the lattice's fixed levels); returns whether it did.
  bool collapse_if_small(std::uint32_t id);
  enum class Filtered { Unchanged, Changed, Gone };  // what filter_below did to a subtree
  template <class Filter>
  Filtered filter_below(std::uint32_t id, Filter& filter, UpdateStats& stats);
  /// Counts in the density cells every point walk(add) hands to add(const std::array<float, 3>&),
  /// a group of keys at a time (one at a time, the grouped kernel would run for each).
  template <class Walk>
  void count_density(Walk&& walk) {
    std::array<std::uint64_t, CellCounts::kMaxKeys> keys;
    std::array<std::uint8_t, CellCounts::kMaxKeys> passed;
    std::size_t n = 0;
    const auto flush = [&] {
      density_.add_below_each(keys.data(), n, CellCounts::kMaxCount, passed.data());
      n = 0;
    };
    walk([&](const std::array<float, 3>& p) {
      keys[n++] = density_key(p);
      if (n == keys.size()) flush();
    });
    flush();
  }
  /// The density-cap cell of stored point p, as CellCounts names it.
  [[nodiscard]] std::uint64_t density_key(const std::array<float, 3>& p) const {
    return CellCounts::key(density_grid_.index(p));
  }
  /// Creates the root node for root_cell_ (inner in Quantised mode, an empty leaf in Exact mode).
  void make_root();
  /// The child of inner node `id` (cell `cell`) at `octant`, created empty if missing.
  std::uint32_t child_or_new(std::uint32_t id, const Cell& cell, int octant);
  void note_created(std::uint32_t id, const Cell& cell);
  std::int64_t start_slot(const Cell& cell) const;
  /// insert_batch's and insert_collected's work (core/batch_insertion.hpp).
  template <class Point>
  void insert_points(std::span<Point> batch);
  friend class BatchInsertion;

  Config cfg_;
  std::shared_ptr<PageLedger> ledger_;  // the pages this tree and its snapshots hold
  NodeStore nodes_;
  PointStore points_;
  std::uint32_t root_ = kNone;
  Cell root_cell_;
  Lattice lattice_;
  int min_leaf_depth_ = 0;  // min_leaf_depth(cfg_)
  bool keeps_subcells_ = false;  // Quantised mode: every leaf's Node::subcells kept
  Motion motion_;
  AgeLimit age_;  // of motion_
  StartTable start_;
  CellCounts density_;  // points per density-cap cell, kept while the cap is on
  WorldGrid density_grid_{{0, 0, 0}, 1.0};  // the cap's cells from the current anchor
  WorkingBuffers buffers_;
  std::shared_ptr<NodeShelf> shelf_ = std::make_shared<NodeShelf>(ledger_);  // shared with the snapshots
  LedgerCharge own_bytes_;  // a snapshot's: its copy of the nodes
  bool snapshot_ = false;
};

}  // namespace eco::detail
