// Repair (core/tree/tree_repair.hpp): refitting, dissolving, dropping and collapsing subtrees, and the
// re-linking a re-centring does.

#include "core/tree/tree_repair.hpp"

#include "core/density/density_cells.hpp"
#include "core/geometry/subcells.hpp"

#include <algorithm>

namespace eco::detail {

const MappedVector<std::pair<std::uint32_t, Cell>>& TreeRepair::detach_subtrees(int depth) {
  MappedVector<std::pair<std::uint32_t, Cell>>& subtrees = t_.buffers().detached();
  subtrees.clear();
  auto collect = [&](auto&& self, std::uint32_t id, const Cell& cell) -> void {
    if (cell.depth == depth) {
      subtrees.emplace_back(id, cell);
      t_.nodes().edit(id).parent = kNone;
      return;
    }
    t_.nodes().for_each_child(id, [&](int o, std::uint32_t ch) { self(self, ch, t_.lattice().child(cell, o)); });
    t_.nodes().release(id);
  };
  if (t_.root() != kNone) collect(collect, t_.root(), t_.root_cell());
  t_.set_root(kNone);
  return subtrees;
}

void TreeRepair::attach_subtree(std::uint32_t id, const Cell& cell) {
  std::uint32_t parent = t_.root();
  Cell at = t_.root_cell();
  while (at.depth < cell.depth - 1) {
    const int o = t_.lattice().octant_of(at, cell);
    parent = t_.child_or_new(parent, at, o);
    at = t_.lattice().child(at, o);
  }
  const int o = t_.lattice().octant_of(at, cell);
  t_.nodes().edit_child(parent, o) = id;
  Node& n = t_.nodes().edit(id);
  n.parent = parent;
  n.octant = static_cast<std::uint8_t>(o);
}

void TreeRepair::refit_moved(std::uint32_t id, const Cell& cell, std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  if (t_.nodes()[id].leaf) return;
  t_.nodes().for_each_child(id, [&](int o, std::uint32_t ch) {
    const Cell child_cell = t_.lattice().child(cell, o);
    const bool fits = t_.lattice().contains(child_cell, t_.nodes()[ch].bounds);
    if (fits) refit_moved(ch, child_cell, displaced, stats);
    if (fits && t_.nodes()[ch].count > 0) {
      if (id == t_.root()) ++stats.relinked_subtrees;
      return;
    }
    // everything below moved out of its octant, or the subtree no longer fits it
    if (!fits) ++stats.rebuilt_subtrees;
    dissolve(ch, fits ? nullptr : &displaced);
  });
  refit(id);
  collapse_if_small(id);
}

void TreeRepair::refit_above(int depth) {
  auto walk = [&](auto&& self, std::uint32_t id) -> void {
    if (t_.nodes()[id].depth >= depth) return;
    t_.nodes().for_each_child(id, [&](int, std::uint32_t ch) { self(self, ch); });
    refit(id);
  };
  if (t_.root() != kNone) walk(walk, t_.root());
}

void TreeRepair::refit(std::uint32_t id) {
  const Node& n = t_.nodes()[id];
  if (n.leaf) {
    // a point names its leaf's cell, whose subcells a leaf keeps in Quantised mode
    const PointSpan s = t_.points().span(n.link, n.count);
    const bool marks = t_.keeps_subcells() && n.count > 0;
    fit_leaf(id, marks ? Subcells(t_.lattice(), t_.lattice().cell_at(n.depth, {s.x[0], s.y[0], s.z[0]})) : Subcells());
    return;
  }
  Aabb bounds;
  std::uint32_t oldest = kNone;
  std::uint32_t count = 0;
  t_.nodes().for_each_child(id, [&](int, std::uint32_t ch) {
    count += t_.nodes()[ch].count;
    bounds.merge(t_.nodes()[ch].bounds);
    oldest = std::min(oldest, t_.nodes()[ch].oldest);
  });
  Node& fitted = t_.nodes().edit(id);
  fitted.count = count;
  fitted.bounds = bounds;
  fitted.oldest = oldest;
}

void TreeRepair::fit_leaf(std::uint32_t id, const Subcells& quarters, const std::optional<Aabb>& known) {
  Node& n = t_.nodes().edit(id);
  const PointSpan s = t_.points().span(n.link, n.count);
  // column by column, each loop vector code; the age keys read only where a column holds them
  Aabb bounds;
  if (known) {
    bounds = *known;
  } else {
    for (std::uint32_t i = 0; i < n.count; ++i) bounds.grow(s.x[i], s.y[i], s.z[i]);
  }
  const bool aged = s.stamps != nullptr || s.times != nullptr;
  std::uint32_t oldest = n.count > 0 && !aged ? t_.age().key(StoredPoint{}) : kNone;
  if (aged) {
    for (std::uint32_t i = 0; i < n.count; ++i) oldest = std::min(oldest, t_.age().key(s[i]));
  }
  std::uint64_t subcells = 0;
  if (t_.keeps_subcells()) {
    for (std::uint32_t i = 0; i < n.count; ++i) subcells |= std::uint64_t{1} << quarters.of({s.x[i], s.y[i], s.z[i]});
  }
  n.set_subcells(subcells);
  n.bounds = bounds;
  n.oldest = oldest;
}

void TreeRepair::dissolve(std::uint32_t id, std::vector<StoredPoint>* out) {
  if (id == t_.root()) t_.set_root(kNone);
  const Node& n = t_.nodes()[id];
  if (n.parent != kNone) t_.nodes().edit_child(n.parent, n.octant) = kNone;
  release_subtree(id, out);
}

void TreeRepair::release_subtree(std::uint32_t id, std::vector<StoredPoint>* out) {
  Node& n = t_.nodes().edit(id);
  if (n.leaf) {
    if (out) {
      t_.points().drain(n.link, n.count, *out);
    } else {
      t_.points().release(n.link);
    }
  } else {
    t_.nodes().for_each_child(id, [&](int, std::uint32_t ch) { release_subtree(ch, out); });
  }
  t_.nodes().release(id);
}

void TreeRepair::drop(std::uint32_t id, UpdateStats& stats, DensityCells* density) {
  stats.pruned += t_.nodes()[id].count;
  if (density) density->forget_all([&](auto&& offer) { walk_points(id, [&](const StoredPoint& s) { offer(s.p); }); });
  dissolve(id, nullptr);
}

bool TreeRepair::collapse_if_small(std::uint32_t id) {
  if (!should_collapse(id)) return false;
  collapse(id);
  return true;
}

bool TreeRepair::should_collapse(std::uint32_t id) const {
  const Node& n = t_.nodes()[id];
  return !n.leaf && n.depth >= t_.min_leaf_depth() && n.count <= t_.config().leaf_capacity;
}

void TreeRepair::collapse(std::uint32_t id) {
  std::vector<StoredPoint>& scratch = t_.buffers().collapsed();
  const std::size_t base = scratch.size();
  t_.nodes().for_each_child(id, [&](int, std::uint32_t ch) { dissolve(ch, &scratch); });
  t_.nodes().make_leaf_of_inner(id);
  Node& n = t_.nodes().edit(id);
  n.count = 0;
  t_.points().append(n.link, id, 0, scratch.data() + base, scratch.data() + scratch.size());
  n.count = std::uint32_t(scratch.size() - base);
  scratch.resize(base);
  refit(id);  // its subcells (bounds and ages as its children's were)
}

}  // namespace eco::detail
