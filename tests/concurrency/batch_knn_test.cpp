// The batch KNN (MapReader::knn over a span of queries): the answers of the one-query call, for
// any thread count and on threads kept between batches (QueryThreads), on a tree and on its
// snapshot; bad arguments refused by name before any query.
// Built under ThreadSanitizer too (make test-threads).

#include "support/map_answers.hpp"

#include <eco/ego_octree.hpp>
#include <eco/query_threads.hpp>
#include <eco/sim/simulator.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace eco::test {
namespace {

EgoOctree driven_tree(std::size_t frames) {
  const sim::Simulator drive(small_drive(frames));
  Config cfg;
  cfg.attributes.ids = true;
  EgoOctree tree(cfg);
  for (std::size_t t = 0; t < drive.size(); ++t) update_with_attributes(tree, drive.frame(t), t);
  return tree;
}

/// Queries near held points, and some far outside the box.
std::vector<Eigen::Vector3d> queries_for(const MapReader& map, std::size_t n) {
  const std::vector<Eigen::Vector3d> held = map.points();
  std::mt19937 rng(9);
  std::uniform_int_distribution<std::size_t> pick(0, held.size() - 1);
  std::normal_distribution<double> jitter(0.0, 0.4);
  std::vector<Eigen::Vector3d> q;
  for (std::size_t i = 0; i < n; ++i) {
    q.push_back(i % 17 == 0 ? Eigen::Vector3d(500.0, -300.0, 40.0 + double(i))
                            : held[pick(rng)] + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng)));
  }
  return q;
}

void expect_batch_is_serial(const MapReader& map, const std::vector<Eigen::Vector3d>& queries, std::size_t k,
                            unsigned threads, Frame frame) {
  SCOPED_TRACE("k = " + std::to_string(k) + ", threads = " + std::to_string(threads));
  std::vector<Neighbor> out(queries.size() * k);
  std::vector<std::size_t> found(queries.size(), 12345);
  map.knn(queries, k, out, found, threads, frame);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const std::vector<Neighbor> one = map.knn(queries[i], k, frame);
    ASSERT_EQ(found[i], one.size()) << "query " << i;
    for (std::size_t j = 0; j < one.size(); ++j) {
      const Neighbor& got = out[i * k + j];
      ASSERT_EQ(got.point, one[j].point) << "query " << i << ", neighbour " << j;
      ASSERT_EQ(got.sq_dist, one[j].sq_dist) << "query " << i << ", neighbour " << j;
      ASSERT_EQ(got.attributes, one[j].attributes) << "query " << i << ", neighbour " << j;
    }
  }
}

TEST(BatchKnn, AnswersAsTheOneQueryCallForAnyThreadCount) {
  EgoOctree tree = driven_tree(6);
  ASSERT_GT(tree.size(), 1000u);
  const std::vector<Eigen::Vector3d> queries = queries_for(tree, 301);
  for (const std::size_t k : {1, 5, 40}) {
    for (const unsigned threads : {1u, 2u, 3u, 8u}) expect_batch_is_serial(tree, queries, k, threads, Frame::World);
  }
  std::vector<Eigen::Vector3d> ego = queries;
  for (Eigen::Vector3d& q : ego) q -= tree.pose().translation();
  expect_batch_is_serial(tree, ego, 5, 2, Frame::Ego);
  const auto snapshot = tree.snapshot();
  const sim::Simulator drive(small_drive(8));
  update_with_attributes(tree, drive.frame(7), 7);
  expect_batch_is_serial(*snapshot, queries, 5, 3, Frame::World);
}

