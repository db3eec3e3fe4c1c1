#pragma once
// The cells a few levels below a lattice cell, named by Morton codes (bit 3 b + a holds bit b of
// the cell's index on axis a: the octant taken b levels above the last), found for many points at
// once: guessed in vector code (core/geometry/vector_clones.hpp), the guesses near a wall settled by the
// walls themselves. Insertion groups points by their start cells and sorts a large group by the
// cells below it with them (src/core/tree/tree.cpp, src/core/tree/sorted_insert.cpp).

#include "core/geometry/geometry.hpp"
#include "core/geometry/set_flags.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace eco::detail {

/// The most levels a code names: 6, in 18 bits.
inline constexpr int kCodeLevels = 6;

/// Bits 0..5 of j moved to bits 0, 3, ..., 15.
[[nodiscard]] constexpr std::uint32_t spread_bits(std::uint32_t j) {
  j = (j | j << 8) & 0x0000F00Fu;
  j = (j | j << 4) & 0x000C30C3u;
  j = (j | j << 2) & 0x00049249u;
  return j;
}

/// The inverse of spread_bits: bits 0, 3, ..., 15 of code moved to bits 0..5.
[[nodiscard]] constexpr std::uint32_t compact_bits(std::uint32_t code) {
  code &= 0x00049249u;
  code = (code | code >> 2) & 0x000C30C3u;
  code = (code | code >> 4) & 0x0000F00Fu;
  code = (code | code >> 8) & 0x0000003Fu;
  return code;
}

/// The cells `levels` below a lattice cell as plain numbers: on axis a, a point p lies
/// (p - low[a]) * inverse[a] of them above the cell's lower wall.
struct CodeGrid {
  std::array<double, 3> low{}, inverse{};
  std::uint32_t cells = 1;  // per axis: 2^levels
  int shift = 0;            // codes are shifted left this far
  bool guessable = false;   // whether guess_cell_codes may be sure of a guess (its walls lie near enough)
};

/// The codes of points[0, n) (x, y, z the first three of every `stride` floats; stride 3 or 7),
/// shifted by grid.shift, where a guess is sure; unsure[i] = 1 where it is not (a point within
/// 2^-12 of a cell's wall, or outside the cell), whose code is left to the caller.
void guess_cell_codes(const CodeGrid& grid, const float* points, std::size_t stride, std::size_t n, std::uint32_t* codes,
                      std::uint8_t* unsure);

/// The grid of the cells `levels` (1..kCodeLevels) below `cell`, codes shifted left by `shift`.
[[nodiscard]] inline CodeGrid code_grid(const Lattice& lattice, const Cell& cell, int levels, int shift) {
  assert(levels >= 1 && levels <= kCodeLevels && cell.depth + levels <= lattice.max_depth);
  const double step = double(lattice.side(cell.depth + levels)) * lattice.unit;
  CodeGrid grid;
  grid.cells = 1u << levels;
  grid.shift = shift;
  double farthest = 0.0;
  for (int a = 0; a < 3; ++a) {
    grid.low[std::size_t(a)] = lattice.wall(a, cell.lo[a]);
    grid.inverse[std::size_t(a)] = 1.0 / step;
    farthest = std::max({farthest, std::abs(grid.low[std::size_t(a)]),
                         std::abs(lattice.wall(a, cell.lo[a] + lattice.side(cell.depth)))});
  }
  // the walls and the guess lie within a few units of 2^-52 of `farthest` of where they would
  // without rounding: far below guess_cell_codes's 2^-12 of a cell while the walls lie within
  // 2^36 cells of the anchor
  grid.guessable = farthest < 0x1p36 * step;
  return grid;
}

/// The subcells (core/geometry/subcells.hpp: bit x + 4 y + 16 z, a quarter of a cell along each axis) that
/// points occupy in a cell whose two levels below are the six bits of their codes from `shift`
/// (the upper level in the upper three), as bits. Those levels' walls are the quarters' walls, so
/// they are Subcells' bits, found without a comparison.
[[nodiscard]] inline std::uint64_t subcells_of_codes(const std::uint32_t* codes, std::size_t n, int shift) {
  std::uint64_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t v = (codes[i] >> shift) & 0x3Fu;  // two levels' octants: x in bits 0 and 3
    out |= std::uint64_t{1} << (compact_bits(v) | compact_bits(v >> 1) << 2 | compact_bits(v >> 2) << 4);
  }
  return out;
}

/// The code of p (inside `cell`) by the octant tests the tree descends by: a level at a time,
/// the wall between the halves decides.
[[nodiscard]] inline std::uint32_t settled_code(const Lattice& lattice, const Cell& cell, const CodeGrid& grid,
                                                const std::array<float, 3>& p) {
  const int levels = std::countr_zero(grid.cells);
  const std::int64_t step = lattice.side(cell.depth + levels);
  std::uint32_t code = 0;
  for (int a = 0; a < 3; ++a) {
    std::uint32_t j = 0;
    for (int bit = levels - 1; bit >= 0; --bit) {
      const std::uint32_t upper = j + (1u << bit);
      if (double(p[std::size_t(a)]) >= lattice.wall(a, cell.lo[a] + std::int64_t(upper) * step)) j = upper;
    }
    code |= spread_bits(j) << a;
  }
  return code << grid.shift;
}

/// The codes of points[0, n) (each inside `cell`, `grid` the cells below it) as settled_code
/// gives them: guessed a group at a time, the unsure ones settled. `unsure` has room for n.
template <class Point>
void find_cell_codes(const Lattice& lattice, const Cell& cell, const CodeGrid& grid, const Point* points, std::size_t n,
                     std::uint32_t* codes, std::uint8_t* unsure) {
  static_assert(sizeof(Point) == 3 * sizeof(float) || sizeof(Point) == 7 * sizeof(float));
  assert(std::all_of(points, points + n, [&](const Point& s) { return lattice.contains(cell, s.p); }));
  const auto settle = [&](std::size_t i) { codes[i] = settled_code(lattice, cell, grid, points[i].p); };
  if (!grid.guessable) {
    for (std::size_t i = 0; i < n; ++i) settle(i);
    return;
  }
  guess_cell_codes(grid, points->p.data(), sizeof(Point) / sizeof(float), n, codes, unsure);
  for_each_set(unsure, n, settle);  // a few near walls: skipped eight flags at a time
}

}  // namespace eco::detail
