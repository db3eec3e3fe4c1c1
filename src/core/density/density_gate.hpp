#pragma once
// The density cap's verdicts on a frame's new points, in their order (the first points to reach a
// full cell are the ones kept), judged a group at a time: the group's cells are found in vector
// code, then its verdicts (density/cell_counts.hpp). Shared by ECO and the flat baselines, so their
// caps cost alike. Points leaving in bulk (a subtree dropped at the box's edge) leave their cells
// the same way.

#include "core/density/cell_counts.hpp"
#include "core/geometry/geometry.hpp"
#include "core/geometry/set_flags.hpp"

#include <eco/config.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace eco::detail {

/// Points judged together: enough misses in flight to hide most of their latency, few enough
/// that the group stays in L1.
inline constexpr std::size_t kDensityGroup = 64;

/// The keys of the cells of points[0, n) (n <= kDensityGroup) where WorldGrid::index's guess is
/// sure — in single precision where the grid's Single is ready, else in double — in vector code
/// (core/geometry/vector_clones.hpp); unsure[i] = 1 where it is not (a point within 2^-12 of a wall, or
/// far out), whose key is then left to WorldGrid::index.
void guess_cell_keys(const WorldGrid& grid, const std::array<float, 3>* points, std::size_t n, std::uint64_t* keys,
                     std::uint8_t* unsure);

/// Finds the cells of points[0, n) (their keys). (Their slots are not asked for ahead: the counts
/// lie in blocks of neighbouring cells, a few bytes a held point, so the table stays in the caches
/// and a prefetch would only add work.)
inline void find_cells(const WorldGrid& grid, const std::array<float, 3>* points, std::uint64_t* keys, std::size_t n) {
  std::array<std::uint8_t, kDensityGroup> unsure;
  guess_cell_keys(grid, points, n, keys, unsure.data());
  for_each_set(unsure.data(), n, [&](std::size_t i) { keys[i] = CellCounts::key(grid.index(points[i])); });
}

/// The density cap's verdicts on points[0, n) (stored coordinates, n <= kDensityGroup), in their
/// order (the first points to reach a full cell are the ones kept): passed[i] = 1 when point i's
/// cell in `grid` held fewer than `limit` points, and it is counted there. Returns how many it
/// refused.
inline std::size_t judge_group(CellCounts& counts, const WorldGrid& grid, std::uint32_t limit,
                               const std::array<float, 3>* points, std::size_t n, std::uint8_t* passed) {
  assert(n <= kDensityGroup);
  std::array<std::uint64_t, kDensityGroup> keys;
  find_cells(grid, points, keys.data(), n);
  return n - counts.add_below_each(keys.data(), n, limit, passed);
}

/// judge_group under `cap`; while the cap is off every point passes, counted nowhere.
inline std::size_t judge_group(CellCounts& counts, const WorldGrid& grid, const DensityCap& cap,
                               const std::array<float, 3>* points, std::size_t n, std::uint8_t* passed) {
  if (!cap.enabled()) {
    std::fill(passed, passed + n, std::uint8_t{1});
    return 0;
  }
  return judge_group(counts, grid, cap.max_points, points, n, passed);
}

/// Calls produce(add); each add(p) hands the stored coordinates of a held point, counted in its
/// cell in `grid` whatever the cell holds (a map recounted or loaded) — a group at a time.
template <class Produce>
void count_in_groups(CellCounts& counts, const WorldGrid& grid, Produce&& produce) {
  std::array<std::array<float, 3>, kDensityGroup> points{};  // (zeroed: GCC cannot see a group filled before it is read)
  std::array<std::uint64_t, kDensityGroup> keys;
  std::array<std::uint8_t, kDensityGroup> passed;
  std::size_t held = 0;
  const auto count = [&] {
    find_cells(grid, points.data(), keys.data(), held);
    counts.add_below_each(keys.data(), held, CellCounts::kMaxCount, passed.data());
    held = 0;
  };
  produce([&](const std::array<float, 3>& p) {
    points[held] = p;
    if (++held == kDensityGroup) count();
  });
  count();
}

/// Calls produce(offer); each offer(p) hands the stored coordinates of a point that leaves, and
/// its cell in `grid` forgets it — a group at a time, as judge_group asks.
template <class Produce>
void forget_in_groups(CellCounts& counts, const WorldGrid& grid, Produce&& produce) {
  std::array<std::array<float, 3>, kDensityGroup> points;
  std::array<std::uint64_t, kDensityGroup> keys{};
  std::size_t held = 0;
  const auto forget = [&] {
    find_cells(grid, points.data(), keys.data(), held);
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
