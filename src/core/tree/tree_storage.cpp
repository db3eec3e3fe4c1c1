// The tree's storage (tree_storage.hpp): its construction, its root's placement, new children and
// the start table.

#include "core/tree/tree_storage.hpp"

#include "core/geometry/cell_codes.hpp"

#include <cassert>
#include <utility>

namespace eco::detail {

TreeStorage::TreeStorage(const Config& c)
    : config_(c),
      ledger_(std::make_shared<PageLedger>()),
      points_(kept_columns(c), ledger_),
      min_leaf_depth_(detail::min_leaf_depth(c)),
      keeps_subcells_(c.recentring == Recentring::Quantised) {
  lattice_.max_depth = c.max_depth();
}

TreeStorage::TreeStorage(TreeStorage& live, NodeStore copied_nodes)
    : config_(live.config_),
      ledger_(live.ledger_),
      nodes_(std::move(copied_nodes)),
      points_(live.points_.share()),
      root_(live.root_),
      root_cell_(live.root_cell_),
      lattice_(live.lattice_),
      min_leaf_depth_(live.min_leaf_depth_),
      keeps_subcells_(live.keeps_subcells_),
      age_(live.age_) {}

void TreeStorage::place(const Cell& root_cell, const Lattice& lattice) {
  root_cell_ = root_cell;
  lattice_ = lattice;
  start_.depth = 0;
}

std::uint32_t TreeStorage::child_or_new(std::uint32_t id, const Cell& cell, int octant) {
  std::uint32_t ch = nodes_.child(id, octant);
  if (ch != kNone) return ch;
  const int depth = cell.depth + 1;
  ch = nodes_.make_leaf(id, octant, depth);
  nodes_.edit_child(id, octant) = ch;
  if (depth < min_leaf_depth_) nodes_.make_inner(ch);
  note_created(ch, lattice_.child(cell, octant));
  return ch;
}

void TreeStorage::note_created(std::uint32_t id, const Cell& cell) {
  if (start_.depth == 0 || cell.depth != start_.depth) return;
  const std::int64_t slot = start_slot(cell);
  if (slot >= 0) start_.slots[std::size_t(slot)] = id;
}

void TreeStorage::rebuild_start_table(int depth) {
  assert(depth <= kCodeLevels);  // slots are Morton codes (start_slot)
  start_.depth = depth;
  start_.per_axis = std::int64_t{1} << depth;
  start_.slots.assign(depth == 0 ? 0 : std::size_t(start_.per_axis * start_.per_axis * start_.per_axis), kNone);
  if (depth == 0) return;
  auto walk = [&](auto&& self, std::uint32_t id, const Cell& cell) -> void {
    if (cell.depth == depth) {
      note_created(id, cell);
      return;
    }
    if (nodes_[id].leaf) return;
    nodes_.for_each_child(id, [&](int o, std::uint32_t ch) { self(self, ch, lattice_.child(cell, o)); });
  };
  walk(walk, root_, root_cell_);
}

std::int64_t TreeStorage::start_slot(const Cell& cell) const {
  const int log2_side = lattice_.max_depth - start_.depth;
  std::uint32_t slot = 0;  // the cell's Morton code below the root: a start cell's points are found by theirs
  for (int a = 0; a < 3; ++a) {
    const std::int64_t rel = (cell.lo[a] - root_cell_.lo[a]) >> log2_side;  // a division by side(start depth)
    if (cell.lo[a] < root_cell_.lo[a] || rel >= start_.per_axis) return -1;
    slot |= spread_bits(std::uint32_t(rel)) << a;
  }
  return slot;
}

Cell TreeStorage::start_cell(std::uint32_t slot) const {
  const int log2_side = lattice_.max_depth - start_.depth;
  Cell cell{root_cell_.lo, start_.depth};
  for (int a = 0; a < 3; ++a) cell.lo[a] += std::int64_t(compact_bits(slot >> a)) << log2_side;
  return cell;
}

}  // namespace eco::detail
