// judge_group, the density cap over a stream of new points judged a group at a time, against the
// rule applied one point after another with a std::map of counts: the same points pass, in the
// same order, for streams shorter than, equal to and longer than a group, in groups of every size,
// with cells already partly full, and the counts it leaves are the map's; with the cap off every
// point passes. forget_in_groups leaves the map's counts too.
// The cells' keys guessed in vector code are WorldGrid's, on walls and off them, near the world's
// origin and far from it.

#include "core/density/density_gate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

/// A coordinate on a wall of `grid`'s axis near f (the first float at or above it), or the float
/// before it, or f itself.
float near_wall(const WorldGrid& grid, int axis, double size, float f, int choice) {
  const double origin = grid.axis(axis).origin;
  const double wall = std::floor((origin + f) / size) * size - origin;
  float at = float(wall);
  if (double(at) < wall) at = std::nextafter(at, std::numeric_limits<float>::infinity());
  return choice == 0 ? f : choice == 1 ? at : std::nextafter(at, -std::numeric_limits<float>::infinity());
}

TEST(DensityGate, GuessedKeysAreTheGridsKeys) {
  struct Case {
    std::array<double, 3> origin;
    double size;
    double reach;
    bool mostly_sure;
  };
  const std::vector<Case> cases{{{0.0, 0.0, 0.0}, 0.1, 30.0, true},
                                {{-10.3, 5.1, 0.7}, 0.2, 30.0, true},
                                {{4.0e6, -3.5e6, 1.0e5}, 0.05, 60.0, true},
                                {{123.456, -0.001, 7.0}, 1e-3, 20.0, true},
                                {{500.0, -500.0, 0.0}, 1e-9, 100.0, false}};  // ~1e11 cells out: beyond kReach
  std::mt19937 rng(17);
  for (const Case& c : cases) {
    const WorldGrid grid(c.origin, c.size);
    std::uniform_real_distribution<double> u(-c.reach, c.reach);
    std::uniform_int_distribution<int> choice(0, 2);
    std::vector<std::array<float, 3>> points;
    for (int i = 0; i < 20000; ++i) {
      std::array<float, 3> p{};
      for (int a = 0; a < 3; ++a) p[a] = near_wall(grid, a, c.size, float(u(rng)), choice(rng));
      points.push_back(p);
    }
    std::size_t sure = 0;
    std::array<std::uint64_t, kDensityGroup> keys{};
    std::array<std::uint8_t, kDensityGroup> unsure{};
    for (std::size_t begin = 0; begin < points.size();) {
      const std::size_t n = std::min(points.size() - begin, 1 + begin % kDensityGroup);
      guess_cell_keys(grid, &points[begin], n, keys.data(), unsure.data());
      for (std::size_t i = 0; i < n; ++i) {
        const std::array<float, 3>& p = points[begin + i];
        if (unsure[i] == 0) {
          ASSERT_EQ(keys[i], CellCounts::key(grid.index(p))) << p[0] << " " << p[1] << " " << p[2] << ", size " << c.size;
          ++sure;
        }
      }
      find_cells(grid, &points[begin], keys.data(), n);
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(keys[i], CellCounts::key(grid.index(points[begin + i])));
      begin += n;
    }
    // two thirds of the coordinates lie on a wall or a float below it: those are left unsure
    if (c.mostly_sure) {
      EXPECT_GT(sure, points.size() / 40) << "size " << c.size;  // the fully random points at least
    } else {
      EXPECT_EQ(sure, 0u);
    }
  }
}

