// PointStore, the leaves' point blocks, against a vector per leaf: appends that grow a block
// through its size classes (of ranges, and of points picked from another block), in-place retains that shrink it, drains and releases, for sets of
// optional columns (stamps, ids, intensities, times); released blocks are reused before the pools
// grow, and compaction moves blocks to the pools' front and gives the emptied pages back.

#include "core/storage/point_store.hpp"

#include <gtest/gtest.h>

#include <deque>
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

/// A store shared as a snapshot, and what each of its leaves held then.
struct SharedAt {
  PointStore snapshot;
  std::vector<std::uint32_t> links;
  std::vector<std::vector<StoredPoint>> model;
};

TEST_P(PointStoreModel, MatchesAVectorPerLeafThroughAppendsPicksRetainsDrainsAndReleases) {
  const Columns kept = columns_of(GetParam());
  PointStore store(kept);
  std::deque<SharedAt> shared;  // up to three snapshots alive, each read as it was taken
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
    switch (rng() % 10) {
      case 0: {  // retain: drop points below a random x
        const float cut = coord(rng);
        const std::uint32_t left = store.retain(link, count, [&](const StoredPoint& s) { return s.p[0] >= cut; });
        std::erase_if(expected, [&](const StoredPoint& s) { return s.p[0] < cut; });
        ASSERT_EQ(left, expected.size());
        ASSERT_EQ(link == kNone, left == 0);
        break;
      }
      case 9: {  // retain: drop the last few points only (the next append writes where they were)
        const std::uint32_t keep = count - std::min<std::uint32_t>(count, 1 + rng() % 4);
        std::uint32_t seen = 0;
        const std::uint32_t left = store.retain(link, count, [&](const StoredPoint&) { return seen++ < keep; });
        expected.resize(keep);
        ASSERT_EQ(left, keep);
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
      case 3:  // now and then, blocks move to the pools' front: every leaf keeps its points
        if (rng() % 16 == 0) {
          const auto holds = [&](std::uint32_t owner, std::uint32_t l) { return owner < kLeaves && links[owner] == l; };
          store.compact(std::size_t(rng() % 20000), holds, [&](std::uint32_t owner, std::uint32_t moved) {
            ASSERT_LT(owner, std::uint32_t(kLeaves));
            links[owner] = moved;
          });
          for (std::size_t other = 0; other < kLeaves; ++other) {
            ASSERT_TRUE(same(contents(store, links[other], std::uint32_t(model[other].size())), model[other]))
                << "leaf " << other << " after compaction at step " << step;
          }
        }
        break;
      case 4: {  // append points picked from another leaf's block, in any order and repeated
        const std::size_t other = (leaf + 1 + rng() % (kLeaves - 1)) % kLeaves;
        const std::vector<StoredPoint>& source = model[other];
        if (source.empty()) break;
        std::vector<std::uint32_t> picked(1 + rng() % 40);
        for (std::uint32_t& i : picked) i = std::uint32_t(rng() % source.size());
        store.append_picked(link, std::uint32_t(leaf), count, store.span(links[other], std::uint32_t(source.size())),
                            picked.data(), std::uint32_t(picked.size()), rng() % 2 == 0 ? 0u : count + 60u);
        for (const std::uint32_t i : picked) expected.push_back(source[i]);
        break;
      }
      default: {  // append a range, now and then a long one (large classes)
        const std::size_t m = rng() % 10 == 0 ? rng() % 3000 : 1 + rng() % 20;
        std::vector<StoredPoint> batch(m);
        for (StoredPoint& s : batch) {  // a column not kept reads back as zero
          s = {{coord(rng), coord(rng), coord(rng)}, kept.stamps ? next_stamp : 0u, kept.ids ? next_stamp * 7u : 0u,
               kept.intensities ? coord(rng) : 0.0f, kept.times ? coord(rng) * 1e3f : 0.0f};
          ++next_stamp;
        }
        store.append(link, std::uint32_t(leaf), count, batch.data(), batch.data() + batch.size());
        expected.insert(expected.end(), batch.begin(), batch.end());
        break;
      }
    }
    ASSERT_TRUE(same(contents(store, link, std::uint32_t(expected.size())), expected)) << "step " << step;
    if (step % 400 == 0) {  // a snapshot now and then; the oldest goes
      shared.push_back({store.share(), links, model});
      if (shared.size() > 3) shared.pop_front();
    }
    if (step % 50 == 0) {
      for (const SharedAt& s : shared) {
        for (std::size_t l = 0; l < kLeaves; ++l) {
          ASSERT_TRUE(same(contents(s.snapshot, s.links[l], std::uint32_t(s.model[l].size())), s.model[l]))
              << "a snapshot's leaf " << l << " at step " << step;
        }
      }
    }
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
    store.append(link, 0, 0, batch.data(), batch.data() + batch.size());
    const std::size_t bytes = store.bytes();
    if (columns > 0) {
      EXPECT_NEAR(double(bytes - previous) / double(batch.size()), 4.0, 0.1) << columns;
    }
    previous = bytes;
  }
}

