// PointStore, the leaves' point blocks, against a vector per leaf: appends that grow a block
// through its size classes, in-place retains that shrink it, drains and releases, with and without
// stamps; released blocks are reused before the pools grow.

#include "core/point_store.hpp"

#include <gtest/gtest.h>

#include <random>
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
    if (a[i].p != b[i].p || a[i].stamp != b[i].stamp) return false;
  }
  return true;
}

TEST(PointStore, SizeClassesGrowByAboutHalfAndTheSmallestFitIsChosen) {
  for (int c = 1; c < 40; ++c) {
    EXPECT_GT(PointStore::capacity_of(c), PointStore::capacity_of(c - 1));
    EXPECT_LE(PointStore::capacity_of(c), 2 * PointStore::capacity_of(c - 1));
  }
  for (std::uint32_t n = 1; n < 5000; ++n) {
    const int c = PointStore::class_for(n);
    ASSERT_GE(PointStore::capacity_of(c), n);
    if (c > 0) {
      ASSERT_LT(PointStore::capacity_of(c - 1), n);
    }
  }
}

class PointStoreModel : public ::testing::TestWithParam<bool> {};

TEST_P(PointStoreModel, MatchesAVectorPerLeafThroughAppendsRetainsDrainsAndReleases) {
  const bool stamps = GetParam();
  PointStore store(stamps);
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
        const std::uint32_t kept = store.retain(link, count, [&](const StoredPoint& s) { return s.p[0] >= cut; });
        std::erase_if(expected, [&](const StoredPoint& s) { return s.p[0] < cut; });
        ASSERT_EQ(kept, expected.size());
        ASSERT_EQ(link == kNone, kept == 0);
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
        for (StoredPoint& s : batch) s = {{coord(rng), coord(rng), coord(rng)}, stamps ? next_stamp++ : 0u};
        store.append(link, count, batch.data(), batch.data() + batch.size());
        expected.insert(expected.end(), batch.begin(), batch.end());
        break;
      }
    }
    ASSERT_TRUE(same(contents(store, link, std::uint32_t(expected.size())), expected)) << "step " << step;
    const PointSpan span = store.span(link, std::uint32_t(expected.size()));
    ASSERT_EQ(span.stamps != nullptr, stamps && link != kNone);
  }
}

INSTANTIATE_TEST_SUITE_P(Stamps, PointStoreModel, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "WithStamps" : "NoStamps"; });

TEST(PointStore, ReleasedBlocksAreReusedBeforeThePoolsGrow) {
  PointStore store(true);
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
