// guess_cell_codes, the cells a few levels below a lattice cell for many points in vector code,
// against the octant tests the tree descends by: wherever a guess is sure it names the cell those
// tests lead to, on walls, a float below them and between them, near the lattice's origin and far
// from it; points outside the cell, and NaN, are never sure. The subcells read off the codes are
// the ones the quarter walls give.

#include "core/geometry/cell_codes.hpp"
#include "core/geometry/geometry.hpp"
#include "core/storage/point_store.hpp"
#include "core/geometry/subcells.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

/// The code the octant tests give for p below `cell`, `levels` deep, shifted as `grid` shifts.
std::uint32_t descended_code(const Lattice& lattice, Cell cell, int levels, const std::array<float, 3>& p, int shift) {
  std::uint32_t code = 0;
  for (int level = 0; level < levels; ++level) {
    const int octant = lattice.octant(cell, p);
    code |= std::uint32_t(octant) << (3 * (levels - 1 - level));
    cell = lattice.child(cell, octant);
  }
  return code << shift;
}

/// A point inside `cell`, on each axis on one of the walls `step` lattice units apart below it (the
/// first float at or above the wall), or halfway to the next wall, or (kinds 3) the float above
/// the wall's: each of the `kinds` as likely.
BarePoint point_on_walls(const Lattice& lattice, const Cell& cell, std::int64_t step, std::mt19937& rng, int kinds) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::uniform_int_distribution<std::int64_t> wall(0, lattice.side(cell.depth) / step - 1);
  BarePoint b;
  for (int a = 0; a < 3; ++a) {
    const double w = lattice.wall(a, cell.lo[a] + wall(rng) * step);
    float f = float(w);
    if (double(f) < w) f = std::nextafter(f, kInf);
    const auto kind = int(rng() % unsigned(kinds));
    if (kind == 1) f = float(w + 0.5 * double(step) * lattice.unit);  // between walls
    if (kind == 2) f = std::nextafter(f, kInf);
    b.p[std::size_t(a)] = f;
  }
  return b;
}

TEST(CellCodes, CompactBitsUndoesSpreadBits) {
  for (std::uint32_t j = 0; j < (1u << kCodeLevels); ++j) {
    EXPECT_EQ(compact_bits(spread_bits(j)), j);
    EXPECT_EQ(compact_bits(spread_bits(j) << 1 | spread_bits(63 - j) << 2 | spread_bits(j)), j);  // other axes ignored
  }
}

TEST(CellCodes, SureGuessesNameTheCellsTheOctantTestsLeadTo) {
  struct Case {
    std::array<double, 3> origin;
    double unit;
    int max_depth;
  };
  const std::vector<Case> cases{{{0.0, 0.0, 0.0}, 0.05, 9},
                                {{-10.3, 5.1, 0.7}, 0.0390625, 10},
                                {{2047.9, -1999.3, 3.1}, 0.07, 8},
                                {{0.1, 0.2, 0.3}, 0.123, 6}};
  std::mt19937 rng(3);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (const Case& c : cases) {
    Lattice lattice;
    lattice.origin = c.origin;
    lattice.unit = c.unit;
    lattice.max_depth = c.max_depth;
    for (int depth = 0; depth < c.max_depth; ++depth) {
      const int levels = std::min(kCodeLevels, c.max_depth - depth);
      const std::int64_t side = lattice.side(depth), step = lattice.side(depth + levels);
      std::uniform_int_distribution<std::int64_t> which(-3, 3);
      const Cell cell{{which(rng) * side, which(rng) * side, which(rng) * side}, depth};
      CodeGrid grid;
      grid.cells = 1u << levels;
      grid.shift = 3 * (kCodeLevels - levels);
      for (int a = 0; a < 3; ++a) {
        grid.low[std::size_t(a)] = lattice.wall(a, cell.lo[a]);
        grid.inverse[std::size_t(a)] = 1.0 / (double(step) * lattice.unit);
      }
      std::uniform_int_distribution<std::int64_t> wall(0, side);
      std::uniform_real_distribution<double> inside(0.0, 1.0);
      for (const std::size_t stride : {std::size_t{3}, std::size_t{7}}) {
        const std::size_t n = 200;
        std::vector<float> data(n * stride, -1.0f);
        std::vector<std::array<float, 3>> points(n);
        std::vector<std::uint8_t> inside_cell(n, 1);
        for (std::size_t i = 0; i < n; ++i) {
          for (int a = 0; a < 3; ++a) {
            float f = 0.0f;
            const int choice = i >= n / 2 ? 3 : int(rng() % 4);  // the second half: random points alone
            if (choice == 3) {  // anywhere in the cell
              f = float(lattice.wall(a, cell.lo[a]) + inside(rng) * double(side) * lattice.unit);
            } else {  // on a wall of the finest cells (or the float below one), the cell's own too
              const double w = lattice.wall(a, cell.lo[a] + wall(rng) / step * step);
              f = float(w);
              if (double(f) < w) f = std::nextafter(f, kInf);
              if (choice == 1) f = std::nextafter(f, -kInf);
            }
            points[i][std::size_t(a)] = f;
          }
          if (i % 50 == 7) points[i][0] = std::numeric_limits<float>::quiet_NaN();
          inside_cell[i] = std::uint8_t(points[i][0] == points[i][0] && lattice.contains(cell, points[i]));
          for (std::size_t a = 0; a < 3; ++a) data[i * stride + a] = points[i][a];
        }
        std::vector<std::uint32_t> codes(n + 1, 7);
        std::vector<std::uint8_t> unsure(n + 1, 7);
        guess_cell_codes(grid, data.data(), stride, n, codes.data(), unsure.data());
        std::size_t sure_random = 0, random = 0;
        for (std::size_t i = 0; i < n; ++i) {
          if (i >= n / 2 && inside_cell[i]) {
            ++random;
            sure_random += unsure[i] == 0;
          }
          if (unsure[i] != 0) continue;
          ASSERT_TRUE(inside_cell[i]) << "a point outside the cell was sure, depth " << depth;
          ASSERT_EQ(codes[i], descended_code(lattice, cell, levels, points[i], grid.shift))
              << points[i][0] << " " << points[i][1] << " " << points[i][2] << ", depth " << depth << ", stride " << stride;
        }
        EXPECT_EQ(codes[n], 7u) << "wrote past the points";
        EXPECT_EQ(unsure[n], 7u) << "wrote past the points";
        // a random coordinate lies within 2^-12 of a wall once in 2^11
        EXPECT_GE(sure_random, random * 95 / 100) << "depth " << depth << ", stride " << stride;
      }
    }
  }
}

