#include "update/stages.hpp"
#include "core/tree/subtree_filter.hpp"

namespace eco::detail {
namespace {

/// Shift-out's judgement: subtrees wholly in the box (and the region, when it is not the cube) and
/// young enough stay whole, subtrees wholly outside leave whole, the others are looked into point
/// by point.
class Pruner {
 public:
  Pruner(Tree& tree, DensityCells* density, const Motion& motion, UpdateStats& stats)
      : t_(tree), density_(density), motion_(motion), stats_(stats), cutoff_(tree.age_limit().cutoff) {}

  [[nodiscard]] Verdict judge(std::uint32_t, const Node& n) const {
    const EgoRegion* region = moved_region();
    if (motion_.box.misses(n.bounds) || (region && region->misses(n.bounds))) return Verdict::DropAll;
    if (box_keeps(n) && (!region || region->contains_all(n.bounds))) return Verdict::KeepAll;
    return Verdict::LookInside;
  }
  bool filter_leaf(std::uint32_t id) {
    const Node& n = t_.nodes()[id];
    if (box_keeps(n)) stats_.region_tested += n.count;  // looked into for the region's surface alone
    t_.retain(id, [&](const StoredPoint& s) { return !leaves(t_, s, motion_, stats_); }, density_);
    return true;  // judged LookInside: it straddles the box's or the region's surface, or holds aged points
  }

 private:
  /// The region when it moved: otherwise every held point lies in it already.
  [[nodiscard]] const EgoRegion* moved_region() const { return motion_.region_moved ? &*motion_.region : nullptr; }
  [[nodiscard]] bool box_keeps(const Node& n) const { return n.oldest >= cutoff_ && motion_.box.contains_all(n.bounds); }

  Tree& t_;
  DensityCells* density_;
  const Motion& motion_;
  UpdateStats& stats_;
  std::uint32_t cutoff_ = 0;
};

}  // namespace

void prune_shift_out(Tree& tree, DensityCells* density, const Motion& motion, UpdateStats& stats) {
  if (tree.root() == kNone) return;
  Pruner pruner(tree, density, motion, stats);
  tree.filter(pruner, stats, density);
}

bool leaves(const Tree& tree, const StoredPoint& s, const Motion& motion, UpdateStats& stats) {
  const bool inside = motion.box.contains(s.p[0], s.p[1], s.p[2]) && (!motion.region_moved || motion.region->contains(s.p));
  if (inside && tree.age_limit().admits(s)) return false;
  ++(inside ? stats.aged_out : stats.pruned);
  return true;
}

}  // namespace eco::detail
