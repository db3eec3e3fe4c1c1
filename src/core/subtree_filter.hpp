#pragma once
// Tree::filter, the walk that takes points out of the tree in place (shift-out, free-space
// clearing): a filter judges each subtree by its node — keep it whole, drop it whole, or look
// inside — and filters the leaves it looks into; the walk refits what changed, collapses inner
// nodes left with few points and releases emptied ones.
//
// A filter provides Verdict judge(std::uint32_t id, const Node&) and bool filter_leaf(std::uint32_t
// id) (keeps some of the leaf's points and refits it: Tree::retain; false when it kept them all
// and left the leaf untouched). A subtree judged DropAll leaves the tree whole.

#include "core/tree.hpp"

namespace eco::detail {

template <class Filter>
void Tree::filter(Filter& filter, UpdateStats& stats) {
  if (root_ == kNone) return;
  if (filter_below(root_, filter, stats) == Filtered::Gone) place_root(root_cell_, lattice_);  // everything left
}

template <class Filter>
Tree::Filtered Tree::filter_below(std::uint32_t id, Filter& filter, UpdateStats& stats) {
  const Node& n = nodes_[id];
  if (n.count == 0) return Filtered::Unchanged;
  const Verdict verdict = filter.judge(id, n);
  if (verdict == Verdict::KeepAll) return Filtered::Unchanged;
  if (verdict == Verdict::DropAll) {
    drop(id, stats);
    return Filtered::Gone;
  }
  if (n.leaf) {
    if (!filter.filter_leaf(id)) return Filtered::Unchanged;
  } else {
    bool changed = false;
    nodes_.for_each_child(id, [&](int o, std::uint32_t ch) {
      const Filtered below = filter_below(ch, filter, stats);
      if (below == Filtered::Gone) unlink_child(id, o);
      changed = changed || below != Filtered::Unchanged;
    });
    if (!changed) return Filtered::Unchanged;
    refit(id);
    if (nodes_[id].count > 0) collapse_if_small(id);
  }
  if (nodes_[id].count == 0 && id != root_) {
    dissolve(id, nullptr);
    return Filtered::Gone;
  }
  return nodes_[id].count == 0 ? Filtered::Gone : Filtered::Changed;
}

}  // namespace eco::detail
