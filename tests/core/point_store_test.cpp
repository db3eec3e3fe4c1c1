// PointStore, the leaves' point blocks, against a vector per leaf: appends that grow a block
// through its size classes, in-place retains that shrink it, drains and releases, for sets of
// optional columns (stamps, ids, intensities, times); released blocks are reused before the pools
// grow.

#include "core/point_store.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace eco::detail {
namespace {

std::vector<StoredPoint> contents(const PointStore& store, std::uint32_t link, std::uint32_t count) {
  std::vector<StoredPoint> out;
  store.for_each(link, count, [&](const StoredPoint& s) { out.push_back(s); });
  return out;
}

bool same(const std::vector<StoredPoint>& a, const std::vector<StoredPoint>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].p != b[i].p || a[i].stamp != b[i].stamp || a[i].id != b[i].id || a[i].intensity != b[i].intensity ||
        a[i].time != b[i].time) {
      return false;
    }
  }
  return true;
}

TEST(PointStore, SizeClassesGrowByAFifthToAThirdThenDoubleAndTheSmallestFitIsChosen) {
  for (int c = 1; PointStore::capacity_of(c - 1) < (1u << 31); ++c) {
    const std::uint32_t before = PointStore::capacity_of(c - 1), now = PointStore::capacity_of(c);
    if (before < 4) {  // 2, 3, 4: a point a step
      EXPECT_EQ(now, before + 1);
    } else if (before < 4096) {
      EXPECT_LE(3 * now, 4 * before) << "class " << c;
      EXPECT_GE(5 * now, 6 * before) << "class " << c;
    } else {
      EXPECT_EQ(now, 2 * before) << "class " << c;
    }
  }
  const std::uint32_t largest = 1u << 31;
  EXPECT_EQ(PointStore::capacity_of(PointStore::class_for(largest)), largest);
  EXPECT_THROW((void)PointStore::class_for(largest + 1), std::length_error);
  for (std::uint32_t n = 1; n < 5000; ++n) {
    const int c = PointStore::class_for(n);
    ASSERT_GE(PointStore::capacity_of(c), n);
    if (c > 0) {
      ASSERT_LT(PointStore::capacity_of(c - 1), n);
    }
  }
}

/// The optional columns of bit set `mask`: stamps, ids, intensities, times.
Columns columns_of(int mask) { return {(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0, (mask & 8) != 0}; }

class PointStoreModel : public ::testing::TestWithParam<int> {};

TEST_P(PointStoreModel, MatchesAVectorPerLeafThroughAppendsRetainsDrainsAndReleases) {
  const Columns kept = columns_of(GetParam());
  PointStore store(kept);
  constexpr int kLeaves = 64;
  std::vector<std::uint32_t> links(kLeaves, kNone);
  std::vector<std::vector<StoredPoint>> model(kLeaves);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-10.0F, 10.0F);
  std::uint32_t next_stamp = 0;
  for (int step = 0; step < 20000; ++step) {
    const std::size_t leaf = rng() % kLeaves;
    std::uint32_t& link = links[leaf];
    std::vector<StoredPoint>& expected = model[leaf];
    const auto count = std::uint32_t(expected.size());
    switch (rng() % 8) {
      case 0: {  // retain: drop points below a random x
        const float cut = coord(rng);
        const std::uint32_t left = store.retain(link, count, [&](const StoredPoint& s) { return s.p[0] >= cut; });
        std::erase_if(expected, [&](const StoredPoint& s) { return s.p[0] < cut; });
        ASSERT_EQ(left, expected.size());
        ASSERT_EQ(link == kNone, left == 0);
        break;
      }
      case 1: {
        std::vector<StoredPoint> drained;
        store.drain(link, count, drained);
        ASSERT_TRUE(same(drained, expected));
        ASSERT_EQ(link, kNone);
        expected.clear();
        break;
      }
      case 2:
        store.release(link);
        ASSERT_EQ(link, kNone);
        expected.clear();
        break;
      default: {  // append a range, now and then a long one (large classes)
        const std::size_t m = rng() % 10 == 0 ? rng() % 3000 : 1 + rng() % 20;
        std::vector<StoredPoint> batch(m);
        for (StoredPoint& s : batch) {  // a column not kept reads back as zero
          s = {{coord(rng), coord(rng), coord(rng)}, kept.stamps ? next_stamp : 0u, kept.ids ? next_stamp * 7u : 0u,
               kept.intensities ? coord(rng) : 0.0f, kept.times ? coord(rng) * 1e3f : 0.0f};
          ++next_stamp;
        }
        store.append(link, count, batch.data(), batch.data() + batch.size());
        expected.insert(expected.end(), batch.begin(), batch.end());
        break;
      }
    }
    ASSERT_TRUE(same(contents(store, link, std::uint32_t(expected.size())), expected)) << "step " << step;
    const PointSpan span = store.span(link, std::uint32_t(expected.size()));
    const bool linked = link != kNone;
    ASSERT_EQ(span.stamps != nullptr, kept.stamps && linked);
    ASSERT_EQ(span.ids != nullptr, kept.ids && linked);
    ASSERT_EQ(span.intensities != nullptr, kept.intensities && linked);
    ASSERT_EQ(span.times != nullptr, kept.times && linked);
  }
}

INSTANTIATE_TEST_SUITE_P(Columns, PointStoreModel, ::testing::Values(0, 1, 6, 8, 14, 15),
                         [](const ::testing::TestParamInfo<int>& p) { return "Mask" + std::to_string(p.param); });

TEST(PointStore, EachKeptColumnCostsFourBytesAPoint) {
  std::vector<StoredPoint> batch(4096);
  std::size_t previous = 0;
  for (int columns = 0; columns <= 4; ++columns) {
    PointStore store(columns_of((1 << columns) - 1));
    std::uint32_t link = kNone;
    store.append(link, 0, batch.data(), batch.data() + batch.size());
    const std::size_t bytes = store.bytes();
    if (columns > 0) {
      EXPECT_NEAR(double(bytes - previous) / double(batch.size()), 4.0, 0.1) << columns;
    }
    previous = bytes;
  }
}

TEST(PointStore, ReleasedBlocksAreReusedBeforeThePoolsGrow) {
  PointStore store(Columns{true, true, true, true});
  std::vector<StoredPoint> batch(50);
  std::vector<std::uint32_t> links(100, kNone);
  for (std::uint32_t& link : links) store.append(link, 0, batch.data(), batch.data() + batch.size());
  for (std::uint32_t& link : links) store.release(link);  // the free lists reach their size
  for (std::uint32_t& link : links) store.append(link, 0, batch.data(), batch.data() + batch.size());
  const std::size_t bytes = store.bytes();
  for (int round = 0; round < 5; ++round) {
    for (std::uint32_t& link : links) store.release(link);
    for (std::uint32_t& link : links) store.append(link, 0, batch.data(), batch.data() + batch.size());
    ASSERT_EQ(store.bytes(), bytes) << round;
  }
}

}  // namespace
}  // namespace eco::detail
