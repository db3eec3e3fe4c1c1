#pragma once
// The density cap's verdicts on a frame's new points, in their order (the first points to reach a
// full cell are the ones kept), judged a group at a time: the group's cells are found and their
// hash slots prefetched before the first is asked, so the table's cache misses overlap instead of
// following one another (a capped map's counts outgrow L1, and a scan visits its cells in no
// order a cache can guess). Shared by ECO and the flat baselines, so their caps cost alike.
// Points leaving in bulk (a subtree dropped at the box's edge) leave their cells the same way.

#include "core/cell_counts.hpp"
#include "core/geometry.hpp"

#include <eco/config.hpp>

#include <array>
#include <cstddef>
#include <cstdint>

namespace eco::detail {

/// Points judged together: enough misses in flight to hide most of their latency, few enough
/// that the group stays in L1.
inline constexpr std::size_t kDensityGroup = 64;

/// The keys of the cells of points[0, n) (n <= kDensityGroup) where WorldGrid::index's guess is
/// sure, in vector code (core/vector_clones.hpp); unsure[i] = 1 where it is not (a point within
/// 2^-12 of a wall, or far out), whose key is then left to WorldGrid::index.
void guess_cell_keys(const WorldGrid& grid, const std::array<float, 3>* points, std::size_t n, std::uint64_t* keys,
                     std::uint8_t* unsure);

/// Finds the cells of points[0, n) (their keys) and starts loading their slots.
inline void find_cells(const CellCounts& counts, const WorldGrid& grid, const std::array<float, 3>* points,
                       std::uint64_t* keys, std::size_t n) {
  std::array<std::uint8_t, kDensityGroup> unsure;
  guess_cell_keys(grid, points, n, keys, unsure.data());
  for (std::size_t i = 0; i < n; ++i) {
    if (unsure[i] != 0) keys[i] = CellCounts::key(grid.index(points[i]));
    counts.prefetch(keys[i]);
  }
}

/// Calls produce(offer); each offer(item, p) hands an item whose point is p (stored
/// coordinates). Calls pass(item) for each item, in the order offered, whose cell in `grid` held
/// fewer than `limit` points (counting it there); returns how many it refused.
template <class Item, class Produce, class Pass>
std::size_t pass_density_cap(CellCounts& counts, const WorldGrid& grid, std::uint32_t limit, Produce&& produce,
                             Pass&& pass) {
  std::array<Item, kDensityGroup> items;
  std::array<std::array<float, 3>, kDensityGroup> points;
  std::array<std::uint64_t, kDensityGroup> keys{};
  std::array<std::uint8_t, kDensityGroup> passed{};
  std::size_t held = 0, refused = 0;
  const auto judge = [&] {
    find_cells(counts, grid, points.data(), keys.data(), held);
    counts.add_below_each(keys.data(), held, limit, passed.data());
    for (std::size_t i = 0; i < held; ++i) {
      if (passed[i] != 0) {
        pass(items[i]);
      } else {
        ++refused;
      }
    }
    held = 0;
  };
  produce([&](const Item& item, const std::array<float, 3>& p) {
    items[held] = item;
    points[held] = p;
    if (++held == kDensityGroup) judge();
  });
  judge();
  return refused;
}

/// pass_density_cap under `cap`, or, when the cap is off, pass(item) for every item offered.
template <class Item, class Produce, class Pass>
std::size_t pass_density_cap(CellCounts& counts, const WorldGrid& grid, const DensityCap& cap, Produce&& produce,
                             Pass&& pass) {
  if (!cap.enabled()) {
    produce([&](const Item& item, const std::array<float, 3>&) { pass(item); });
    return 0;
  }
  return pass_density_cap<Item>(counts, grid, cap.max_points, produce, pass);
}

/// Calls produce(offer); each offer(p) hands the stored coordinates of a point that leaves, and
/// its cell in `grid` forgets it — a group at a time, slots prefetched, as pass_density_cap asks.
template <class Produce>
void forget_in_groups(CellCounts& counts, const WorldGrid& grid, Produce&& produce) {
  std::array<std::array<float, 3>, kDensityGroup> points;
  std::array<std::uint64_t, kDensityGroup> keys{};
  std::size_t held = 0;
  const auto forget = [&] {
    find_cells(counts, grid, points.data(), keys.data(), held);
    for (std::size_t i = 0; i < held; ++i) counts.remove(keys[i]);
    held = 0;
  };
  produce([&](const std::array<float, 3>& p) {
    points[held] = p;
    if (++held == kDensityGroup) forget();
  });
  forget();
}

}  // namespace eco::detail