TEST(BlocksPerPage, FindsTheSamePageAsADivisionForEveryBlockIndex) {
  std::mt19937 rng(3);
  for (std::uint32_t count = 1; count <= 1200; ++count) {
    const BlocksPerPage per_page(count);
    for (std::uint32_t i = 0; i < 4 * count + 64; ++i) ASSERT_EQ(per_page.page_of(i), i / count) << i << " / " << count;
    for (int k = 0; k < 2000; ++k) {
      const std::uint32_t i = std::uint32_t(rng());  // over the whole range, far past 2^26 links
      ASSERT_EQ(per_page.page_of(i), i / count) << i << " / " << count;
    }
    ASSERT_EQ(per_page.page_of(0xFFFFFFFFu), 0xFFFFFFFFu / count) << count;
  }
}

TEST(PointStore, ASparsePoolCostsOneSmallPageNotAPageOfPowerOfTwoBlocks) {
  PointStore store;  // a leaf in each of the first 18 size classes (2 to 128 points)
  std::vector<BarePoint> points(128);
  std::vector<std::uint32_t> links(18, kNone);
  for (int c = 0; c < 18; ++c) {
    store.append(links[std::size_t(c)], 0, 0, points.data(), points.data() + PointStore::capacity_of(c));
  }
  // each pool's page: the fewest 4 KiB pages that hold a block with at most an eighth left over
  // (8 KiB for 128 points' 1540 B); pages of 2^k blocks took 20-28 KiB for most of them
  EXPECT_LE(store.bytes(), 18 * std::size_t{8192} + 4096);
}

TEST(PointStore, ReleasedBlocksAreReusedBeforeThePoolsGrow) {
  PointStore store(Columns{true, true, true, true});
  std::vector<StoredPoint> batch(50);
  std::vector<std::uint32_t> links(100, kNone);
  for (std::uint32_t& link : links) store.append(link, 0, 0, batch.data(), batch.data() + batch.size());
  for (std::uint32_t& link : links) store.release(link);  // the free lists reach their size
  for (std::uint32_t& link : links) store.append(link, 0, 0, batch.data(), batch.data() + batch.size());
  const std::size_t bytes = store.bytes();
  for (int round = 0; round < 5; ++round) {
    for (std::uint32_t& link : links) store.release(link);
    for (std::uint32_t& link : links) store.append(link, 0, 0, batch.data(), batch.data() + batch.size());
    ASSERT_EQ(store.bytes(), bytes) << round;
  }
}

/// Blocks of one size class: `n` two-point blocks, block i holding the points (i, 0, 0), (i, 1, 0).
std::vector<std::uint32_t> two_point_blocks(PointStore& store, std::size_t n) {
  std::vector<std::uint32_t> links(n, kNone);
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<BarePoint> two{{{float(i), 0.0f, 0.0f}}, {{float(i), 1.0f, 0.0f}}};
    store.append(links[i], std::uint32_t(i), 0, two.data(), two.data() + 2);
  }
  return links;
}

