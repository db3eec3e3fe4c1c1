#include "core/geometry/cell_codes.hpp"

#include "core/geometry/vector_clones.hpp"

#include <algorithm>

namespace eco::detail {
namespace {

/// A guess this far inside its cell is its cell: the walls and the guess are each within a few
/// units of 2^-52 of the walls' distance from the anchor, which a guessable grid keeps below 2^36
/// cells (code_grid): a few units of 2^-16 of a cell, far below this.
constexpr double kSure = 0x1p-12;

template <std::size_t kStride>
[[gnu::always_inline]] inline void guess_lanes(const CodeGrid& g, const float* points, std::size_t n, std::uint32_t* codes,
                                               std::uint8_t* unsure) {
  const double top = double(g.cells) - 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t code = 0, sure = 1;
    for (std::size_t a = 0; a < 3; ++a) {
      const double above = (double(points[i * kStride + a]) - g.low[a]) * g.inverse[a];
      const double held = std::min(std::max(0.0, above), top);  // NaN: 0 (max(a, b) keeps a unless a < b)
      const auto j = std::uint32_t(std::int32_t(held));
      const double fraction = above - double(j);
      sure &= std::uint32_t(fraction > kSure) & std::uint32_t(fraction < 1.0 - kSure);
      code |= spread_bits(j) << a;
    }
    codes[i] = code << g.shift;
    unsure[i] = std::uint8_t(1 - sure);
  }
}

}  // namespace

ECO_WIDE_VECTOR_CLONES
void guess_cell_codes(const CodeGrid& grid, const float* points, std::size_t stride, std::size_t n, std::uint32_t* codes,
                      std::uint8_t* unsure) {
  if (stride == 3) return guess_lanes<3>(grid, points, n, codes, unsure);
  guess_lanes<7>(grid, points, n, codes, unsure);
}

}  // namespace eco::detail
