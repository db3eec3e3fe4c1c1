#pragma once
// A leaf's occupied subcells: its cell cut in four along each axis (64 subcells), one bit for
// each that holds a point. The tree keeps it with every leaf in Quantised mode, where the lattice's
// walls stay put between precision-origin moves, so that a voxel map one or two levels below a
// leaf reads one word instead of the leaf's points (src/query/voxelize.cpp). Kept as the bounds
// are: grown as points come in, recomputed when they leave. Scalar on purpose: a leaf takes a
// few points a batch, too few for vector code to pay for itself.

#include "core/geometry/geometry.hpp"

#include <array>
#include <bit>
#include <cstdint>

namespace eco::detail {

/// The subcell walls of one cell: per axis, the three inner walls at lattice indices
/// lo + floor(j * side / 4), in double as the lattice gives them (a stored float is compared in
/// double: no rounding of the walls, and no branch to build them). A cell fewer than four lattice
/// units wide has walls on its own (lower and middle) lattice walls only: its bits are then
/// distinct only as far as the lattice goes, which is as far as a voxel map looks.
class Subcells {
 public:
  Subcells() = default;  // of no cell: a placeholder, not to be asked
  Subcells(const Lattice& lattice, const Cell& cell) {
    const std::int64_t side = lattice.side(cell.depth);
    for (int a = 0; a < 3; ++a) {
      for (std::int64_t j = 0; j < 3; ++j) {
        walls_[std::size_t(a)][std::size_t(j)] = lattice.wall(a, cell.lo[a] + (j + 1) * side / 4);
      }
    }
  }

  /// The subcell of stored point p (inside the cell): (x, y, z) is x + 4 y + 16 z.
  [[nodiscard]] int of(const std::array<float, 3>& p) const {
    return along(0, p[0]) | along(1, p[1]) << 2 | along(2, p[2]) << 4;
  }
  /// The subcells of points [from, to) (anything with a stored `p`), as bits.
  template <class Point>
  [[nodiscard]] std::uint64_t bits(const Point* from, const Point* to) const {
    std::uint64_t out = 0;
    for (const Point* s = from; s != to; ++s) out |= std::uint64_t{1} << of(s->p);
    return out;
  }

 private:
  /// Which quarter of the cell along `axis` holds coordinate v.
  [[nodiscard]] int along(int axis, float v) const {
    const auto& w = walls_[std::size_t(axis)];
    const double d = v;
    return int(d >= w[0]) + int(d >= w[1]) + int(d >= w[2]);
  }

  std::array<std::array<double, 3>, 3> walls_{};
};

/// Subcell bits seen one level coarser: the 2 × 2 × 2 cells of the same cell, bit x + 2 y + 4 z.
[[nodiscard]] inline std::uint8_t halved(std::uint64_t bits) {
  std::uint8_t out = 0;
  for (; bits != 0; bits &= bits - 1) {
    const int b = std::countr_zero(bits);
    out |= std::uint8_t(1u << ((b >> 1 & 1) | (b >> 3 & 1) << 1 | (b >> 5 & 1) << 2));
  }
  return out;
}

}  // namespace eco::detail
