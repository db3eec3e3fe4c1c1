#include "update/stages.hpp"

#include <cmath>

namespace eco::detail {
namespace {

/// The deepest node whose cell holds all of `search` (points lie in their cells, so every point
/// in `search` is below it).
std::uint32_t enclosing_node(const Tree& tree, const Box& search) {
  std::uint32_t id = tree.root;
  Cell cell = tree.root_cell;
  while (!tree.nodes[id].leaf) {
    const std::int64_t half = tree.lattice.side(cell.depth) / 2;
    int octant = 0;
    for (int a = 0; a < 3; ++a) {
      const double wall = tree.lattice.wall(a, cell.lo[a] + half);
      if (search.lo[a] >= wall) {
        octant |= 1 << a;
      } else if (search.hi[a] >= wall) {
        return id;  // straddles this wall
      }
    }
    const std::uint32_t child = tree.nodes.child(id, octant);
    if (child == kNone) return id;  // nothing there; the walk below finds nothing quickly
    id = child;
    cell = tree.lattice.child(cell, octant);
  }
  return id;
}

}  // namespace

bool density_allows(const Tree& tree, const std::array<float, 3>& p) {
  const double r = tree.cfg.density_cap.cell_size;
  const std::uint32_t limit = tree.cfg.density_cap.max_points;
  std::array<std::int64_t, 3> key{};
  Box search;  // the density cell in the anchor frame, widened so rounding never hides a point
  search.half_open = false;
  for (int a = 0; a < 3; ++a) {
    key[a] = world_grid_index(tree.anchor[a], p[a], r);
    const double margin = 1e-6 * (std::abs(tree.anchor[a]) + r + 1.0);
    search.lo[a] = double(key[a]) * r - tree.anchor[a] - margin;
    search.hi[a] = double(key[a] + 1) * r - tree.anchor[a] + margin;
  }
  std::uint32_t found = 0;
  auto visit = [&](auto&& self, std::uint32_t id) -> bool {  // true once the cap is reached
    const Node& n = tree.nodes[id];
    if (n.count == 0 || search.misses(n.bounds)) return false;
    if (!n.leaf) {
      for (int o = 0; o < 8; ++o) {
        const std::uint32_t ch = tree.nodes.child(id, o);
        if (ch != kNone && self(self, ch)) return true;
      }
      return false;
    }
    tree.points.for_each(n.link, n.count, [&](const StoredPoint& s) {
      if (!search.contains(s.p[0], s.p[1], s.p[2])) return;  // cheap pre-test; floor decides
      bool same = true;
      for (int a = 0; a < 3; ++a) same = same && world_grid_index(tree.anchor[a], s.p[a], r) == key[a];
      found += same ? 1 : 0;
    });
    return found >= limit;
  };
  return !visit(visit, enclosing_node(tree, search));
}

}  // namespace eco::detail
