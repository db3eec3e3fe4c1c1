#include "update/stages.hpp"

#include <cmath>
#include <utility>

namespace eco::detail {
namespace {

/// Where the root cell and the lattice go for the current pose.
std::pair<Cell, Lattice> place_root(const Tree& t, const Motion& motion) {
  Lattice lattice = t.lattice;
  Cell cell;
  const int depth = lattice.max_depth;
  if (t.cfg.recentring == Recentring::Quantised) {
    const int k = int(t.cfg.quantum_levels);
    const double q = t.cfg.quantum();
    lattice.unit = std::ldexp(q, k - depth);
    for (int a = 0; a < 3; ++a) {
      lattice.origin[a] = -motion.anchor[a];
      const std::int64_t m = std::llround(motion.pose.translation()[a] / q);
      cell.lo[a] = (m - (std::int64_t{1} << (k - 1))) * (std::int64_t{1} << (depth - k));
    }
  } else {
    lattice.unit = std::ldexp(t.cfg.box_side, -depth);
    lattice.origin = motion.box.lo;
  }
  return {cell, lattice};
}

// --- Quantised: re-link the depth-k subtrees ---------------------------------------------------

class Relinker {
 public:
  Relinker(Tree& tree, std::vector<StoredPoint>& displaced)
      : t_(tree), displaced_(displaced), k_(int(tree.cfg.quantum_levels)) {}

  void run(const Cell& new_root) {
    collect(t_.root, t_.root_cell);
    t_.root_cell = new_root;
    t_.make_root();
    for (const auto& [id, cell] : subtrees_) {
      if (t_.lattice.encloses(new_root, cell)) {
        attach(id, cell);
        ++t_.last.relinked_subtrees;
      } else {  // cannot hold points after shift-out; dissolved for safety all the same
        t_.dissolve(id, &displaced_);
        ++t_.last.rebuilt_subtrees;
      }
    }
    refit_top(t_.root);
  }

 private:
  /// Records the depth-k subtrees and releases the inner nodes above them.
  void collect(std::uint32_t id, const Cell& cell) {
    if (cell.depth == k_) {
      subtrees_.emplace_back(id, cell);
      return;
    }
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = t_.nodes.child(id, o);
      if (ch != kNone) collect(ch, t_.lattice.child(cell, o));
    }
    t_.nodes.release(id);
  }

  void attach(std::uint32_t id, const Cell& cell) {
    std::uint32_t parent = t_.root;
    Cell at = t_.root_cell;
    while (at.depth < k_ - 1) {
      const int o = t_.lattice.octant_of(at, cell);
      parent = t_.child_or_new(parent, at, o);
      at = t_.lattice.child(at, o);
    }
    const int o = t_.lattice.octant_of(at, cell);
    t_.nodes.child(parent, o) = id;
    t_.nodes[id].parent = parent;
    t_.nodes[id].octant = static_cast<std::uint8_t>(o);
  }

  void refit_top(std::uint32_t id) {
    if (t_.nodes[id].depth >= k_) return;
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = t_.nodes.child(id, o);
      if (ch != kNone) refit_top(ch);
    }
    t_.refit(id);
  }

  Tree& t_;
  std::vector<StoredPoint>& displaced_;
  int k_;
  std::vector<std::pair<std::uint32_t, Cell>> subtrees_;
};

// --- Exact: keep what still fits, rebuild the rest ---------------------------------------------

/// Node id fits `cell` under the new lattice; checks its children against their moved octants.
void refit_exact(Tree& t, std::uint32_t id, const Cell& cell, std::vector<StoredPoint>& displaced) {
  if (t.nodes[id].leaf) return;
  for (int o = 0; o < 8; ++o) {
    const std::uint32_t ch = t.nodes.child(id, o);
    if (ch == kNone) continue;
    const Cell child_cell = t.lattice.child(cell, o);
    if (t.lattice.contains(child_cell, t.nodes[ch].bounds)) {
      refit_exact(t, ch, child_cell, displaced);
      if (t.nodes[ch].count == 0) {  // everything below moved out of its octant
        t.dissolve(ch, nullptr);
        t.nodes.child(id, o) = kNone;
      } else if (id == t.root) {
        ++t.last.relinked_subtrees;
      }
    } else {
      t.dissolve(ch, &displaced);
      t.nodes.child(id, o) = kNone;
      ++t.last.rebuilt_subtrees;
    }
  }
  t.refit(id);
  if (t.should_collapse(id)) t.collapse(id);
}

}  // namespace

std::vector<StoredPoint> refine_overlap(Tree& tree, const Motion& motion, std::vector<StoredPoint> displaced) {
  const auto [new_root, lattice] = place_root(tree, motion);
  if (tree.root == kNone) {
    tree.lattice = lattice;
    tree.root_cell = new_root;
    tree.make_root();
  } else if (tree.cfg.recentring == Recentring::Quantised) {
    if (new_root.lo != tree.root_cell.lo) Relinker(tree, displaced).run(new_root);
  } else if (lattice.origin != tree.lattice.origin) {
    tree.lattice = lattice;
    refit_exact(tree, tree.root, tree.root_cell, displaced);
  }
  return displaced;
}

}  // namespace eco::detail