/// Whether every block of `links` (kNone: none) reads in `store` as two_point_blocks() wrote it.
bool reads_as_written(const PointStore& store, const std::vector<std::uint32_t>& links) {
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i] == kNone) continue;
    const std::vector<StoredPoint> expected{{{float(i), 0.0f, 0.0f}}, {{float(i), 1.0f, 0.0f}}};
    if (!same(contents(store, links[i], 2), expected)) return false;
  }
  return true;
}

TEST(PointStore, BlocksFreeBeforeASnapshotAreWrittenWhereTheyLieWithoutACopy) {
  auto ledger = std::make_shared<PageLedger>();
  PointStore store(Columns{}, ledger);
  std::vector<std::uint32_t> links = two_point_blocks(store, 8 * 1024);  // a page holds a few hundred
  std::vector<std::uint32_t> read = links;  // what the snapshot holds
  for (std::size_t k = 0; k < 8; ++k) {  // 5 free on each of 8 pages
    for (std::size_t i = 0; i < 5; ++i) store.release(links[1024 * k + 7 * i]), read[1024 * k + 7 * i] = kNone;
  }
  const PointStore snapshot = store.share();
  const std::vector<BarePoint> other{{{-1.0f, -2.0f, -3.0f}}, {{-4.0f, -5.0f, -6.0f}}};
  std::vector<std::uint32_t> fresh(40, kNone);
  for (std::uint32_t& link : fresh) store.append(link, 0, 0, other.data(), other.data() + 2);
  EXPECT_EQ(ledger->snapshot_bytes(), 0u) << "40 free blocks on 8 pages the snapshot holds: no page copied";
  EXPECT_TRUE(reads_as_written(snapshot, read));
  auto alone_ledger = std::make_shared<PageLedger>();
  PointStore alone(Columns{}, alone_ledger);
  (void)two_point_blocks(alone, 8 * 1024);
  EXPECT_EQ(ledger->live_bytes.load(), alone_ledger->live_bytes.load()) << "the pools did not grow";
}

TEST(PointStore, BlocksLetGoOfWhileASnapshotIsAliveWaitForItToGo) {
  auto ledger = std::make_shared<PageLedger>();
  PointStore store(Columns{}, ledger);
  const std::vector<std::uint32_t> links = two_point_blocks(store, 2048);
  std::vector<std::uint32_t> live = links;
  auto older = std::make_unique<PointStore>(store.share());
  for (std::size_t i = 0; i < 600; ++i) store.release(live[3 * i]);  // on every page: the snapshot reads them
  auto younger = std::make_unique<PointStore>(store.share());
  for (std::size_t i = 0; i < 600; ++i) store.release(live[3 * i + 1]);

  // the younger snapshot's going frees nothing: the older one still reads every block let go of
  younger.reset();
  const std::vector<BarePoint> other{{{-1.0f, -2.0f, -3.0f}}, {{-4.0f, -5.0f, -6.0f}}};
  std::vector<std::uint32_t> fresh(1200, kNone);
  for (std::uint32_t& link : fresh) store.append(link, 0, 0, other.data(), other.data() + 2);
  EXPECT_TRUE(reads_as_written(*older, links)) << "no block the older snapshot reads was written";
  const std::size_t copied = ledger->snapshot_bytes();
  EXPECT_GT(copied, 0u) << "the blocks were reused by copying their pages";

  // blocks let go of before a newer snapshot are written in place once the older one goes
  for (std::size_t i = 0; i < 500; ++i) store.release(fresh[i]);
  const PointStore newer = store.share();
  older.reset();
  (void)store.release_replaced();
  const std::size_t bytes = ledger->bytes.load();
  std::vector<std::uint32_t> again(300, kNone);
  for (std::uint32_t& link : again) store.append(link, 0, 0, other.data(), other.data() + 2);
  EXPECT_EQ(ledger->bytes.load(), bytes) << "300 blocks from the 500 freed before the newer snapshot: no page copied or added";
  for (std::size_t i = 500; i < fresh.size(); ++i) {
    ASSERT_TRUE(same(contents(newer, fresh[i], 2), {as_stored(other[0]), as_stored(other[1])})) << i;
  }
}

