#pragma once
// What a tree is made of — its nodes, its leaves' points, its root and lattice, the start table
// insertion starts from, its working buffers — behind the operations that keep them agreeing.
// Tree composes its operations on it; batch insertion (core/tree/batch_insertion.hpp) and
// repair (core/tree/tree_repair.hpp) are operations on it too, each handed the storage it works on.

#include "core/geometry/geometry.hpp"
#include "core/storage/node_store.hpp"
#include "core/storage/point_store.hpp"
#include "core/storage/shared_pages.hpp"
#include "core/storage/working_buffers.hpp"
#include "core/tree/age_limit.hpp"

#include <eco/config.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace eco::detail {

/// The depth above which every node is inner: k in Quantised mode (the lattice-fixed levels), else 0.
inline int min_leaf_depth(const Config& config) {
  return config.recentring == Recentring::Quantised ? int(config.quantum_levels) : 0;
}

/// The point columns a tree under `config` keeps: stamps for an age limit in frames, and the
/// attributes it asks for.
inline Columns kept_columns(const Config& config) {
  return {config.max_age_frames > 0, config.attributes.ids, config.attributes.intensity, config.attributes.time};
}

/// What a tree is made of, behind the operations that keep its parts agreeing. What the
/// configuration fixes cannot change; the root's placement changes only whole (a root cell with
/// its lattice); the start table is filled from the nodes at its depth (rebuild_start_table, before
/// each update's insertion), enters those made since (child_or_new), and is set aside by a new
/// placement. The nodes and points are read and
/// written through their stores' own interfaces (core/storage/).
class TreeStorage {
 public:
  /// An empty tree's storage under `config`, which must have passed Config::validate().
  explicit TreeStorage(const Config& config);
  /// A snapshot's: `live`'s points shared page by page, `nodes` its copy of `live`'s nodes; no
  /// start table or buffers (a snapshot takes no points in).
  TreeStorage(TreeStorage& live, NodeStore copied_nodes);

  // --- fixed by the configuration ---------------------------------------------------------------
  [[nodiscard]] const Config& config() const { return config_; }
  [[nodiscard]] int min_leaf_depth() const { return min_leaf_depth_; }  ///< min_leaf_depth(config)
  /// Quantised mode: every leaf's Node::subcells kept.
  [[nodiscard]] bool keeps_subcells() const { return keeps_subcells_; }
  /// The pages this tree and its snapshots hold.
  [[nodiscard]] const std::shared_ptr<PageLedger>& ledger() const { return ledger_; }

  // --- the stores -------------------------------------------------------------------------------
  [[nodiscard]] NodeStore& nodes() { return nodes_; }
  [[nodiscard]] const NodeStore& nodes() const { return nodes_; }
  [[nodiscard]] PointStore& points() { return points_; }
  [[nodiscard]] const PointStore& points() const { return points_; }
  [[nodiscard]] WorkingBuffers& buffers() { return buffers_; }
  [[nodiscard]] const WorkingBuffers& buffers() const { return buffers_; }

  // --- the root and where it lies ---------------------------------------------------------------
  [[nodiscard]] std::uint32_t root() const { return root_; }
  [[nodiscard]] const Cell& root_cell() const { return root_cell_; }
  [[nodiscard]] const Lattice& lattice() const { return lattice_; }
  void set_root(std::uint32_t id) { root_ = id; }
  /// Places the root's cell under `lattice` (the root node is the caller's to make). The start
  /// table is set aside until rebuilt: its cells were the old placement's.
  void place(const Cell& root_cell, const Lattice& lattice);

  // --- the frame --------------------------------------------------------------------------------
  [[nodiscard]] const AgeLimit& age() const { return age_; }  ///< the current frame's
  void set_age(const AgeLimit& age) { age_ = age; }

  // --- new nodes and the start table -------------------------------------------------------------
  /// The child in `octant` of inner node `id` (cell `cell`), made (inner above min_leaf_depth,
  /// and entered in the start table) if there is none.
  std::uint32_t child_or_new(std::uint32_t id, const Cell& cell, int octant);
  /// Enters node `id` in the start table when `cell` lies at its depth.
  void note_created(std::uint32_t id, const Cell& cell);
  /// Fills the start table at `depth` (0: none; at most kCodeLevels) from the nodes there now.
  void rebuild_start_table(int depth);
  /// The start table's depth: 0 while there is none.
  [[nodiscard]] int start_depth() const { return start_.depth; }
  /// How many cells the table has (8^depth).
  [[nodiscard]] std::size_t start_slots() const { return start_.slots.size(); }
  /// The table's slot of `cell` (at the table's depth): its Morton code below the root, or -1
  /// outside the root.
  [[nodiscard]] std::int64_t start_slot(const Cell& cell) const;
  /// The node entered at `slot`, or kNone.
  [[nodiscard]] std::uint32_t start_node(std::size_t slot) const { return start_.slots[slot]; }
  /// The cell of `slot` (start_slot's inverse).
  [[nodiscard]] Cell start_cell(std::uint32_t slot) const;
  /// The table's bytes.
  [[nodiscard]] std::size_t start_bytes() const { return start_.slots.capacity() * sizeof(std::uint32_t); }

 private:
  /// Nodes at one depth, indexed by their cell: where insertion starts instead of the root.
  struct StartTable {
    int depth = 0;
    std::int64_t per_axis = 1;
    std::vector<std::uint32_t> slots;
  };

  Config config_;
  std::shared_ptr<PageLedger> ledger_;
  NodeStore nodes_;
  PointStore points_;
  std::uint32_t root_ = kNone;
  Cell root_cell_;
  Lattice lattice_;
  int min_leaf_depth_ = 0;
  bool keeps_subcells_ = false;
  AgeLimit age_;
  StartTable start_;
  WorkingBuffers buffers_;
};

}  // namespace eco::detail
