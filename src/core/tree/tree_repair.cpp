// Repair (core/tree/tree_repair.hpp): refitting, dissolving, dropping and collapsing subtrees, and the
// re-linking a re-centring does.

#include "core/tree/tree_repair.hpp"

#include "core/density/density_gate.hpp"
#include "core/geometry/subcells.hpp"

#include <algorithm>

namespace eco::detail {

const MappedVector<std::pair<std::uint32_t, Cell>>& TreeRepair::detach_subtrees(int depth) {
  MappedVector<std::pair<std::uint32_t, Cell>>& subtrees = t_.buffers_.detached();
  subtrees.clear();
  auto collect = [&](auto&& self, std::uint32_t id, const Cell& cell) -> void {
    if (cell.depth == depth) {
      subtrees.emplace_back(id, cell);
      return;
    }
    t_.nodes_.for_each_child(id, [&](int o, std::uint32_t ch) { self(self, ch, t_.lattice_.child(cell, o)); });
    t_.nodes_.release(id);
  };
  if (t_.root_ != kNone) collect(collect, t_.root_, t_.root_cell_);
  t_.root_ = kNone;
  return subtrees;
}

void TreeRepair::attach_subtree(std::uint32_t id, const Cell& cell) {
  std::uint32_t parent = t_.root_;
  Cell at = t_.root_cell_;
  while (at.depth < cell.depth - 1) {
    const int o = t_.lattice_.octant_of(at, cell);
    parent = t_.child_or_new(parent, at, o);
    at = t_.lattice_.child(at, o);
  }
  const int o = t_.lattice_.octant_of(at, cell);
  t_.nodes_.edit_child(parent, o) = id;
  Node& n = t_.nodes_.edit(id);
  n.parent = parent;
  n.octant = static_cast<std::uint8_t>(o);
}

void TreeRepair::refit_moved(std::uint32_t id, const Cell& cell, std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  if (t_.nodes_[id].leaf) return;
  t_.nodes_.for_each_child(id, [&](int o, std::uint32_t ch) {
    const Cell child_cell = t_.lattice_.child(cell, o);
    const bool fits = t_.lattice_.contains(child_cell, t_.nodes_[ch].bounds);
    if (fits) refit_moved(ch, child_cell, displaced, stats);
    if (fits && t_.nodes_[ch].count > 0) {
      if (id == t_.root_) ++stats.relinked_subtrees;
      return;
    }
    // everything below moved out of its octant, or the subtree no longer fits it
    if (!fits) ++stats.rebuilt_subtrees;
    dissolve(ch, fits ? nullptr : &displaced);
    t_.nodes_.edit_child(id, o) = kNone;
  });
  refit(id);
  collapse_if_small(id);
}

void TreeRepair::refit_above(int depth) {
  auto walk = [&](auto&& self, std::uint32_t id) -> void {
    if (t_.nodes_[id].depth >= depth) return;
    t_.nodes_.for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
    refit(id);
  };
  if (t_.root_ != kNone) walk(walk, t_.root_);
}

void TreeRepair::refit(std::uint32_t id) {
  const Node& n = t_.nodes_[id];
  if (n.leaf) {
    // a point names its leaf's cell, whose subcells a leaf keeps in Quantised mode
    const PointSpan s = t_.points_.span(n.link, n.count);
    const bool marks = t_.keeps_subcells_ && n.count > 0;
    fit_leaf(id, marks ? Subcells(t_.lattice_, t_.lattice_.cell_at(n.depth, {s.x[0], s.y[0], s.z[0]})) : Subcells());
    return;
  }
  Aabb bounds;
  std::uint32_t oldest = kNone;
  std::uint32_t count = 0;
  t_.nodes_.for_each_child(id, [&](int, std::uint32_t ch) {
    count += t_.nodes_[ch].count;
    bounds.merge(t_.nodes_[ch].bounds);
    oldest = std::min(oldest, t_.nodes_[ch].oldest);
  });
  Node& fitted = t_.nodes_.edit(id);
  fitted.count = count;
  fitted.bounds = bounds;
  fitted.oldest = oldest;
}

void TreeRepair::fit_leaf(std::uint32_t id, const Subcells& quarters) {
  Node& n = t_.nodes_.edit(id);
  const PointSpan s = t_.points_.span(n.link, n.count);
  // column by column, each loop vector code; the age keys read only where a column holds them
  Aabb bounds;
  for (std::uint32_t i = 0; i < n.count; ++i) bounds.grow(s.x[i], s.y[i], s.z[i]);
  const bool aged = s.stamps != nullptr || s.times != nullptr;
  std::uint32_t oldest = n.count > 0 && !aged ? t_.age_.key(StoredPoint{}) : kNone;
  if (aged) {
    for (std::uint32_t i = 0; i < n.count; ++i) oldest = std::min(oldest, t_.age_.key(s[i]));
  }
  std::uint64_t subcells = 0;
  if (t_.keeps_subcells_) {
    for (std::uint32_t i = 0; i < n.count; ++i) subcells |= std::uint64_t{1} << quarters.of({s.x[i], s.y[i], s.z[i]});
  }
  n.set_subcells(subcells);
  n.bounds = bounds;
  n.oldest = oldest;
}

void TreeRepair::dissolve(std::uint32_t id, std::vector<StoredPoint>* out) {
  if (id == t_.root_) t_.root_ = kNone;
  Node& n = t_.nodes_.edit(id);
  if (n.leaf) {
    if (out) {
      t_.points_.drain(n.link, n.count, *out);
    } else {
      t_.points_.release(n.link);
    }
  } else {
    t_.nodes_.for_each_child(id, [&](int, std::uint32_t ch) { dissolve(ch, out); });
  }
  t_.nodes_.release(id);
}

void TreeRepair::drop(std::uint32_t id, UpdateStats& stats) {
  stats.pruned += t_.nodes_[id].count;
  if (t_.cfg_.density_cap.enabled()) {
    forget_in_groups(t_.density_, t_.density_grid_,
                     [&](auto&& offer) { walk_points(id, [&](const StoredPoint& s) { offer(s.p); }); });
  }
  dissolve(id, nullptr);
}

bool TreeRepair::collapse_if_small(std::uint32_t id) {
  if (!should_collapse(id)) return false;
  collapse(id);
  return true;
}

bool TreeRepair::should_collapse(std::uint32_t id) const {
  const Node& n = t_.nodes_[id];
  return !n.leaf && n.depth >= t_.min_leaf_depth_ && n.count <= t_.cfg_.leaf_capacity;
}

void TreeRepair::collapse(std::uint32_t id) {
  std::vector<StoredPoint>& scratch = t_.buffers_.collapsed();
  const std::size_t base = scratch.size();
  t_.nodes_.for_each_child(id, [&](int, std::uint32_t ch) { dissolve(ch, &scratch); });
  t_.nodes_.make_leaf_of_inner(id);
  Node& n = t_.nodes_.edit(id);
  n.count = 0;
  t_.points_.append(n.link, id, 0, scratch.data() + base, scratch.data() + scratch.size());
  n.count = std::uint32_t(scratch.size() - base);
  scratch.resize(base);
  refit(id);  // its subcells (bounds and ages as its children's were)
}

}  // namespace eco::detail