TEST(BatchKnn, ThreadsKeptBetweenBatchesAnswerAsTheOneQueryCallBatchAfterBatch) {
  EgoOctree tree = driven_tree(6);
  const std::vector<Eigen::Vector3d> queries = queries_for(tree, 700);
  const std::size_t k = 5;
  for (const unsigned count : {1u, 2u, 4u}) {
    QueryThreads threads(count);
    ASSERT_EQ(threads.size(), count);
    for (int batch = 0; batch < 20; ++batch) {  // the same helpers, woken twenty times
      const std::span<const Eigen::Vector3d> some(queries.data(), queries.size() - std::size_t(batch) * 31);
      std::vector<Neighbor> out(some.size() * k);
      std::vector<std::size_t> found(some.size(), 12345);
      tree.knn(some, k, out, found, threads);
      for (std::size_t i = 0; i < some.size(); ++i) {
        const std::vector<Neighbor> one = tree.knn(some[i], k);
        ASSERT_EQ(found[i], one.size()) << "batch " << batch << ", query " << i;
        for (std::size_t j = 0; j < one.size(); ++j) ASSERT_EQ(out[i * k + j].point, one[j].point);
      }
    }
    std::vector<Neighbor> out(k);
    std::vector<std::size_t> found(1);
    const std::vector<Eigen::Vector3d> bad{Eigen::Vector3d(std::nan(""), 0, 0)};
    EXPECT_THROW(tree.knn(bad, k, out, found, threads), std::invalid_argument);  // and the pool goes on
    tree.knn(std::span<const Eigen::Vector3d>(queries.data(), 1), k, out, found, threads);
    EXPECT_EQ(found[0], k);
  }
  EXPECT_THROW(QueryThreads(0), std::invalid_argument);
}

TEST(BatchKnn, AHelpersExceptionReachesTheCallerAndThePoolGoesOn) {
  QueryThreads threads(3);
  std::atomic<int> calls{0};
  EXPECT_THROW(threads.run([&] {
    if (calls.fetch_add(1) == 1) throw std::runtime_error("one of three");
  }),
               std::runtime_error);
  EXPECT_EQ(calls.load(), 3);
  calls = 0;
  threads.run([&] { calls.fetch_add(1); });
  EXPECT_EQ(calls.load(), 3);
}

TEST(BatchKnn, MoreThreadsThanQueriesAndEmptyBatchesAndMaps) {
  const EgoOctree tree = driven_tree(2);
  const std::vector<Eigen::Vector3d> two = queries_for(tree, 2);
  expect_batch_is_serial(tree, two, 3, 16, Frame::World);
  std::vector<Neighbor> none;
  std::vector<std::size_t> no_counts;
  tree.knn(std::span<const Eigen::Vector3d>(), 4, none, no_counts, 4);
  const EgoOctree empty;
  std::vector<Neighbor> out(2 * 3);
  std::vector<std::size_t> found(2, 7);
  empty.knn(two, 3, out, found);
  EXPECT_EQ(found, (std::vector<std::size_t>{0, 0}));
}

TEST(BatchKnn, BadArgumentsAreRefusedByNameBeforeAnyQuery) {
  const EgoOctree tree = driven_tree(2);
  std::vector<Eigen::Vector3d> queries = queries_for(tree, 5);
  const Neighbor marker{Eigen::Vector3d(1, 2, 3), 4.0, {}};
  const auto refused = [&](std::size_t k, std::size_t out_size, std::size_t found_size, unsigned threads,
                           const std::string& words) {
    std::vector<Neighbor> out(out_size, marker);
    std::vector<std::size_t> found(found_size, 99);
    try {
      tree.knn(queries, k, out, found, threads);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    for (const Neighbor& n : out) EXPECT_EQ(n.point, marker.point) << "written before refusing: " << words;
    for (const std::size_t f : found) EXPECT_EQ(f, 99u) << "written before refusing: " << words;
  };
  refused(0, 0, 5, 1, "k = 0 must be >= 1");
  refused(2, 10, 5, 0, "threads = 0 must be >= 1");
  refused(2, 9, 5, 1, "out.size() = 9 must be queries.size() * k = 10");
  refused(2, 10, 4, 1, "found.size() = 4 must be queries.size() = 5");
  queries[3].y() = std::numeric_limits<double>::quiet_NaN();
  refused(2, 10, 5, 2, "queries[3] is not finite");
  queries[3].y() = std::numeric_limits<double>::infinity();
  refused(2, 10, 5, 2, "queries[3] is not finite");
}

}  // namespace
}  // namespace eco::test
