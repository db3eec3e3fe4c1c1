// NodeStore on its own: fresh nodes, inner nodes with eight empty child slots, release and reuse
// of node ids and child blocks (the pools stop growing once they hold the high-water mark),
// against a set of the ids that should be live.

#include "core/storage/node_store.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <vector>

namespace eco::detail {
namespace {

TEST(NodeStore, AFreshLeafIsEmptyAndKnowsItsPlace) {
  NodeStore nodes;
  const std::uint32_t root = nodes.make_leaf(kNone, 0, 0);
  const std::uint32_t id = nodes.make_leaf(root, 5, 3);
  EXPECT_NE(id, root);
  const Node& n = nodes[id];
  EXPECT_TRUE(n.leaf);
  EXPECT_EQ(n.count, 0u);
  EXPECT_EQ(n.parent, root);
  EXPECT_EQ(n.octant, 5);
  EXPECT_EQ(n.depth, 3);
  EXPECT_EQ(n.link, kNone);
  EXPECT_EQ(n.oldest, kNone);
  EXPECT_EQ(nodes.live(), 2u);
}

TEST(NodeStore, InnerNodesStartWithEightEmptySlotsAndGiveTheirBlockBack) {
  NodeStore nodes;
  const std::uint32_t id = nodes.make_leaf(kNone, 0, 0);
  nodes.make_inner(id);
  EXPECT_FALSE(nodes[id].leaf);
  for (int o = 0; o < 8; ++o) EXPECT_EQ(nodes.child(id, o), kNone);
  nodes.edit_child(id, 3) = nodes.make_leaf(id, 3, 1);
  EXPECT_EQ(nodes[nodes.child(id, 3)].parent, id);
  nodes.release(nodes.child(id, 3));
  nodes.edit_child(id, 3) = kNone;
  nodes.make_leaf_of_inner(id);
  EXPECT_TRUE(nodes[id].leaf);
  EXPECT_EQ(nodes[id].link, kNone);
  nodes.make_inner(id);  // a recycled block is cleared again
  for (int o = 0; o < 8; ++o) EXPECT_EQ(nodes.child(id, o), kNone);
}

TEST(NodeStore, ReleasedIdsAreReusedAndLiveIdsNeverCollide) {
  NodeStore nodes;
  std::set<std::uint32_t> live;
  std::vector<std::uint32_t> inner;
  std::mt19937 rng(11);
  std::size_t high_water = 0;
  for (int step = 0; step < 20000; ++step) {
    const bool grow = live.size() < 50 || rng() % 3 != 0;
    if (grow) {
      const std::uint32_t id = nodes.make_leaf(kNone, int(rng() % 8), int(rng() % 20));
      ASSERT_TRUE(live.insert(id).second) << "id " << id << " handed out twice";
      if (rng() % 4 == 0) {
        nodes.make_inner(id);
        inner.push_back(id);
      }
    } else {
      auto at = live.begin();
      std::advance(at, long(rng() % live.size()));
      const std::uint32_t id = *at;
      std::erase(inner, id);
      nodes.release(id);
      live.erase(at);
    }
    ASSERT_EQ(nodes.live(), live.size());
    high_water = std::max(high_water, live.size());
    // ids stay below the high-water mark: released ones are taken before new ones
    ASSERT_LT(*live.rbegin(), high_water);
  }
  for (const std::uint32_t id : inner) {
    ASSERT_FALSE(nodes[id].leaf);
  }
  // a second wave no larger than the first costs no memory
  std::vector<std::uint32_t> wave;
  for (const std::uint32_t id : live) nodes.release(id);
  const std::size_t bytes = nodes.bytes();
  for (std::size_t i = 0; i < high_water; ++i) wave.push_back(nodes.make_leaf(kNone, 0, 0));
  EXPECT_EQ(nodes.bytes(), bytes);
}

}  // namespace
}  // namespace eco::detail
