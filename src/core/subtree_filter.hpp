#pragma once
// Tree::filter, the walk that takes points out of the tree in place (shift-out, free-space
// clearing): a filter judges each subtree by its node — keep it whole, drop it whole, or look
// inside — and filters the leaves it looks into; the walk refits what changed, collapses inner
// nodes left with few points and releases emptied ones.
//
// A filter provides Verdict judge(std::uint32_t id, const Node&), void drop(std::uint32_t id)
// (the subtree leaves the tree: Tree::drop) and bool filter_leaf(std::uint32_t id) (keeps some
// of the leaf's points and refits it: Tree::filter_leaf or Tree::retain; false when it kept them
// all and left the leaf untouched).

#include "core/tree.hpp"

namespace eco::detail {

template <class Filter>
void Tree::filter(Filter& filter) {
  if (root_ == kNone) return;
  if (filter_below(root_, filter) == Filtered::Gone) place_root(root_cell_, lattice_);  // everything left
}

template <class Filter>
Tree::Filtered Tree::filter_below(std::uint32_t id, Filter& filter) {
  const Node& n = nodes_[id];
  if (n.count == 0) return Filtered::Unchanged;
  const Verdict verdict = filter.judge(id, n);
  if (verdict == Verdict::KeepAll) return Filtered::Unchanged;
  if (verdict == Verdict::DropAll) {
    filter.drop(id);
    return Filtered::Gone;
  }
  if (n.leaf) {
    if (!filter.filter_leaf(id)) return Filtered::Unchanged;
  } else {
    bool changed = false;
    nodes_.for_each_child(id, [&](int o, std::uint32_t ch) {
      const Filtered below = filter_below(ch, filter);
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
