// WorldGrid and world_grid_index against the contract's rule found by bisection: the cell i of a
// stored coordinate f is the largest i with i*size - origin <= f (double walls). Sampled at random
// and exactly on walls (the first float at or above a wall and the float before it), for sizes
// that are not binary fractions and origins far from the world's.

#include "core/geometry/geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

/// The largest i in [-2^40, 2^40] with double(i) * size - origin <= f: the rule, by bisection.
std::int64_t cell_by_bisection(double origin, float stored, double size) {
  const double f = stored;
  std::int64_t lo = -(std::int64_t{1} << 40), hi = std::int64_t{1} << 40;  // rule holds at lo, fails at hi
  while (hi - lo > 1) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    (double(mid) * size - origin <= f ? lo : hi) = mid;
  }
  return lo;
}

/// Stored coordinates within `reach` of the anchor: random ones and both sides of every wall
/// near a few random ones.
std::vector<float> samples(double origin, double size, double reach, std::mt19937& rng) {
  std::vector<float> out;
  std::uniform_real_distribution<double> u(-reach, reach);
  for (int n = 0; n < 2000; ++n) {
    const float f = float(u(rng));
    out.push_back(f);
    const double i = std::floor((origin + f) / size);
    for (double k = i - 1; k <= i + 2; ++k) {
      const double wall = k * size - origin;
      float at = float(wall);
      if (double(at) < wall) at = std::nextafter(at, std::numeric_limits<float>::infinity());
      out.push_back(at);
      out.push_back(std::nextafter(at, -std::numeric_limits<float>::infinity()));
    }
  }
  return out;
}

struct GridCase {
  std::array<double, 3> origin;
  double size;
  double reach;
};

TEST(WorldGrid, AgreesWithTheRuleOnAndBetweenWalls) {
  const std::vector<GridCase> cases{
      {{0.0, 0.0, 0.0}, 0.1, 30.0},
      {{-10.3, 5.1, 0.7}, 0.2, 30.0},
      {{4096.0, -8192.0, 2048.0}, 1.0 / 3.0, 40.0},
      {{4.0e6, -3.5e6, 1.0e5}, 0.05, 60.0},
      {{123.456, -0.001, 7.0}, 1e-3, 20.0},
      {{0.0, 0.0, 0.0}, 7.3, 200.0},
      {{500.0, -500.0, 0.0}, 1e-9, 100.0},  // points ~1e11 cells from the origin's: guesses below 0 truncate up
  };
  std::mt19937 rng(7);
  for (const GridCase& c : cases) {
    const WorldGrid grid(c.origin, c.size);
    for (int a = 0; a < 3; ++a) {
      for (const float f : samples(c.origin[a], c.size, c.reach, rng)) {
        const std::int64_t want = cell_by_bisection(c.origin[a], f, c.size);
        ASSERT_EQ(grid.index(a, f), want) << "size " << c.size << " origin " << c.origin[a] << " f " << f;
        ASSERT_EQ(world_grid_index(c.origin[a], f, c.size), want) << "size " << c.size << " f " << f;
      }
    }
  }
}

TEST(WorldGrid, IndexesAPointPerAxis) {
  const WorldGrid grid({1.0, -2.0, 0.5}, 0.5);
  const std::array<float, 3> p{0.2f, 2.1f, -0.5f};
  const std::array<std::int64_t, 3> want{cell_by_bisection(1.0, p[0], 0.5), cell_by_bisection(-2.0, p[1], 0.5),
                                         cell_by_bisection(0.5, p[2], 0.5)};
  EXPECT_EQ(grid.index(p), want);
  EXPECT_EQ(want, (std::array<std::int64_t, 3>{2, 0, 0}));  // 1.2 / 0.5, 0.1 / 0.5, 0.0 / 0.5
}

}  // namespace
}  // namespace eco::detail
