#pragma once
// The walk that takes points out of the tree in place (shift-out, free-space clearing): a filter
// judges each subtree by its node — keep it whole, drop it whole, or look inside — and filters
// the leaves it looks into; the walk refits what changed, collapses inner nodes left with few
// points and releases emptied ones.

#include "core/tree.hpp"

namespace eco::detail {

enum class Verdict { KeepAll, DropAll, LookInside };

/// `filter` provides Verdict judge(const Node&), void drop(std::uint32_t id) (the subtree
/// leaves the tree) and void filter_leaf(std::uint32_t id) (keeps some of the leaf's points).
/// Returns true when the subtree at `id` is gone (released; the root never is).
template <class Filter>
bool filter_subtree(Tree& t, std::uint32_t id, Filter& filter) {
  const Node& n = t.nodes()[id];
  if (n.count == 0) return false;
  const Verdict verdict = filter.judge(n);
  if (verdict == Verdict::KeepAll) return false;
  if (verdict == Verdict::DropAll) {
    filter.drop(id);
    return true;
  }
  if (n.leaf) {
    filter.filter_leaf(id);
  } else {
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = t.nodes().child(id, o);
      if (ch != kNone && filter_subtree(t, ch, filter)) t.unlink_child(id, o);
    }
    t.refit(id);
    if (t.nodes()[id].count > 0 && t.should_collapse(id)) t.collapse(id);
  }
  if (t.nodes()[id].count == 0 && id != t.root()) {
    t.dissolve(id, nullptr);
    return true;
  }
  return false;
}

}  // namespace eco::detail
