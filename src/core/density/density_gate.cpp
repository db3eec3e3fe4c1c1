#include "core/density/density_gate.hpp"

#include "core/geometry/vector_clones.hpp"

#include <algorithm>

namespace eco::detail {

namespace {

/// One axis of a guess: the low kAxisBits of the cell index whose count above the base is
/// `above`, truncated (the floor: counted only in [0, span), where it is positive and an int32
/// holds it), added to the base's low bits; `sure` cleared unless `above` lies in that range and
/// more than kSure inside its cell. Shared by the float and the double guess.
template <class Real>
[[gnu::always_inline]] inline std::uint32_t axis_bits(Real above, Real span, std::uint32_t base_low,
                                                      std::uint32_t& sure) {
  constexpr std::uint32_t kMask = (1u << CellCounts::kAxisBits) - 1;
  constexpr Real kSure = Real(WorldGrid::kSure);
  const std::uint32_t held = (above >= Real(0)) & (above < span);
  const Real counted = held != 0 ? above : Real(0);
  const std::int32_t whole = std::int32_t(counted);
  const Real fraction = counted - Real(whole);
  sure &= held & (fraction > kSure) & (fraction < Real(1) - kSure);
  return (std::uint32_t(whole) + base_low) & kMask;
}

/// Points the float guess takes at a time: whole vectors of floats at any width up to AVX-512.
constexpr std::size_t kFloatBlock = 16;

/// The float guesses of points[0, kFloatBlock): a trip count the compiler knows and arrays that do
/// not overlap, so the loop is vector code with neither a scalar tail nor run-time checks. (A loop
/// over n took its AVX-512 code only for n = 64, GCC's threshold: smaller groups ran scalar.)
[[gnu::always_inline]] inline void guess_float_block(const WorldGrid::Single& single,
                                                     const std::array<float, 3>* __restrict points,
                                                     std::uint64_t* __restrict keys, std::uint8_t* __restrict unsure) {
  const std::array<WorldGrid::Single::Axis, 3> axes = single.axis;
  const float inverse = single.inverse, span = float(2 * WorldGrid::kSingleReach);
  std::array<std::uint32_t, 3> base_low{};  // the bases' low bits: a key keeps kAxisBits of each index
  for (int a = 0; a < 3; ++a) base_low[std::size_t(a)] = std::uint32_t(axes[std::size_t(a)].base);
  // the indices in 32-bit lanes first, the keys after: mixed with 64-bit keys, GCC chose 4 lanes
  std::array<std::array<std::uint32_t, kFloatBlock>, 3> index;
  std::array<std::uint32_t, kFloatBlock> sure;
  for (std::size_t i = 0; i < kFloatBlock; ++i) {
    sure[i] = 1;
    for (std::size_t a = 0; a < 3; ++a) {
      const float above = axes[a].offset + (points[i][a] - axes[a].near) * inverse;
      index[a][i] = axis_bits(above, span, base_low[a], sure[i]);
    }
  }
  for (std::size_t i = 0; i < kFloatBlock; ++i) {
    keys[i] = std::uint64_t(index[0][i]) | std::uint64_t(index[1][i]) << CellCounts::kAxisBits |
              std::uint64_t(index[2][i]) << (2 * CellCounts::kAxisBits);
    unsure[i] = std::uint8_t(1 - sure[i]);
  }
}

/// The guesses in single precision, for a grid whose Single is ready (WorldGrid says why they
/// hold), a block at a time, the last, partial one through a padded copy.
ECO_WIDE_VECTOR_CLONES
void guess_in_float(const WorldGrid::Single& single, const std::array<float, 3>* points, std::size_t n,
                    std::uint64_t* keys, std::uint8_t* unsure) {
  const std::size_t whole = n - n % kFloatBlock;
  for (std::size_t begin = 0; begin < whole; begin += kFloatBlock) {
    guess_float_block(single, points + begin, keys + begin, unsure + begin);
  }
  if (whole == n) return;
  std::array<std::array<float, 3>, kFloatBlock> tail{};
  std::array<std::uint64_t, kFloatBlock> tail_keys;
  std::array<std::uint8_t, kFloatBlock> tail_unsure;
  std::copy(points + whole, points + n, tail.begin());
  guess_float_block(single, tail.data(), tail_keys.data(), tail_unsure.data());
  std::copy_n(tail_keys.begin(), n - whole, keys + whole);
  std::copy_n(tail_unsure.begin(), n - whole, unsure + whole);
}

/// WorldGrid::index's guesses, in double: the count of cells above the base (within kReach of
/// the origin's cell it lies in (0, 2^31)).
ECO_WIDE_VECTOR_CLONES
void guess_in_double(const WorldGrid& grid, const std::array<float, 3>* points, std::size_t n, std::uint64_t* keys,
                     std::uint8_t* unsure) {
  const double inverse = grid.inverse();
  const std::array<WorldGrid::Axis, 3> axes{grid.axis(0), grid.axis(1), grid.axis(2)};
  std::array<std::uint32_t, 3> base_low{};
  for (int a = 0; a < 3; ++a) base_low[std::size_t(a)] = std::uint32_t(std::int64_t(axes[std::size_t(a)].base));
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t key = 0;
    std::uint32_t sure = 1;
    for (int a = 0; a < 3; ++a) {
      const double cells = (axes[a].origin + double(points[i][a])) * inverse;
      sure &= std::uint32_t(std::abs(cells) < axes[a].fast_below);
      key |= std::uint64_t(axis_bits(cells - axes[a].base, 0x1p31, base_low[std::size_t(a)], sure))
             << (a * CellCounts::kAxisBits);
    }
    keys[i] = key;
    unsure[i] = std::uint8_t(1 - sure);
  }
}

}  // namespace

void guess_cell_keys(const WorldGrid& grid, const std::array<float, 3>* points, std::size_t n, std::uint64_t* keys,
                     std::uint8_t* unsure) {
  if (grid.single().ready) {
    guess_in_float(grid.single(), points, n, keys, unsure);
  } else {
    guess_in_double(grid, points, n, keys, unsure);
  }
}

}  // namespace eco::detail
