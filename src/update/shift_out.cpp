#include "update/stages.hpp"
#include "core/subtree_filter.hpp"

namespace eco::detail {
namespace {

/// Shift-out's judgement: subtrees wholly in the box and young enough stay whole, subtrees wholly
/// outside leave whole, the others are looked into point by point.
class Pruner {
 public:
  Pruner(Tree& tree, const Box& box, UpdateStats& stats)
      : t_(tree), box_(box), stats_(stats), cutoff_(tree.age_limit().cutoff) {}

  [[nodiscard]] Verdict judge(std::uint32_t, const Node& n) const {
    if (n.oldest >= cutoff_ && box_.contains_all(n.bounds)) return Verdict::KeepAll;
    if (box_.misses(n.bounds)) return Verdict::DropAll;
    return Verdict::LookInside;
  }
  bool filter_leaf(std::uint32_t id) {
    t_.retain(id, [&](const StoredPoint& s) { return !leaves(t_, s, box_, stats_); });
    return true;  // judged LookInside: it straddles the box's walls or holds aged points
  }

 private:
  Tree& t_;
  const Box& box_;
  UpdateStats& stats_;
  std::uint32_t cutoff_ = 0;
};

}  // namespace

void prune_shift_out(Tree& tree, const Motion& motion, UpdateStats& stats) {
  if (tree.root() == kNone) return;
  Pruner pruner(tree, motion.box, stats);
  tree.filter(pruner, stats);
}

bool leaves(const Tree& tree, const StoredPoint& s, const Box& box, UpdateStats& stats) {
  if (box.contains(s.p[0], s.p[1], s.p[2]) && tree.age_limit().admits(s)) return false;
  ++(box.contains(s.p[0], s.p[1], s.p[2]) ? stats.aged_out : stats.pruned);
  return true;
}

}  // namespace eco::detail