TEST(CellCodes, FoundCodesAreTheOctantTestsForEveryPoint) {
  // find_cell_codes: the guesses where sure, the walls elsewhere, and the walls alone for a grid
  // too far out for guesses (as if its walls lay beyond 2^36 of its cells)
  const Lattice lattice{{-3.3, 1.7, 0.4}, 0.05, 9};
  std::mt19937 rng(8);
  for (const int depth : {0, 3, 5}) {
    const int levels = std::min(kCodeLevels, lattice.max_depth - depth);
    const Cell cell{{-lattice.side(depth), 0, 2 * lattice.side(depth)}, depth};
    const std::int64_t step = lattice.side(depth + levels);
    std::vector<BarePoint> bare;
    std::vector<StoredPoint> stored;
    for (int i = 0; i < 500; ++i) {
      const BarePoint b = point_on_walls(lattice, cell, step, rng, 2);
      ASSERT_TRUE(lattice.contains(cell, b.p));
      bare.push_back(b);
      stored.push_back(StoredPoint{b.p, 7, 8, 9.0f, 10.0f});
    }
    for (const bool guessable : {true, false}) {
      CodeGrid grid = code_grid(lattice, cell, levels, 3 * (kCodeLevels - levels));
      ASSERT_TRUE(grid.guessable);
      grid.guessable = guessable;
      std::vector<std::uint32_t> from_bare(bare.size()), from_stored(bare.size());
      std::vector<std::uint8_t> unsure(bare.size());
      find_cell_codes(lattice, cell, grid, bare.data(), bare.size(), from_bare.data(), unsure.data());
      find_cell_codes(lattice, cell, grid, stored.data(), stored.size(), from_stored.data(), unsure.data());
      for (std::size_t i = 0; i < bare.size(); ++i) {
        const std::uint32_t want = descended_code(lattice, cell, levels, bare[i].p, grid.shift);
        ASSERT_EQ(from_bare[i], want) << "depth " << depth << ", point " << i << (guessable ? "" : ", walls alone");
        ASSERT_EQ(from_stored[i], want) << "depth " << depth << ", point " << i << (guessable ? "" : ", walls alone");
      }
    }
  }
}

TEST(CellCodes, SubcellsOfCodesAreTheQuarterCellsTheWallsGive) {
  // every cell some levels below the coded one (with two coded levels below it), its points' codes
  // against Subcells' comparisons, for points on the walls, a float above them and between them
  const Lattice lattice{{-1023.95, 2047.3, -511.05}, 0.05, 9};
  std::mt19937 rng(11);
  for (const int depth : {0, 3, 5}) {
    const int levels = std::min(kCodeLevels, lattice.max_depth - depth);
    const Cell cell{{3 * lattice.side(depth), -lattice.side(depth), 0}, depth};
    const std::int64_t step = lattice.side(depth + levels);
    std::vector<BarePoint> points(3000);
    for (BarePoint& b : points) b = point_on_walls(lattice, cell, step, rng, 3);
    const CodeGrid grid = code_grid(lattice, cell, levels, 3 * (kCodeLevels - levels));
    std::vector<std::uint32_t> codes(points.size());
    std::vector<std::uint8_t> unsure(points.size());
    find_cell_codes(lattice, cell, grid, points.data(), points.size(), codes.data(), unsure.data());
    for (int level = 0; level + 2 <= levels; ++level) {
      std::map<std::array<std::int64_t, 3>, std::vector<std::size_t>> by_cell;  // the points of each cell `level` down
      for (std::size_t i = 0; i < points.size(); ++i) {
        Cell c = cell;
        for (int l = 0; l < level; ++l) c = lattice.child(c, lattice.octant(c, points[i].p));
        by_cell[c.lo].push_back(i);
      }
      for (const auto& [lo, members] : by_cell) {
        const Cell c{lo, depth + level};
        std::vector<std::uint32_t> their_codes;
        std::uint64_t want = 0;
        for (const std::size_t i : members) {
          their_codes.push_back(codes[i]);
          want |= std::uint64_t{1} << Subcells(lattice, c).of(points[i].p);
        }
        const int shift = grid.shift + 3 * (levels - 2 - level);
        ASSERT_EQ(subcells_of_codes(their_codes.data(), their_codes.size(), shift), want)
            << "depth " << depth << ", level " << level;
      }
    }
  }
}

}  // namespace
}  // namespace eco::detail
