#pragma once
// The operations that put a tree's structure right after points left or its lattice moved:
// refitting a node from what lies below it, dissolving and dropping subtrees, collapsing inner
// nodes left with few points, and re-linking the subtrees a re-centring keeps. They work on a
// tree's storage (core/tree/tree_storage.hpp), and keep its invariants only as Tree's operations
// compose them.

#include "core/tree/tree_storage.hpp"

#include <eco/types.hpp>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace eco::detail {

class DensityCells;

class Subcells;

class TreeRepair {
 public:
  explicit TreeRepair(TreeStorage& storage) : t_(storage) {}

  /// Recomputes count, bounds and oldest stamp of `id` from its points or children.
  void refit(std::uint32_t id);
  /// The same for leaf `id`, whose cell's subcells are `quarters` (kept in Quantised mode), and
  /// whose points' bounds are `bounds` where the caller has them already.
  void fit_leaf(std::uint32_t id, const Subcells& quarters, const std::optional<Aabb>& bounds = std::nullopt);
  /// Releases the subtree at `id` (and the node itself, unlinked from its parent; the root leaves
  /// the tree without one); appends its points to `out` if given.
  void dissolve(std::uint32_t id, std::vector<StoredPoint>* out);
  /// Releases the subtree at `id` whose points leave the tree (counted as pruned, and forgotten
  /// in `density`).
  void drop(std::uint32_t id, UpdateStats& stats, DensityCells* density);
  /// Turns inner node `id` into one leaf holding all the points below it when they are so few
  /// that it should be one (at most N_max, below the lattice's fixed levels); returns whether it did.
  bool collapse_if_small(std::uint32_t id);
  [[nodiscard]] bool should_collapse(std::uint32_t id) const;
  /// Turns inner node `id` into one leaf holding all the points below it.
  void collapse(std::uint32_t id);

  /// Tree::relink_top's parts: releases the nodes above `depth` and lists the subtrees at `depth`
  /// with their cells, each without a parent (the tree is left without a root); links one under
  /// the root, creating the inner nodes on its way; refits every node above `depth`, bottom up.
  const MappedVector<std::pair<std::uint32_t, Cell>>& detach_subtrees(int depth);
  void attach_subtree(std::uint32_t id, const Cell& cell);
  void refit_above(int depth);
  /// Tree::move_lattice's walk: node `id` fits `cell` under the moved lattice.
  void refit_moved(std::uint32_t id, const Cell& cell, std::vector<StoredPoint>& displaced, UpdateStats& stats);

  /// Calls f(const StoredPoint&) for every point below `id`.
  template <class F>
  void walk_points(std::uint32_t id, F&& f) const {
    const Node& n = t_.nodes()[id];
    if (n.leaf) {
      t_.points().for_each(n.link, n.count, f);
      return;
    }
    t_.nodes().for_each_child(id, [&](int, std::uint32_t ch) { walk_points(ch, f); });
  }

 private:
  /// dissolve's walk: the nodes below `id` go with it, their links with them.
  void release_subtree(std::uint32_t id, std::vector<StoredPoint>* out);

  TreeStorage& t_;
};

}  // namespace eco::detail
