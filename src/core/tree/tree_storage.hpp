#pragma once
// What a tree is made of — its nodes, its leaves' points, its root and lattice, the start table
// insertion starts from, its working buffers — and the one primitive
// that keeps these agreeing as nodes are made (a new node at the start depth enters the table).
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

/// Nodes at one depth, indexed by their cell: where insertion starts instead of the root.
struct StartTable {
  int depth = 0;
  std::int64_t per_axis = 1;
  std::vector<std::uint32_t> slots;
};

struct TreeStorage {
  /// An empty tree's storage under `config`, which must have passed Config::validate().
  explicit TreeStorage(const Config& config);
  /// A snapshot's: `live`'s points shared page by page, `nodes` its copy of `live`'s nodes; no
  /// start table or buffers (a snapshot takes no points in).
  TreeStorage(TreeStorage& live, NodeStore copied_nodes);

  /// The child in `octant` of inner node `id` (cell `cell`), made (inner above min_leaf_depth,
  /// and entered in the start table) if there is none.
  std::uint32_t child_or_new(std::uint32_t id, const Cell& cell, int octant);
  /// Enters node `id` in the start table when `cell` lies at its depth.
  void note_created(std::uint32_t id, const Cell& cell);
  /// The start table's slot of `cell` (at the table's depth): its Morton code below the root, or
  /// -1 outside the root.
  [[nodiscard]] std::int64_t start_slot(const Cell& cell) const;

  Config config;
  std::shared_ptr<PageLedger> ledger;  ///< the pages this tree and its snapshots hold
  NodeStore nodes;
  PointStore points;
  std::uint32_t root = kNone;
  Cell root_cell;
  Lattice lattice;
  int min_leaf_depth = 0;       ///< min_leaf_depth(config)
  bool keeps_subcells = false;  ///< Quantised mode: every leaf's Node::subcells kept
  AgeLimit age;                 ///< the current frame's
  StartTable start;
  WorkingBuffers buffers;
};

}  // namespace eco::detail
