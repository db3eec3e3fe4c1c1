#pragma once
// The walk that takes points out of the tree in place (shift-out, free-space clearing): a filter
// judges each subtree by its node — keep it whole, drop it whole, or look inside — and filters
// the leaves it looks into; the walk refits what changed, collapses inner nodes left with few
// points and releases emptied ones.

#include "core/tree.hpp"

namespace eco::detail {

enum class Verdict { KeepAll, DropAll, LookInside };

/// What a filter did to a subtree.
enum class Filtered { Unchanged, Changed, Gone };

/// `filter` provides Verdict judge(std::uint32_t id, const Node&), void drop(std::uint32_t id) (the subtree
/// leaves the tree) and bool filter_leaf(std::uint32_t id) (keeps some of the leaf's points and
/// refits it; false when it kept them all and left the leaf untouched). Only what changed is
/// refitted; the root is never released (Gone: it holds nothing now).
template <class Filter>
Filtered filter_subtree(Tree& t, std::uint32_t id, Filter& filter) {
  const Node& n = t.nodes()[id];
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
    t.nodes().for_each_child(id, [&](int o, std::uint32_t ch) {
      const Filtered below = filter_subtree(t, ch, filter);
      if (below == Filtered::Gone) t.unlink_child(id, o);
      changed = changed || below != Filtered::Unchanged;
    });
    if (!changed) return Filtered::Unchanged;
    t.refit(id);
    if (t.nodes()[id].count > 0) t.collapse_if_small(id);
  }
  if (t.nodes()[id].count == 0 && id != t.root()) {
    t.dissolve(id, nullptr);
    return Filtered::Gone;
  }
  return t.nodes()[id].count == 0 ? Filtered::Gone : Filtered::Changed;
}

}  // namespace eco::detail
