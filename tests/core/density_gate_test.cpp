// pass_density_cap, the density cap over a stream of new points judged a group at a time, against
// the rule applied one point after another with a std::map of counts: the same points pass, in
// the same order, for streams shorter than, equal to and longer than a group, with cells already
// partly full, and the counts it leaves are the map's. forget_in_groups leaves the map's counts too.

#include "core/density_gate.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

struct Offered {
  int id;
  std::array<float, 3> p;
};

TEST(DensityGate, PassesWhatTheRuleOneByOnePassesInOrder) {
  const WorldGrid grid({12.5, -3.25, 0.75}, 0.2);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);  // ~10 cells an axis: cells fill up
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, kDensityGroup - 1, kDensityGroup,
                              kDensityGroup + 1, 5 * kDensityGroup + 7}) {
    for (const std::uint32_t limit : {0u, 1u, 3u}) {
      std::vector<Offered> stream;
      for (std::size_t i = 0; i < n; ++i) stream.push_back({int(i), {coordinate(rng), coordinate(rng), coordinate(rng)}});
      // some cells hold points already: the first few of the stream, counted beforehand
      CellCounts counts;
      std::map<std::uint64_t, std::uint32_t> expected;
      for (std::size_t i = 0; i < std::min<std::size_t>(n, 5); ++i) {
        const std::uint64_t key = CellCounts::key(grid.index(stream[i].p));
        counts.add(key);
        ++expected[key];
      }
      std::vector<int> want;
      std::size_t want_refused = 0;
      for (const Offered& o : stream) {
        std::uint32_t& held = expected[CellCounts::key(grid.index(o.p))];
        if (held < limit) {
          ++held;
          want.push_back(o.id);
        } else {
          ++want_refused;
        }
      }
      std::vector<int> got;
      const std::size_t refused = pass_density_cap<Offered>(
          counts, grid, limit, [&](auto&& offer) { for (const Offered& o : stream) offer(o, o.p); },
          [&](const Offered& o) { got.push_back(o.id); });
      EXPECT_EQ(got, want) << n << " points, limit " << limit;
      EXPECT_EQ(refused, want_refused) << n << " points, limit " << limit;
      for (const auto& [key, held] : expected) EXPECT_EQ(counts.count(key), held);
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