TEST(PointStore, ABlockGivenRoomTakesThatManyPointsWithoutMoving) {
  std::vector<StoredPoint> points(128);
  for (std::uint32_t i = 0; i < points.size(); ++i) points[i] = {{float(i), 0.5f, -float(i)}, 0, i, 0.0f, 0.0f};
  // fills a block to 40 points one at a time after a first append of 3 given `room`; how often it moved
  auto moves_to_40 = [&](std::uint32_t room) {
    PointStore store(Columns{false, true, false, false});
    std::uint32_t link = kNone;
    store.append(link, 7, 0, points.data(), points.data() + 3, room);
    std::uint32_t moves = 0;
    for (std::uint32_t count = 3; count < 40; ++count) {
      const std::uint32_t before = link;
      store.append(link, 7, count, points.data() + count, points.data() + count + 1);
      moves += link != before;
    }
    EXPECT_TRUE(same(contents(store, link, 40), std::vector<StoredPoint>(points.begin(), points.begin() + 40)));
    return moves;
  };
  EXPECT_GT(moves_to_40(0), 5u);  // without room, through the size classes
  EXPECT_GT(moves_to_40(20), 0u);
  EXPECT_EQ(moves_to_40(40), 0u);
  EXPECT_EQ(moves_to_40(128), 0u);
}

TEST(PointStore, CompactionGivesBackThePagesAShrunkMapEmptiedWithinItsBudget) {
  PointStore store(Columns{false, true, true, true});
  std::mt19937 rng(5);
  std::vector<std::uint32_t> links(6000, kNone);
  std::vector<std::vector<StoredPoint>> model(links.size());
  const auto owner = [](std::size_t i) { return std::uint32_t(1000 + i); };  // any numbers
  const auto all_held = [&] {
    for (std::size_t i = 0; i < links.size(); ++i) {
      ASSERT_TRUE(same(contents(store, links[i], std::uint32_t(model[i].size())), model[i])) << "leaf " << i;
      if (links[i] != kNone) {
        ASSERT_EQ(store.owner_of(links[i]), owner(i));
      }
    }
  };
  for (std::size_t i = 0; i < links.size(); ++i) {  // blocks of many sizes, interleaved
    model[i].resize(1 + rng() % 40);
    for (StoredPoint& s : model[i]) s = {{float(i), float(rng() % 1000), 0.5f}, 0, std::uint32_t(rng()), 1.5f, 2.5f};
    store.append(links[i], owner(i), 0, model[i].data(), model[i].data() + model[i].size());
  }
  const std::size_t full = store.bytes();
  EXPECT_EQ(store.free_bytes(), 0u);
  for (std::size_t i = 0; i < links.size(); ++i) {  // a map that shrank: nine leaves in ten leave
    if (i % 10 != 3) {
      store.release(links[i]);
      model[i].clear();
    }
  }
  EXPECT_GT(store.free_bytes(), full / 2);
  const auto holds = [&](std::uint32_t o, std::uint32_t link) { return o - 1000 < links.size() && links[o - 1000] == link; };
  const auto relink = [&](std::uint32_t o, std::uint32_t link) { links[o - 1000] = link; };
  constexpr std::size_t kBudget = 20000;
  std::size_t calls = 0;
  for (std::size_t done = 1; done > 0; ++calls) {  // as updates would: a budget at a time
    const std::size_t before = store.bytes();
    done = store.compact(kBudget, holds, relink);
    EXPECT_LE(done, kBudget + 4096) << "one block past the budget at most";
    EXPECT_LE(store.bytes(), before);
    all_held();
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(calls, 3u);
  EXPECT_LT(store.bytes(), full / 5) << "the emptied pages are given back";
  EXPECT_LT(store.free_bytes(), full / 20);
  // the store goes on as before: blocks grow, move and are released
  for (std::size_t i = 0; i < links.size(); i += 7) {
    std::vector<StoredPoint> more(1 + rng() % 30, StoredPoint{{1, 2, 3}, 0, 9, 8, 7});
    store.append(links[i], owner(i), std::uint32_t(model[i].size()), more.data(), more.data() + more.size());
    model[i].insert(model[i].end(), more.begin(), more.end());
  }
  all_held();
}

}  // namespace
}  // namespace eco::detail
