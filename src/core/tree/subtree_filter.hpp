#pragma once
// Tree::filter, the walk that takes points out of the tree in place (shift-out, free-space
// clearing): a filter judges each subtree by its node — keep it whole, drop it whole, or look
// inside — and filters the leaves it looks into; the walk refits what changed, collapses inner
// nodes left with few points and releases emptied ones.
//
// A filter provides Verdict judge(std::uint32_t id, const Node&) and bool filter_leaf(std::uint32_t
// id) (keeps some of the leaf's points and refits it: Tree::retain; false when it kept them all
// and left the leaf untouched). A subtree judged DropAll leaves the tree whole.

#include "core/density/density_cells.hpp"
#include "core/tree/tree.hpp"
#include "core/tree/tree_repair.hpp"

namespace eco::detail {

/// A filter's verdict on a subtree: keep it whole, drop it whole, or look inside.
enum class Verdict { KeepAll, DropAll, LookInside };

namespace filtering {

enum class Filtered { Unchanged, Changed, Gone };  // what filter_below did to a subtree

template <class Filter>
Filtered filter_below(const Tree& tree, TreeRepair& repair, std::uint32_t id, Filter& filter, UpdateStats& stats,
                      DensityCells* density) {
  const NodeStore& nodes = tree.nodes();
  const Node& n = nodes[id];
  if (n.count == 0) return Filtered::Unchanged;
  const Verdict verdict = filter.judge(id, n);
  if (verdict == Verdict::KeepAll) return Filtered::Unchanged;
  if (verdict == Verdict::DropAll) {
    repair.drop(id, stats, density);
    return Filtered::Gone;
  }
  if (n.leaf) {
    if (!filter.filter_leaf(id)) return Filtered::Unchanged;
  } else {
    bool changed = false;
    nodes.for_each_child(id, [&](int, std::uint32_t ch) {  // a child gone is unlinked by its dissolve
      changed = filter_below(tree, repair, ch, filter, stats, density) != Filtered::Unchanged || changed;
    });
    if (!changed) return Filtered::Unchanged;
    repair.refit(id);
    if (nodes[id].count > 0) repair.collapse_if_small(id);
  }
  if (nodes[id].count == 0 && id != tree.root()) {
    repair.dissolve(id, nullptr);
    return Filtered::Gone;
  }
  return nodes[id].count == 0 ? Filtered::Gone : Filtered::Changed;
}

}  // namespace filtering

template <class Filter>
void Tree::filter(Filter& filter, UpdateStats& stats, DensityCells* density) {
  if (s_.root() == kNone) return;
  TreeRepair repair(s_);
  if (filtering::filter_below(*this, repair, s_.root(), filter, stats, density) == filtering::Filtered::Gone) {
    place_root(s_.root_cell(), s_.lattice());  // everything left
  }
}

template <class Keep>
void Tree::retain(std::uint32_t id, Keep&& keep, DensityCells* density) {
  Node& n = s_.nodes().edit(id);
  n.count = s_.points().retain(n.link, n.count, [&](const StoredPoint& s) {
    if (keep(s)) return true;
    if (density) density->forget(s.p);
    return false;
  });
  TreeRepair(s_).refit(id);
}

}  // namespace eco::detail
