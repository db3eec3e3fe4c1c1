// CellCounts, the density cap's per-cell counts, against a std::map: random adds, capped adds
// and removals (which shift later members of a probe run back), through several growths, at every
// width of count (the cap's bits) and past it (the side table); and the group form of the capped
// add, key after key as the map counts them.

#include "core/density/cell_counts.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

class CellCountsOfCap : public ::testing::TestWithParam<std::uint32_t> {};

TEST_P(CellCountsOfCap, MatchesAMapThroughAddsCapsRemovalsAndGrowth) {
  const std::uint32_t cap = GetParam();
  CellCounts counts(cap);
  std::map<std::uint64_t, std::uint32_t> expected;
  std::mt19937_64 rng(3 + cap);
  std::uniform_int_distribution<std::int64_t> cell(-40, 40);  // few cells: long probe runs
  for (int step = 0; step < 200000; ++step) {
    const std::uint64_t key = CellCounts::key({cell(rng), cell(rng), cell(rng) / 8});
    const int op = int(rng() % 4);
    if (op == 0 && expected.count(key) > 0) {
      counts.remove(key);
      if (--expected[key] == 0) expected.erase(key);
    } else {
      // up to the cap and past it: counts past their bits live in the side table
      const std::uint32_t limit = std::uint32_t(rng() % (cap + 3));
      const bool added = counts.add_below(key, limit);
      const std::uint32_t had = expected.count(key) ? expected[key] : 0;
      ASSERT_EQ(added, had < limit) << step;
      if (added) ++expected[key];
    }
    if (step % 997 == 0) {
      ASSERT_EQ(counts.cells(), expected.size());
      for (const auto& [k, n] : expected) ASSERT_EQ(counts.count(k), n);
    }
  }
  std::size_t seen = 0;
  counts.for_each([&](std::uint64_t k, std::uint32_t n) {
    ++seen;
    EXPECT_EQ(expected.at(k), n);
  });
  EXPECT_EQ(seen, expected.size());
  counts.remove(CellCounts::key({1000, 1000, 1000}));  // a cell holding nothing: no effect
  EXPECT_EQ(counts.cells(), expected.size());
  for (const auto& [k, n] : expected) {  // emptied to the last point: every block leaves the table
    for (std::uint32_t i = 0; i < n; ++i) counts.remove(k);
  }
  EXPECT_EQ(counts.cells(), 0u);
  counts.for_each([](std::uint64_t, std::uint32_t) { ADD_FAILURE() << "a cell left after emptying"; });
}

TEST(CellCounts, NeighbouringCellsShareABlockAcrossTheWrap) {
  // 4 x 4 x 4 cells either side of the 2^18 wrap of each axis: distinct cells, each counted alone
  CellCounts counts(1);
  const std::size_t empty = counts.bytes();
  std::map<std::uint64_t, std::uint32_t> expected;
  for (std::int64_t x = -4; x < 4; ++x) {
    for (std::int64_t y = -4; y < 4; ++y) {
      for (std::int64_t z = -4; z < 4; ++z) {
        const std::uint64_t key = CellCounts::key({x, y, z});
        ASSERT_TRUE(counts.add_below(key, 1));
        ASSERT_FALSE(counts.add_below(key, 1));
        expected[key] = 1;
      }
    }
  }
  EXPECT_EQ(counts.cells(), 512u);
  for (const auto& [key, n] : expected) ASSERT_EQ(counts.count(key), n);
  EXPECT_EQ(counts.count(CellCounts::key({4, 0, 0})), 0u);
  // 512 cells in 8 blocks: the first table (256 slots of a tag and one word) is enough
  EXPECT_EQ(counts.bytes(), std::size_t(256 * 2 * 8));
  EXPECT_EQ(empty, 0u);
}

TEST_P(CellCountsOfCap, GroupedAddsAreTheMapsKeyAfterKey) {
  const std::uint32_t cap = GetParam();
  CellCounts counts(cap);
  std::map<std::uint64_t, std::uint32_t> expected;
  std::mt19937_64 rng(8 + cap);
  std::uniform_int_distribution<std::int64_t> cell(-30, 30);
  std::vector<std::uint64_t> keys;
  std::vector<std::uint8_t> passed;
  for (int group = 0; group < 3000; ++group) {
    const std::size_t n = std::size_t(rng() % 130);  // empty groups too; growth inside a group
    const std::uint32_t limit = std::uint32_t(rng() % std::min(cap + 3, 5u));  // the repeats' rule at 1 and 2
    keys.clear();
    for (std::size_t i = 0; i < n; ++i) {
      // runs of one cell as well as scattered cells: a key repeats within its group
      keys.push_back(i > 0 && rng() % 3 == 0 ? keys.back() : CellCounts::key({cell(rng), cell(rng), cell(rng) / 6}));
    }
    passed.assign(n + 1, 7);
    const std::size_t counted = counts.add_below_each(keys.data(), n, limit, passed.data());
    std::size_t expected_counted = 0;
    for (std::size_t i = 0; i < n; ++i) {
      std::uint32_t& had = expected[keys[i]];
      expected_counted += had < limit ? 1 : 0;
      ASSERT_EQ(passed[i], had < limit ? 1 : 0) << "group " << group << ", key " << i;
      if (had < limit) ++had;
      if (had == 0) expected.erase(keys[i]);
    }
    ASSERT_EQ(passed[n], 7) << "wrote past the group";
    ASSERT_EQ(counted, expected_counted) << "group " << group;
    if (group % 7 == 0 && !expected.empty()) {  // removals between groups shift probe runs back
      const std::uint64_t key = expected.begin()->first;
      counts.remove(key);
      if (--expected[key] == 0) expected.erase(key);
    }
  }
  ASSERT_EQ(counts.cells(), expected.size());
  for (const auto& [key, n] : expected) ASSERT_EQ(counts.count(key), n);
}

// 1, 2, 4, 8 and 16 bits a count
INSTANTIATE_TEST_SUITE_P(Widths, CellCountsOfCap, ::testing::Values(1u, 2u, 3u, 9u, 200u, 1023u));

TEST(CellCounts, EightVerdictsBecomeTheirBitsInOrder) {
  for (unsigned pattern = 0; pattern < 256; ++pattern) {
    std::uint64_t eight = 0;  // byte b is bit b of the pattern
    for (int b = 0; b < 8; ++b) eight |= std::uint64_t((pattern >> b) & 1u) << (8 * b);
    ASSERT_EQ(verdict_bits(eight), pattern) << "pattern " << pattern;
  }
}

TEST(CellCounts, KeysWrapModulo2To18PerAxis) {
  EXPECT_EQ(CellCounts::key({-1, 0, 0}), CellCounts::key({(1 << 18) - 1, 0, 0}));
  EXPECT_NE(CellCounts::key({1, 0, 0}), CellCounts::key({0, 1, 0}));
  EXPECT_NE(CellCounts::key({0, 0, 1}), CellCounts::key({0, 1, 0}));
}

}  // namespace
}  // namespace eco::detail
