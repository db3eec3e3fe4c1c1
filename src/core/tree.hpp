#pragma once
// The state behind an EgoOctree, and the structural operations the update stages share:
// inserting a batch of points, splitting a leaf, dissolving and collapsing subtrees, refitting bounds.

#include "core/cell_counts.hpp"
#include "core/geometry.hpp"
#include "core/node_store.hpp"
#include "core/point_store.hpp"
#include "core/motion.hpp"

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <optional>
#include <vector>

namespace eco::detail {

/// Nodes at one depth, indexed by their cell: where insertion starts instead of the root
/// (the paper's movement-aware start depth; in Quantised mode depth k, a direct lattice lookup).
struct StartTable {
  int depth = 0;
  std::int64_t per_axis = 1;
  std::vector<std::uint32_t> slots;
};

struct Tree {
  explicit Tree(const Config& config);

  Config cfg;
  NodeStore nodes;
  PointStore points;
  std::uint32_t root = kNone;
  Cell root_cell;
  Lattice lattice;
  int min_leaf_depth = 0;  // k in Quantised mode (the top k levels are always inner), else 0

  std::optional<Motion> motion;  // the current frame's (set_motion); none before the first
  UpdateStats last;

  StartTable start;
  CellCounts density;  // points per density-cap cell, kept while the cap is on
  WorldGrid density_grid{{0, 0, 0}, 1.0};  // the cap's cells from the current anchor (set_motion)
  std::vector<StoredPoint> scratch;  // points of a leaf being split or a subtree collapsed
  struct BatchBuffers {  // insert_batch's and shift-in's, kept so that no frame pays for fresh pages
    std::vector<StoredPoint> scan, points;
    std::vector<std::uint32_t> slot_of, group_start, group_end;
  } batch_buffers;

  // --- the current frame ------------------------------------------------------------------
  [[nodiscard]] const Eigen::Isometry3d& pose() const {
    static const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
    return motion ? motion->pose : identity;
  }
  [[nodiscard]] Eigen::Vector3d anchor() const { return motion ? motion->anchor : Eigen::Vector3d::Zero(); }
  [[nodiscard]] Box box() const { return motion ? motion->box : Box{}; }
  /// Frames taken in so far (the current frame's number).
  [[nodiscard]] std::uint32_t frame() const { return motion ? motion->frame : 0; }

  // --- geometry -----------------------------------------------------------------------------
  /// Anchor-frame float coordinates of a world point (the stored representation).
  [[nodiscard]] std::array<float, 3> to_stored(const Eigen::Vector3d& world) const;
  [[nodiscard]] Eigen::Vector3d to_world(const std::array<float, 3>& stored) const;
  /// Whether held point `s` stays: inside `box` and within the age limit. Counts what it drops
  /// in `last` (pruned takes precedence over aged) and takes it out of the density counts.
  bool keeps(const StoredPoint& s, const Box& box) {
    if (!box.contains(s.p[0], s.p[1], s.p[2])) {
      ++last.pruned;
      forget(s);
      return false;
    }
    if (s.stamp < age_cutoff()) {
      ++last.aged_out;
      forget(s);
      return false;
    }
    return true;
  }
  /// Enters a new frame (stage 1): its motion, and the density grid seen from its anchor.
  void set_motion(const Motion& m) {
    motion = m;
    density_grid = WorldGrid({m.anchor[0], m.anchor[1], m.anchor[2]}, cfg.density_cap.cell_size);
  }
  /// The density-cap cell of stored point p, as CellCounts names it.
  [[nodiscard]] std::uint64_t density_key(const std::array<float, 3>& p) const {
    return CellCounts::key(density_grid.index(p));
  }
  /// Takes a point that leaves the tree out of the density counts.
  void forget(const StoredPoint& s) {
    if (cfg.density_cap.enabled()) density.remove(density_key(s.p));
  }
  /// Points stamped before this frame are past the age limit (0 while no limit applies).
  [[nodiscard]] std::uint32_t age_cutoff() const {
    const std::uint32_t age = cfg.max_age_frames;
    return age > 0 && frame() > age ? frame() - age : 0;
  }

  // --- structure ----------------------------------------------------------------------------
  /// Inserts every point of `batch` (each in the root cell), reordering it: the points are
  /// partitioned by octant top-down from the start table's depth, so each node on their way
  /// is visited once per batch, not once per point.
  void insert_batch(std::vector<StoredPoint>& batch);
  /// Gives back the working buffers' memory when it is far above the `used` points a frame needs
  /// now (a first frame that took a whole map in), so they keep what steady frames use.
  void trim_buffers(std::size_t used);
  /// Bytes held by the working buffers.
  [[nodiscard]] std::size_t buffer_bytes() const;
  /// Recomputes count, bounds and oldest stamp of `id` from its points or children.
  void refit(std::uint32_t id);
  /// Releases the subtree at `id` (and the node itself); appends its points to `out` if given.
  void dissolve(std::uint32_t id, std::vector<StoredPoint>* out);
  /// Releases the subtree at `id` whose points leave the tree (counted as pruned).
  void drop(std::uint32_t id);
  /// Turns inner node `id` into one leaf holding all the points below it.
  void collapse(std::uint32_t id);
  /// Whether `id` (inner) holds so few points that it should be one leaf.
  [[nodiscard]] bool should_collapse(std::uint32_t id) const;
  /// Calls f(const StoredPoint&) for every point below `id`.
  template <class F>
  void walk_points(std::uint32_t id, F&& f) const {
    const Node& n = nodes[id];
    if (n.leaf) {
      points.for_each(n.link, n.count, f);
      return;
    }
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = nodes.child(id, o);
      if (ch != kNone) walk_points(ch, f);
    }
  }
  /// Creates the root node for root_cell (inner in Quantised mode, an empty leaf in Exact mode).
  void make_root();
  /// Fills the start table from the current tree.
  void rebuild_start_table(int depth);
  /// The child of inner node `id` (cell `cell`) at `octant`, created empty if missing.
  std::uint32_t child_or_new(std::uint32_t id, const Cell& cell, int octant);

 private:
  void split(std::uint32_t id, const Cell& cell);
  /// Inserts points [from, to), all inside `cell`, into the subtree at `id`, partitioning them
  /// into `temp` (room for as many; both ranges are overwritten); the caller adds them to the
  /// ancestors.
  void insert_range(std::uint32_t id, const Cell& cell, StoredPoint* from, StoredPoint* to,
                    StoredPoint* temp);
  /// The node at the start depth holding `cell`'s points (created on the way), or the leaf above.
  std::uint32_t start_node(const Cell& cell, Cell& at);
  /// Prefetches the start node of the first non-empty group at or after `from` (groups of
  /// insert_batch, `first` their bounds), so its miss overlaps the work on the group before.
  void prefetch_start_node(std::size_t from, const std::vector<std::uint32_t>& first) const;
  void note_created(std::uint32_t id, const Cell& cell);
  std::int64_t start_slot(const Cell& cell) const;
};

}  // namespace eco::detail
