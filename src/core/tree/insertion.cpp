// Batch insertion (core/tree/batch_insertion.hpp): grouping a batch by start cell, the top-down
// partition into octants, splitting full leaves; and the tree's part of it, new children and the
// start table insertion starts from. The sort-based descent for large groups is in sorted_insert.cpp.

#include "core/tree/batch_insertion.hpp"
#include "core/geometry/cell_codes.hpp"
#include "core/geometry/subcells.hpp"
#include "core/tree/tree.hpp"
#include "core/tree/tree_repair.hpp"

#include <algorithm>
#include <cassert>
#include <utility>

namespace eco::detail {

// ---------------------------------------------------------------------------------------------
// Insertion

template <class Point>
void BatchInsertion::insert(std::span<Point> batch) {
  if (batch.empty()) return;
  MappedVector<Point>& partitioned = t_.buffers().partitioned<Point>();
  partitioned.resize(batch.size());
  Point* points = batch.data();      // the batch, grouped once it is
  Point* temp = partitioned.data();  // room for as many
  MappedVector<std::uint32_t>& slot_of = t_.buffers().slots();  // the groups' sorts' second array, once grouped
  MappedVector<std::uint32_t>& codes = t_.buffers().codes();
  slot_of.resize(batch.size());
  codes.resize(batch.size());
  // Group the points by their start-depth cell (a counting sort), then insert each group below
  // its start node (a large group sorted by the cells below it: insert_sorted) and add it to the
  // ancestors once.
  const int depth = t_.start_depth();
  MappedVector<std::uint32_t>& first = t_.buffers().group_starts();
  first.assign((depth == 0 ? 1 : t_.start_slots()) + 1, 0);
  if (depth == 0) {
    first[1] = std::uint32_t(batch.size());
  } else {
    // a start cell's slot is its Morton code below the root (start_slot)
    const CodeGrid grid = code_grid(t_.lattice(), t_.root_cell(), depth, 0);
    find_cell_codes(t_.lattice(), t_.root_cell(), grid, batch.data(), batch.size(), slot_of.data(),
                    reinterpret_cast<std::uint8_t*>(codes.data()));
    for (std::size_t i = 0; i < batch.size(); ++i) ++first[std::size_t(slot_of[i]) + 1];
    // first[s + 1] becomes where group s starts, then where it ends as the points go in: at the
    // end first[s] is where group s starts (no second array of positions)
    std::uint32_t start = 0;
    for (std::size_t b = 1; b < first.size(); ++b) start += std::exchange(first[b], start);
    for (std::size_t i = 0; i < batch.size(); ++i) temp[first[std::size_t(slot_of[i]) + 1]++] = batch[i];
    std::swap(points, temp);
  }
  for (std::size_t b = 0; b + 1 < first.size(); ++b) {
    if (first[b] == first[b + 1]) continue;
    prefetch_start_node(b + 1, first);
    Point* group = points + first[b];
    const std::uint32_t m = first[b + 1] - first[b];
    Cell cell = depth == 0 ? t_.root_cell() : t_.start_cell(std::uint32_t(b));
    const std::uint32_t id = depth == 0 ? t_.root() : start_node(cell, cell);
    if (m >= kSortedGroup) {
      insert_sorted(id, cell, group, group + m, temp + first[b], codes.data() + first[b],
                    slot_of.data() + first[b]);
    } else {
      insert_range(id, cell, group, group + m, temp + first[b]);
    }
    const Node top = t_.nodes()[id];
    for (std::uint32_t up = top.parent; up != kNone; up = t_.nodes()[up].parent) {
      Node& n = t_.nodes().edit(up);
      n.count += m;
      n.bounds.merge(top.bounds);
      n.oldest = std::min(n.oldest, top.oldest);
    }
  }
}

void BatchInsertion::prefetch_start_node(std::size_t from, std::span<const std::uint32_t> first) const {
  if (t_.start_depth() == 0) return;
  for (std::size_t b = from; b + 1 < first.size(); ++b) {
    if (first[b] == first[b + 1]) continue;
    if (const std::uint32_t id = t_.start_node(b); id != kNone) t_.nodes().prefetch(id);
    return;
  }
}

std::uint32_t BatchInsertion::start_node(const Cell& cell, Cell& at) {
  const std::int64_t slot = t_.start_slot(cell);
  if (slot >= 0 && t_.start_node(std::size_t(slot)) != kNone) {
    at = cell;
    return t_.start_node(std::size_t(slot));
  }
  std::uint32_t id = t_.root();
  const Cell target = cell;
  at = t_.root_cell();
  while (at.depth < target.depth && !t_.nodes()[id].leaf) {
    const int o = t_.lattice().octant_of(at, target);
    id = t_.child_or_new(id, at, o);
    at = t_.lattice().child(at, o);
  }
  return id;
}

template <class Point>
BatchInsertion::Added BatchInsertion::insert_range(std::uint32_t id, const Cell& cell, Point* from, Point* to, Point* temp,
                               std::optional<std::uint64_t> subcells) {
  const auto m = std::uint32_t(to - from);
  Added added;
  const bool fits = t_.nodes()[id].count + m <= t_.config().leaf_capacity || cell.depth >= t_.lattice().max_depth;
  if (t_.nodes()[id].leaf && fits) {
    Node& n = t_.nodes().edit(id);
    t_.points().append(n.link, id, n.count, from, to);
    n.count += m;
    for (const Point* s = from; s != to; ++s) {
      added.bounds.grow(s->p[0], s->p[1], s->p[2]);
      added.oldest = std::min(added.oldest, t_.age().key(as_stored(*s)));
    }
    if (t_.keeps_subcells()) {
      n.set_subcells(n.subcells() | (subcells ? *subcells : Subcells(t_.lattice(), cell).bits(from, to)));
    }
    added.add_to(n);
    return added;
  }
  // Partition by octant into `temp` (a counting sort); the children read from there and use
  // this range as theirs. Bounds and ages are taken once, at the leaves, and summed on the way up.
  const std::array<double, 3> middle = t_.lattice().middle(cell);
  auto octant = [&](const Point& s) { return Lattice::octant_within(middle, s.p[0], s.p[1], s.p[2]); };
  // the range's two halves counted and scattered side by side, each with its own cursors: two
  // chains of increments, not one (a scan's points come in runs of one octant)
  const std::uint32_t h = m / 2;
  std::array<std::uint32_t, 8> first_half{}, second_half{};
  for (std::uint32_t i = 0; i < h; ++i) {
    ++first_half[std::size_t(octant(from[i]))];
    ++second_half[std::size_t(octant(from[h + i]))];
  }
  if (m % 2 != 0) ++second_half[std::size_t(octant(from[m - 1]))];
  if (t_.nodes()[id].leaf) {  // it holds at most leaf_capacity: its children need no split
    std::array<std::uint32_t, 8> incoming{};
    for (std::size_t o = 0; o < 8; ++o) incoming[o] = first_half[o] + second_half[o];
    split(id, cell, incoming);
  }
  t_.nodes().prefetch_children(id);  // their misses overlap the scatter below
  std::array<std::uint32_t, 9> begin{};
  std::array<std::uint32_t, 8> at{}, at2{};
  for (std::size_t o = 0; o < 8; ++o) {
    at[o] = begin[o];
    at2[o] = begin[o] + first_half[o];
    begin[o + 1] = at2[o] + second_half[o];
  }
  for (std::uint32_t i = 0; i < h; ++i) {
    temp[at[std::size_t(octant(from[i]))]++] = from[i];
    temp[at2[std::size_t(octant(from[h + i]))]++] = from[h + i];
  }
  if (m % 2 != 0) temp[at2[std::size_t(octant(from[m - 1]))]++] = from[m - 1];
  for (int o = 0; o < 8; ++o) {
    const std::uint32_t lo = begin[std::size_t(o)], hi = begin[std::size_t(o) + 1];
    if (lo == hi) continue;
    const std::uint32_t ch = t_.child_or_new(id, cell, o);
    added.merge(insert_range(ch, t_.lattice().child(cell, o), temp + lo, temp + hi, from + lo));
  }
  Node& n = t_.nodes().edit(id);
  n.count += m;
  added.add_to(n);
  return added;
}

// sorted_insert.cpp calls them too
template BatchInsertion::Added BatchInsertion::insert_range(std::uint32_t, const Cell&, StoredPoint*, StoredPoint*, StoredPoint*,
                                        std::optional<std::uint64_t>);
template BatchInsertion::Added BatchInsertion::insert_range(std::uint32_t, const Cell&, BarePoint*, BarePoint*, BarePoint*,
                                        std::optional<std::uint64_t>);

void BatchInsertion::split(std::uint32_t id, const Cell& cell, const std::array<std::uint32_t, 8>& incoming) {
  const std::uint32_t m = t_.nodes()[id].count;
  std::uint32_t block = std::exchange(t_.nodes().edit(id).link, kNone);  // released once the children hold its points
  t_.nodes().make_inner(id);
  const PointSpan points = t_.points().span(block, m);
  // Each point's octant found once, then the points' indices grouped by octant (a counting sort):
  // each child copies its points straight from the block's columns.
  MappedVector<std::uint32_t>& order = t_.buffers().split_order();
  order.resize(2 * std::size_t(m));
  std::uint32_t* const octant = order.data();
  std::uint32_t* const grouped = octant + m;
  const std::array<double, 3> middle = t_.lattice().middle(cell);
  for (std::uint32_t i = 0; i < m; ++i) {
    octant[i] = std::uint32_t(Lattice::octant_within(middle, points.x[i], points.y[i], points.z[i]));
  }
  std::array<std::uint32_t, 9> begin{};
  for (std::uint32_t i = 0; i < m; ++i) ++begin[octant[i] + 1];
  for (std::size_t o = 0; o < 8; ++o) begin[o + 1] += begin[o];
  std::array<std::uint32_t, 8> at{};
  std::copy(begin.begin(), begin.end() - 1, at.begin());
  for (std::uint32_t i = 0; i < m; ++i) grouped[at[octant[i]]++] = i;
  for (int o = 0; o < 8; ++o) {
    const std::uint32_t own = begin[std::size_t(o) + 1] - begin[std::size_t(o)];
    if (own == 0) continue;
    const std::uint32_t child = t_.child_or_new(id, cell, o);
    const std::uint32_t all = own + incoming[std::size_t(o)];
    Node& n = t_.nodes().edit(child);
    t_.points().append_picked(n.link, child, 0, points, grouped + begin[std::size_t(o)], own,
                          all <= t_.config().leaf_capacity ? all : 0);
    n.count = own;
    TreeRepair(t_).fit_leaf(child, t_.keeps_subcells() ? Subcells(t_.lattice(), t_.lattice().child(cell, o)) : Subcells());
  }
  t_.points().release(block);
  t_.nodes().for_each_child(id, [&](int o, std::uint32_t ch) {
    if (t_.nodes()[ch].count > t_.config().leaf_capacity && cell.depth + 1 < t_.lattice().max_depth) {
      split(ch, t_.lattice().child(cell, o));
    }
  });
}

// ---------------------------------------------------------------------------------------------
// The tree's part: a batch handed to BatchInsertion

template <class Point>
void Tree::insert_points(std::span<Point> batch) {
  BatchInsertion(s_).insert(batch);
}
template void Tree::insert_points(std::span<StoredPoint>);
template void Tree::insert_points(std::span<BarePoint>);

}  // namespace eco::detail
