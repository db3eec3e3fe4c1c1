#include "update/stages.hpp"

#include <cmath>
#include <utility>

namespace eco::detail {
namespace {

/// Where the root cell and the lattice go for the current pose.
std::pair<Cell, Lattice> root_for(const Tree& t, const Motion& motion) {
  const Config& cfg = t.config();
  Lattice lattice = t.lattice();
  Cell cell;
  const int depth = lattice.max_depth;
  if (cfg.recentring == Recentring::Quantised) {
    const int k = int(cfg.quantum_levels);
    const double q = cfg.quantum();
    lattice.unit = std::ldexp(q, k - depth);
    for (int a = 0; a < 3; ++a) {
      lattice.origin[a] = -motion.anchor[a];
      const std::int64_t m = std::llround(motion.pose.translation()[a] / q);
      cell.lo[a] = (m - (std::int64_t{1} << (k - 1))) * (std::int64_t{1} << (depth - k));
    }
  } else {
    lattice.unit = std::ldexp(cfg.box_side, -depth);
    lattice.origin = motion.box.lo;
  }
  return {cell, lattice};
}

}  // namespace

std::vector<StoredPoint> refine_overlap(Tree& tree, const Motion& motion, std::vector<StoredPoint> displaced,
                                        UpdateStats& stats) {
  const auto [new_root, lattice] = root_for(tree, motion);
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
