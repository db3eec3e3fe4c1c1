// The tree's storage (tree_storage.hpp): its construction, new children and the start table.

#include "core/tree/tree_storage.hpp"

#include "core/geometry/cell_codes.hpp"

#include <utility>

namespace eco::detail {

TreeStorage::TreeStorage(const Config& c)
    : config(c),
      ledger(std::make_shared<PageLedger>()),
      points(kept_columns(c), ledger),
      min_leaf_depth(detail::min_leaf_depth(c)),
      keeps_subcells(c.recentring == Recentring::Quantised) {
  lattice.max_depth = c.max_depth();
}

TreeStorage::TreeStorage(TreeStorage& live, NodeStore copied_nodes)
    : config(live.config),
      ledger(live.ledger),
      nodes(std::move(copied_nodes)),
      points(live.points.share()),
      root(live.root),
      root_cell(live.root_cell),
      lattice(live.lattice),
      min_leaf_depth(live.min_leaf_depth),
      keeps_subcells(live.keeps_subcells),
      age(live.age) {}

std::uint32_t TreeStorage::child_or_new(std::uint32_t id, const Cell& cell, int octant) {
  std::uint32_t ch = nodes.child(id, octant);
  if (ch != kNone) return ch;
  const int depth = cell.depth + 1;
  ch = nodes.make_leaf(id, octant, depth);
  nodes.edit_child(id, octant) = ch;
  if (depth < min_leaf_depth) nodes.make_inner(ch);
  note_created(ch, lattice.child(cell, octant));
  return ch;
}

std::int64_t TreeStorage::start_slot(const Cell& cell) const {
  const int log2_side = lattice.max_depth - start.depth;
  std::uint32_t slot = 0;  // the cell's Morton code below the root: a start cell's points are found by theirs
  for (int a = 0; a < 3; ++a) {
    const std::int64_t rel = (cell.lo[a] - root_cell.lo[a]) >> log2_side;  // a division by side(start depth)
    if (cell.lo[a] < root_cell.lo[a] || rel >= start.per_axis) return -1;
    slot |= spread_bits(std::uint32_t(rel)) << a;
  }
  return slot;
}

void TreeStorage::note_created(std::uint32_t id, const Cell& cell) {
  if (start.depth == 0 || cell.depth != start.depth) return;
  const std::int64_t slot = start_slot(cell);
  if (slot >= 0) start.slots[std::size_t(slot)] = id;
}

}  // namespace eco::detail