TEST(DensityGate, KeysGuessedInSinglePrecisionAreTheGridsKeys) {
  // Grids seen from an ego box (centre, half side): the float guesses where the box spans at most
  // 2^8 cells either side and lies within 2^34 cells of the world's origin, the double ones else.
  struct Case {
    std::array<double, 3> origin, centre;
    double size, reach;
    bool ready;
  };
  const std::vector<Case> cases{
      {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, 0.1, 10.0, true},
      {{-10.3, 5.1, 0.7}, {2047.5, -1999.25, 3.0}, 0.3, 10.0, true},         // the box far from the origin
      {{4.0e6, -3.5e6, 1.0e5}, {-300.1, 12.7, -0.4}, 0.07, 10.0, true},      // 1e8 cells out
      {{1.5e9, -1.6e9, 1.7e9}, {1000.0, -1000.0, 3.0}, 0.15, 10.0, true},    // near 2^34 cells
      {{1.8e9, 0.0, 0.0}, {0.0, 0.0, 0.0}, 0.1, 10.0, false},                // beyond 2^34: none sure
      {{2.0e9, 0.0, 0.0}, {-2.0e9, 0.0, 0.0}, 0.1, 10.0, false},             // the box near, the origin not
      {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, 0.02, 10.0, false},                 // 500 cells either side
      {{123.456, -0.001, 7.0}, {5.0, 5.0, 5.0}, 0.123, 31.0, true}};         // 1 / size not a float
  std::mt19937 rng(29);
  for (const Case& c : cases) {
    SCOPED_TRACE("size " + std::to_string(c.size) + ", origin " + std::to_string(c.origin[0]));
    const WorldGrid grid(c.origin, c.size, c.centre, c.reach);
    ASSERT_EQ(grid.single().ready, c.ready);
    // inside the box and up to twice as far (the points a frame drops lie next to it)
    // points on walls (or a float below one) and off them, inside the box and up to twice as far
    // (the points a frame drops lie next to it) or far beyond, where a float's rounding is
    // coarser than kSure; then random points inside the box alone
    std::uniform_real_distribution<double> near(-2 * c.reach, 2 * c.reach), far(-200 * c.reach, 200 * c.reach),
        in(-c.reach, c.reach);
    std::uniform_int_distribution<int> choice(0, 2);
    std::array<std::uint64_t, kDensityGroup> keys{};
    std::array<std::uint8_t, kDensityGroup> unsure{};
    std::array<std::array<float, 3>, kDensityGroup> points{};
    std::size_t sure_random = 0, random = 0;
    for (int group = 0; group < 1000; ++group) {
      const bool on_walls = group % 2 == 0;
      for (std::array<float, 3>& p : points) {
        for (std::size_t a = 0; a < 3; ++a) {
          const double d = !on_walls ? in(rng) : group % 4 == 0 ? near(rng) : far(rng);
          const float f = float(c.centre[a] + d);
          p[a] = on_walls ? near_wall(grid, int(a), c.size, f, choice(rng)) : f;
        }
      }
      guess_cell_keys(grid, points.data(), points.size(), keys.data(), unsure.data());
      for (std::size_t i = 0; i < points.size(); ++i) {
        const std::array<float, 3>& p = points[i];
        if (unsure[i] == 0) {
          ASSERT_EQ(keys[i], CellCounts::key(grid.index(p))) << p[0] << " " << p[1] << " " << p[2];
        }
        if (!on_walls) {
          ++random;
          sure_random += unsure[i] == 0;
        }
      }
    }
    // a random coordinate lies within 2^-12 of a wall once in 2^11: nearly every such point is sure,
    // unless the grid lies too far out for any guess
    if (c.origin[0] < 0x1p34 * c.size) {
      EXPECT_GT(sure_random, random * 99 / 100);
    } else {
      EXPECT_EQ(sure_random, 0u);
    }
  }
}

TEST(DensityGate, JudgesGroupsAsTheRuleJudgesOnePointAfterAnother) {
  const WorldGrid grid({12.5, -3.25, 0.75}, 0.2);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);  // ~10 cells an axis: cells fill up
  std::uniform_real_distribution<float> step(-0.03f, 0.03f);
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, kDensityGroup - 1, kDensityGroup,
                              kDensityGroup + 1, 5 * kDensityGroup + 7}) {
    for (const std::uint32_t limit : {0u, 1u, 3u}) {
      std::vector<std::array<float, 3>> stream;
      for (std::size_t i = 0; i < n; ++i) {
        // scattered, and in walks of small steps as a scan meets its cells: runs of one cell
        if (i > 0 && rng() % 8 != 0) {
          const std::array<float, 3>& p = stream.back();
          stream.push_back({p[0] + step(rng), p[1] + step(rng), p[2] + step(rng)});
        } else {
          stream.push_back({coordinate(rng), coordinate(rng), coordinate(rng)});
        }
      }
      // some cells hold points already: the first few of the stream, counted beforehand
      CellCounts counts;
      std::map<std::uint64_t, std::uint32_t> expected;
      for (std::size_t i = 0; i < std::min<std::size_t>(n, 5); ++i) {
        const std::uint64_t key = CellCounts::key(grid.index(stream[i]));
        counts.add(key);
        ++expected[key];
      }
      std::vector<std::uint8_t> want;
      std::size_t want_refused = 0;
      for (const auto& p : stream) {
        std::uint32_t& held = expected[CellCounts::key(grid.index(p))];
        want.push_back(held < limit ? 1 : 0);
        if (held < limit) {
          ++held;
        } else {
          ++want_refused;
        }
      }
      // groups of every size up to a whole one, one after another
      std::vector<std::uint8_t> got(n);
      std::size_t refused = 0;
      for (std::size_t begin = 0, size = 1; begin < n; begin += size, size = size % kDensityGroup + 1) {
        size = std::min(size, n - begin);
        refused += judge_group(counts, grid, limit, &stream[begin], size, &got[begin]);
      }
      EXPECT_EQ(got, want) << n << " points, limit " << limit;
      EXPECT_EQ(refused, want_refused) << n << " points, limit " << limit;
      for (const auto& [key, held] : expected) EXPECT_EQ(counts.count(key), held);
    }
  }
}

