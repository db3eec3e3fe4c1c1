// CellCounts, the density cap's per-cell counts, against a std::map: random adds, capped adds
// and removals (which shift later members of a probe run back), through several growths; and the
// group form of the capped add, key after key as the map counts them.

#include "core/cell_counts.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

TEST(CellCounts, MatchesAMapThroughAddsCapsRemovalsAndGrowth) {
  CellCounts counts;
  std::map<std::uint64_t, std::uint32_t> expected;
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<std::int64_t> cell(-40, 40);  // few cells: long probe runs
  for (int step = 0; step < 200000; ++step) {
    const std::uint64_t key = CellCounts::key({cell(rng), cell(rng), cell(rng) / 8});
    const int op = int(rng() % 4);
    if (op == 0 && expected.count(key) > 0) {
      counts.remove(key);
      if (--expected[key] == 0) expected.erase(key);
    } else {
      const std::uint32_t limit = std::uint32_t(rng() % 4);
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
}

TEST(CellCounts, GroupedAddsAreTheMapsKeyAfterKey) {
  CellCounts counts;
  std::map<std::uint64_t, std::uint32_t> expected;
  std::mt19937_64 rng(8);
  std::uniform_int_distribution<std::int64_t> cell(-30, 30);
  std::vector<std::uint64_t> keys;
  std::vector<std::uint8_t> passed;
  for (int group = 0; group < 3000; ++group) {
    const std::size_t n = std::size_t(rng() % 130);  // empty groups too; growth inside a group
    const std::uint32_t limit = std::uint32_t(rng() % 4);
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
