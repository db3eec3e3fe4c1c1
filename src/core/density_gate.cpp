#include "core/density_gate.hpp"

#include "core/vector_clones.hpp"

namespace eco::detail {

namespace {

constexpr std::uint32_t kMask = (1u << CellCounts::kAxisBits) - 1;

/// The guesses in single precision, for a grid whose Single is ready (WorldGrid says why they hold).
ECO_WIDE_VECTOR_CLONES
void guess_in_float(const WorldGrid::Single& single, const std::array<float, 3>* points, std::size_t n,
                    std::uint64_t* keys, std::uint8_t* unsure) {
  const std::array<WorldGrid::Single::Axis, 3> axes = single.axis;
  const float inverse = single.inverse, span = float(2 * WorldGrid::kSingleReach), sure_above = float(WorldGrid::kSure);
  std::array<std::uint32_t, 3> base_low{};  // the bases' low bits: a key keeps kAxisBits of each index
  for (int a = 0; a < 3; ++a) base_low[std::size_t(a)] = std::uint32_t(axes[std::size_t(a)].base);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t key = 0;
    std::uint32_t sure = 1;
    for (int a = 0; a < 3; ++a) {
      const float above = axes[a].offset + (points[i][a] - axes[a].near) * inverse;
      const std::uint32_t held = (above >= 0.0f) & (above < span);
      const float counted = held != 0 ? above : 0.0f;
      const std::int32_t whole = std::int32_t(counted);  // a truncation of a positive number: its floor
      const float fraction = counted - float(whole);
      sure &= held & (fraction > sure_above) & (fraction < 1.0f - sure_above);
      const std::uint32_t low = std::uint32_t(whole) + base_low[std::size_t(a)];
      key |= std::uint64_t(low & kMask) << (a * CellCounts::kAxisBits);
    }
    keys[i] = key;
    unsure[i] = std::uint8_t(1 - sure);
  }
}

/// WorldGrid::index's guesses, in double.
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
      // WorldGrid::index's guess: the count of cells above the base truncated (within kReach of
      // the origin's cell it lies in (0, 2^31), where an int32 holds it), its low bits added to
      // the base's
      const double cells = (axes[a].origin + double(points[i][a])) * inverse;
      const double above = cells - axes[a].base;
      const std::uint32_t held = (above >= 0.0) & (above < 0x1p31);
      const double counted = held != 0 ? above : 0.0;
      const std::int32_t whole = std::int32_t(counted);
      const double fraction = counted - double(whole);
      sure &= held & (fraction > WorldGrid::kSure) & (fraction < 1.0 - WorldGrid::kSure) &
              (std::abs(cells) < axes[a].fast_below);
      const std::uint32_t low = std::uint32_t(whole) + base_low[std::size_t(a)];
      key |= std::uint64_t(low & kMask) << (a * CellCounts::kAxisBits);
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
