// Subcells (src/core/geometry/subcells.hpp): a leaf's occupied quarter-cells as one word, against the
// lattice's own descent two levels down (one level for a cell two units wide), for points on the
// walls, the float just below them and between them, and for runs of points.

#include "core/geometry/subcells.hpp"
#include "support/float_walls.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

using test::first_float_at_or_above;

/// The subcell bit of p by descending the lattice: two levels for cells four units wide or more;
/// a cell two units wide has one level below it, its halves, which are quarters 1 and 3 (the
/// quarter walls lo, lo + 1, lo + 1).
int descended_subcell(const Lattice& lattice, const Cell& cell, const std::array<float, 3>& p) {
  const int levels = lattice.side(cell.depth) >= 4 ? 2 : 1;
  Cell c = cell;
  for (int l = 0; l < levels; ++l) c = lattice.child(c, lattice.octant(c, p));
  const std::int64_t step = lattice.side(c.depth);
  int bit = 0;
  for (int a = 0; a < 3; ++a) {
    const int along = int((c.lo[a] - cell.lo[a]) / step) * (levels == 2 ? 1 : 2) + (levels == 2 ? 0 : 1);
    bit |= along << (2 * a);
  }
  return bit;
}

struct Points {
  std::vector<float> x, y, z;
  [[nodiscard]] std::array<float, 3> at(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

/// Points inside `cell`: uniform, and on or just below each of its lattice walls along one axis.
Points points_in(const Lattice& lattice, const Cell& cell, std::mt19937& rng) {
  const std::int64_t side = lattice.side(cell.depth);
  std::uniform_real_distribution<double> inside(0.0, 1.0);
  std::uniform_int_distribution<std::int64_t> wall(1, side);
  std::uniform_int_distribution<int> axis(0, 2);
  Points out;
  for (int i = 0; i < 300; ++i) {
    std::array<float, 3> p{};
    for (int a = 0; a < 3; ++a) p[a] = float(lattice.wall(a, cell.lo[a]) + inside(rng) * double(side) * lattice.unit);
    if (i % 3 != 0) {
      const int a = axis(rng);
      const float on = first_float_at_or_above(lattice.wall(a, cell.lo[a] + wall(rng) - (i % 3 == 1 ? 0 : 1)));
      p[std::size_t(a)] = i % 2 == 0 ? on : std::nextafter(on, -std::numeric_limits<float>::infinity());
    }
    if (!lattice.contains(cell, p)) continue;  // a wall's float below the cell's own lower wall
    out.x.push_back(p[0]);
    out.y.push_back(p[1]);
    out.z.push_back(p[2]);
  }
  return out;
}

TEST(Subcells, EachPointNamesTheQuarterCellTheLatticeDescendsTo) {
  for (const std::array<double, 3> origin : {std::array<double, 3>{-3.3, 1.7, 0.4}, std::array<double, 3>{-1023.95, 2047.3, -511.05}}) {
    const Lattice lattice{origin, 0.05, 9};
    std::mt19937 rng(5);
    for (int depth = 2; depth <= 8; ++depth) {
      const std::int64_t side = lattice.side(depth);
      std::uniform_int_distribution<std::int64_t> at(0, (std::int64_t{1} << depth) - 1);
      for (int trial = 0; trial < 20; ++trial) {
        const Cell cell{{at(rng) * side, at(rng) * side, at(rng) * side}, depth};
        const Points pts = points_in(lattice, cell, rng);
        ASSERT_GT(pts.x.size(), 150u);
        const Subcells walls(lattice, cell);
        for (std::size_t i = 0; i < pts.x.size(); ++i) {
          ASSERT_EQ(walls.of(pts.at(i)), descended_subcell(lattice, cell, pts.at(i))) << "depth " << depth << ", point " << i;
        }
      }
    }
  }
}

TEST(Subcells, BitsOfARunAreItsPointsSubcells) {
  const Lattice lattice{{-3.3, 1.7, 0.4}, 0.05, 9};
  std::mt19937 rng(8);
  const Cell cell{{64, 128, 32}, 4};  // 32 units a side
  const Points pts = points_in(lattice, cell, rng);
  struct Stored {
    std::array<float, 3> p;
  };
  std::vector<Stored> run;
  for (std::size_t i = 0; i < pts.x.size(); ++i) run.push_back({pts.at(i)});
  const Subcells walls(lattice, cell);
  for (std::size_t begin = 0; begin < run.size(); begin += 7) {
    for (std::size_t end = begin; end <= run.size(); end += 1 + end / 8) {
      std::uint64_t want = 0;
      for (std::size_t i = begin; i < end; ++i) want |= std::uint64_t{1} << descended_subcell(lattice, cell, run[i].p);
      ASSERT_EQ(walls.bits(run.data() + begin, run.data() + end), want) << begin << ".." << end;
    }
  }
}

TEST(Subcells, HalvedSeesEachQuarterInItsHalf) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    std::uint64_t bits = rng() & rng();  // sparse and dense words
    if (trial < 64) bits = std::uint64_t{1} << trial;
    unsigned want = 0;
    for (int b = 0; b < 64; ++b) {
      if (bits >> b & 1) want |= 1u << ((b & 3) / 2 + ((b >> 2 & 3) / 2) * 2 + ((b >> 4) / 2) * 4);
    }
    ASSERT_EQ(unsigned(halved(bits)), want) << std::hex << bits;
  }
}

}  // namespace
}  // namespace eco::detail