TEST(DensityGate, EveryPointPassesWhileTheCapIsOff) {
  const WorldGrid grid({0.0, 0.0, 0.0}, 0.2);
  const std::vector<std::array<float, 3>> points(kDensityGroup, {0.05f, 0.05f, 0.05f});  // one cell
  CellCounts counts;
  std::vector<std::uint8_t> passed(points.size(), 0);
  EXPECT_EQ(judge_group(counts, grid, DensityCap{}, points.data(), points.size(), passed.data()), 0u);
  EXPECT_EQ(passed, std::vector<std::uint8_t>(points.size(), 1));
  EXPECT_EQ(counts.cells(), 0u);  // counted nowhere
  EXPECT_EQ(judge_group(counts, grid, DensityCap{0.2, 2}, points.data(), points.size(), passed.data()),
            points.size() - 2);
  EXPECT_EQ(counts.count(CellCounts::key(grid.index(points[0]))), 2u);
}

TEST(DensityGate, WalksThePassedVerdictsInOrderAndNothingBeyondThem) {
  std::mt19937 rng(5);
  for (std::size_t n = 0; n <= kDensityGroup; ++n) {
    for (int density = 0; density <= 4; ++density) {  // none passed, then sparser to all passed
      std::vector<std::uint8_t> passed(kDensityGroup, 1);  // past n: set, and never to be walked
      for (std::size_t i = 0; i < n; ++i) passed[i] = std::uint8_t(int(rng() % 4) < density);
      std::vector<std::size_t> expected, got;
      for (std::size_t i = 0; i < n; ++i) {
        if (passed[i] != 0) expected.push_back(i);
      }
      for_each_set(passed.data(), n, [&](std::size_t i) { got.push_back(i); });
      EXPECT_EQ(got, expected) << n << " verdicts, density " << density;
    }
  }
}

TEST(DensityGate, ForgetsInGroupsWhatLeavesOnePointAtATime) {
  const WorldGrid grid({-4.0, 7.5, 0.25}, 0.2);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  for (const std::size_t leaving : {std::size_t{0}, std::size_t{1}, kDensityGroup, 3 * kDensityGroup + 5}) {
    std::vector<std::array<float, 3>> held;
    for (std::size_t i = 0; i < 4 * kDensityGroup; ++i) held.push_back({coordinate(rng), coordinate(rng), coordinate(rng)});
    CellCounts counts;
    std::map<std::uint64_t, std::uint32_t> expected;
    for (const auto& p : held) {
      counts.add(CellCounts::key(grid.index(p)));
      ++expected[CellCounts::key(grid.index(p))];
    }
    forget_in_groups(counts, grid, [&](auto&& offer) {
      for (std::size_t i = 0; i < leaving; ++i) offer(held[i]);
    });
    for (std::size_t i = 0; i < leaving; ++i) --expected[CellCounts::key(grid.index(held[i]))];
    std::size_t cells = 0;
    for (const auto& [key, n] : expected) {
      EXPECT_EQ(counts.count(key), n) << leaving << " leaving";
      cells += n > 0 ? 1 : 0;
    }
    EXPECT_EQ(counts.cells(), cells) << leaving << " leaving";
  }
}

}  // namespace
}  // namespace eco::detail
