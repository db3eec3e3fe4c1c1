// Insertion of a large group of points below one node, by sorting instead of partitioning: the
// cell each point falls in a few levels down is found once (src/core/geometry/cell_codes.hpp), the points
// are sorted by the cells' Morton codes, and each of those levels reads its children's ranges off
// the codes instead of moving every point into them (insert_range's counting sort per level).

#include "core/tree/batch_insertion.hpp"
#include "core/geometry/cell_codes.hpp"
#include "core/tree/tree.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace eco::detail {
namespace {

constexpr int kDigitBits = 9;  // codes of 3 kCodeLevels = 18 bits, sorted in two passes
constexpr std::uint32_t kDigits = 1u << kDigitBits;
static_assert(2 * kDigitBits == 3 * kCodeLevels);

/// One pass of a least-significant-digit radix sort: points and codes into the `_out` arrays,
/// stably by the digit of the codes at `shift`.
template <class Point>
void sort_pass(const Point* points, const std::uint32_t* codes, std::uint32_t m, int shift, Point* points_out,
               std::uint32_t* codes_out) {
  std::array<std::uint32_t, kDigits> at{};
  for (std::uint32_t i = 0; i < m; ++i) ++at[(codes[i] >> shift) & (kDigits - 1)];
  std::uint32_t start = 0;
  for (std::uint32_t& a : at) start += std::exchange(a, start);
  for (std::uint32_t i = 0; i < m; ++i) {
    const std::uint32_t to = at[(codes[i] >> shift) & (kDigits - 1)]++;
    points_out[to] = points[i];
    codes_out[to] = codes[i];
  }
}

}  // namespace

template <class Point>
BatchInsertion::Added BatchInsertion::insert_sorted(std::uint32_t id, const Cell& cell, Point* from, Point* to, Point* temp,
                                std::uint32_t* codes, std::uint32_t* codes_temp) {
  const auto m = std::uint32_t(to - from);
  const int levels = std::min(kCodeLevels, t_.lattice().max_depth - cell.depth);
  if (levels < 1) return insert_range(id, cell, from, to, temp);
  // the first level in the top bits, however many are coded
  const CodeGrid grid = code_grid(t_.lattice(), cell, levels, 3 * (kCodeLevels - levels));
  find_cell_codes(t_.lattice(), cell, grid, from, m, codes, reinterpret_cast<std::uint8_t*>(codes_temp));
  sort_pass(from, codes, m, 0, temp, codes_temp);
  sort_pass(temp, codes_temp, m, kDigitBits, from, codes);
  return descend_sorted(id, cell, 0, from, to, temp, codes);
}

template <class Point>
BatchInsertion::Added BatchInsertion::descend_sorted(std::uint32_t id, const Cell& cell, int level, Point* from, Point* to, Point* temp,
                                 const std::uint32_t* codes) {
  const auto m = std::uint32_t(to - from);
  if (level == kCodeLevels || cell.depth >= t_.lattice().max_depth ||
      (t_.nodes()[id].leaf && t_.nodes()[id].count + m <= t_.config().leaf_capacity)) {
    // a leaf with room, or below the coded levels; a leaf's subcells are read off the codes where
    // they name the two levels below it (its quarter walls are theirs: four lattice units or more)
    std::optional<std::uint64_t> subcells;
    if (t_.keeps_subcells() && level + 2 <= kCodeLevels && t_.lattice().side(cell.depth) >= 4) {
      subcells = subcells_of_codes(codes, m, 3 * (kCodeLevels - 2 - level));
    }
    return insert_range(id, cell, from, to, temp, subcells);
  }
  const int shift = 3 * (kCodeLevels - 1 - level);
  if (t_.nodes()[id].leaf) {  // it holds at most leaf_capacity: its children need no split
    std::array<std::uint32_t, 8> incoming{};
    for (std::uint32_t i = 0; i < m; ++i) ++incoming[(codes[i] >> shift) & 7u];
    split(id, cell, incoming);
  }
  t_.nodes().prefetch_children(id);
  Added added;
  for (std::uint32_t begin = 0, end = 0; begin < m; begin = end) {  // an octant's points lie together, in order
    const std::uint32_t octant = (codes[begin] >> shift) & 7u;
    // the codes share the levels above and are sorted: the run ends at the first higher octant
    const std::uint32_t last_of_run = (codes[begin] >> shift << shift) | ((1u << shift) - 1);
    end = std::uint32_t(std::upper_bound(codes + begin, codes + m, last_of_run) - codes);
    const std::uint32_t ch = t_.child_or_new(id, cell, int(octant));
    added.merge(descend_sorted(ch, t_.lattice().child(cell, int(octant)), level + 1, from + begin, from + end,
                               temp + begin, codes + begin));
  }
  Node& n = t_.nodes().edit(id);
  n.count += m;
  added.add_to(n);
  return added;
}

template BatchInsertion::Added BatchInsertion::insert_sorted(std::uint32_t, const Cell&, StoredPoint*, StoredPoint*, StoredPoint*,
                                         std::uint32_t*, std::uint32_t*);
template BatchInsertion::Added BatchInsertion::insert_sorted(std::uint32_t, const Cell&, BarePoint*, BarePoint*, BarePoint*,
                                         std::uint32_t*, std::uint32_t*);

}  // namespace eco::detail
