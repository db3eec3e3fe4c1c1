#include "update/stages.hpp"

namespace eco::detail {
namespace {

class Pruner {
 public:
  Pruner(Tree& tree, const Box& box, UpdateStats& stats)
      : t_(tree), box_(box), stats_(stats), cutoff_(tree.age_cutoff()) {}

  /// Prunes the subtree at id; returns true when the node itself is gone.
  bool prune(std::uint32_t id) {
    const Node& n = t_.nodes()[id];
    if (n.count == 0) return false;
    if (n.oldest >= cutoff_ && box_.contains_all(n.bounds)) return false;
    if (box_.misses(n.bounds)) {
      t_.drop(id, stats_);
      return true;
    }
    if (n.leaf) {
      t_.filter_leaf(id, box_, stats_);
    } else {
      for (int o = 0; o < 8; ++o) {
        const std::uint32_t ch = t_.nodes().child(id, o);
        if (ch != kNone && prune(ch)) t_.unlink_child(id, o);
      }
      t_.refit(id);
      if (t_.nodes()[id].count > 0 && t_.should_collapse(id)) t_.collapse(id);
    }
    if (t_.nodes()[id].count == 0 && id != t_.root()) {
      t_.dissolve(id, nullptr);
      return true;
    }
    return false;
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
  if (Pruner(tree, motion.box, stats).prune(tree.root())) {  // the whole tree left: start afresh
    tree.place_root(tree.root_cell(), tree.lattice());
  }
}

}  // namespace eco::detail
