#include "update/stages.hpp"

namespace eco::detail {

std::vector<StoredPoint> refine_overlap(Tree& tree, const Motion& motion, std::vector<StoredPoint> displaced,
                                        UpdateStats& stats) {
  const auto [new_root, lattice] = root_placement(tree.config(), motion);
  if (tree.root() == kNone) {
    tree.place_root(new_root, lattice);
  } else if (tree.config().recentring == Recentring::Quantised) {
    if (new_root.lo != tree.root_cell().lo) tree.relink_top(new_root, int(tree.config().quantum_levels), displaced, stats);
  } else if (lattice.origin != tree.lattice().origin) {
    tree.move_lattice(lattice, displaced, stats);
  }
  return displaced;
}

}  // namespace eco::detail
