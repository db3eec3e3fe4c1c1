#pragma once
// The state behind an EgoOctree and the structural operations the update stages compose. Their
// parts live beside it: batch insertion (core/tree/batch_insertion.hpp), the filter that takes points
// out (core/tree/subtree_filter.hpp), and the repair both leave to refit (core/tree/tree_repair.hpp).

#include "core/geometry/motion.hpp"
#include "core/tree/tree_storage.hpp"

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace eco::detail {

struct TreeParts;
class DensityCells;

/// A tree's memory (Tree::memory()).
struct TreeMemory {
  std::size_t bytes = 0;           ///< nodes, leaf blocks, start table, working buffers
  std::size_t buffer_bytes = 0;    ///< of those, the working buffers'
  std::size_t snapshot_bytes = 0;  ///< beside them, what only snapshots hold (core/storage/shared_pages.hpp)
};

/// The tree behind an EgoOctree: its storage (core/tree/tree_storage.hpp) and the frame it is in.
/// Queries read it through the const accessors; stages change it through the operations, each of
/// which leaves the tree whole, and count what they do in the UpdateStats they are handed. The
/// density cap's counts are its owner's (core/density/density_cells.hpp): the operations that take
/// points out forget them in the counts they are handed (null while the cap is off).
class Tree {
 public:
  explicit Tree(const Config& config);
  /// The tree `parts` describe (core/tree/tree_parts.hpp) under `config`. Throws std::invalid_argument
  /// naming the first part that does not fit.
  Tree(const Config& config, const TreeParts& parts);
  Tree(const Tree&) = delete;
  Tree& operator=(const Tree&) = delete;
  ~Tree();  // a snapshot's puts its nodes on the shelf for the next snapshot's copy
  /// This tree as it is now, read-only from any thread while this one changes: it shares every
  /// page of points and copies the nodes; this tree copies a page when it next writes it.
  [[nodiscard]] std::unique_ptr<const Tree> share();

  // --- reading --------------------------------------------------------------------------------
  [[nodiscard]] const Config& config() const { return s_.config(); }
  [[nodiscard]] const NodeStore& nodes() const { return s_.nodes(); }
  [[nodiscard]] const PointStore& points() const { return s_.points(); }
  [[nodiscard]] std::uint32_t root() const { return s_.root(); }
  [[nodiscard]] const Cell& root_cell() const { return s_.root_cell(); }
  [[nodiscard]] const Lattice& lattice() const { return s_.lattice(); }
  [[nodiscard]] std::size_t size() const { return s_.root() == kNone ? 0 : s_.nodes()[s_.root()].count; }
  [[nodiscard]] TreeMemory memory() const;
  [[nodiscard]] const Motion& motion() const { return motion_; }  ///< the current frame's
  [[nodiscard]] const AgeLimit& age_limit() const { return s_.age(); }  ///< the current frame's

  // --- the frame ------------------------------------------------------------------------------
  /// Enters a new frame: its motion, its age limit, and the held times re-expressed in place when
  /// the clock's origin moved.
  void set_motion(const Motion& m);
  /// The region the frame ends with, once the budget narrowed it (Config::region.max_points).
  void narrow_region(const EgoRegion& region, const RegionSize& size) {
    motion_.region = region;
    motion_.region_size = size;
    motion_.region_moved = true;
  }
  /// Gives back what a map that shrank holds in free blocks (a bounded share an update), then the
  /// pages this update replaced by copies and the spare ones beyond what it copied.
  void give_back_memory(std::size_t floor = kMemoryFloor);

  // --- insertion ------------------------------------------------------------------------------
  /// Inserts every point of `batch` (each in the root cell), reordering it.
  void insert_batch(std::span<StoredPoint> batch) { insert_points(batch); }
  void insert_batch(std::span<BarePoint> batch) { insert_points(batch); }
  /// Inserts the points `collect(push)` hands to push(const Point&), in batches of at most
  /// kInsertChunk through the working buffers, each shown to `look(std::span<const Point>)`
  /// first. Returns how many (core/tree/batch_insertion.hpp).
  template <class Point, class Collect, class Look>
  std::size_t insert_collected(Collect&& collect, Look&& look);
  /// Large enough that a batch shares the walk to most start nodes, small enough to stay near the cache.
  static constexpr std::size_t kInsertChunk = std::size_t(1) << 14;
  /// Fills the start table (where insertion starts) from the current tree at `depth`.
  void rebuild_start_table(int depth) { s_.rebuild_start_table(depth); }

  // --- removal --------------------------------------------------------------------------------
  /// Keeps the points of leaf `id` for which keep(const StoredPoint&) is true, and refits it; the
  /// others leave `density` (core/tree/subtree_filter.hpp).
  template <class Keep>
  void retain(std::uint32_t id, Keep&& keep, DensityCells* density);
  /// Takes points out in place as `filter` judges each subtree and leaf, and out of `density`
  /// (core/tree/subtree_filter.hpp).
  template <class Filter>
  void filter(Filter& filter, UpdateStats& stats, DensityCells* density);
  /// Appends every held point to `out`; the tree is left without a root.
  void take_points(std::vector<StoredPoint>& out);

  // --- the root -------------------------------------------------------------------------------
  /// Makes an empty root for `cell` under `lattice` (inner in Quantised mode, else a leaf),
  /// releasing whatever the tree held.
  void place_root(const Cell& cell, const Lattice& lattice);
  /// Exact re-centring: moves the lattice's walls, keeps every subtree whose bounds still fit its
  /// moved cell and dissolves the others into `displaced`.
  void move_lattice(const Lattice& lattice, std::vector<StoredPoint>& displaced, UpdateStats& stats);
  /// Quantised re-centring: the root moves to `new_root`; the subtrees at `depth` are re-linked
  /// under new top levels, and one `new_root` does not enclose is dissolved into `displaced`.
  void relink_top(const Cell& new_root, int depth, std::vector<StoredPoint>& displaced, UpdateStats& stats);
  /// Doubles the root's cell: the old root becomes child `octant` (i-Octree's growth).
  void grow_root(int octant);

 private:
  struct Sharing {};
  Tree(Tree& live, Sharing);
  static constexpr std::size_t kFreeShare = 8;
  static constexpr std::size_t kMemoryFloor = std::size_t{1} << 14;  // below, not worth it (four pages)
  static constexpr std::size_t kCompactionBudget = std::size_t{1} << 20;
  void compact_points(std::size_t floor);
  void shift_times(double shift);  // against a time origin moved by -shift [s]
  void make_root();
  template <class Point>
  void insert_points(std::span<Point> batch);

  TreeStorage s_;
  Motion motion_;
  std::shared_ptr<NodeShelf> shelf_ = std::make_shared<NodeShelf>(s_.ledger());  // shared with snapshots
  LedgerCharge own_bytes_;  // a snapshot's: its copy of the nodes
  bool snapshot_ = false;
};

}  // namespace eco::detail
