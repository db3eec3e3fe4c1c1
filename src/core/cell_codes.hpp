#pragma once
// The cells a few levels below a lattice cell, named by Morton codes (bit 3 b + a holds bit b of
// the cell's index on axis a), guessed for many points in vector code (core/vector_clones.hpp):
// insertion sorts a large group of points by them (src/core/sorted_insert.cpp).

#include <array>
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

/// A cell's subdivision as plain numbers: on axis a, a point p lies (p - low[a]) * inverse[a]
/// cells above the lower wall, in [0, cells).
struct CodeGrid {
  std::array<double, 3> low{}, inverse{};
  std::uint32_t cells = 1;  // per axis: 2^levels, levels <= kCodeLevels
  int shift = 0;            // codes are shifted left this far
};

/// The codes of points[0, n) (x, y, z the first three of every `stride` floats; stride 3 or 7),
/// shifted by grid.shift, where a guess is sure; unsure[i] = 1 where it is not (a point within
/// 2^-12 of a cell's wall, or outside the subdivided cell), whose code is left to the caller.
void guess_cell_codes(const CodeGrid& grid, const float* points, std::size_t stride, std::size_t n, std::uint32_t* codes,
                      std::uint8_t* unsure);

}  // namespace eco::detail
