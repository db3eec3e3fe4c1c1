#pragma once
// Contiguous, index-addressed node storage with free lists: no allocation per node in steady
// state, O(1) release. Nodes are read with [] and child(), written through edit() and edit_child().

#include "core/geometry/geometry.hpp"
#include "core/storage/mapped_memory.hpp"
#include "core/storage/shared_pages.hpp"

#include <array>
#include <cassert>
#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

namespace eco::detail {

inline constexpr std::uint32_t kNone = 0xFFFFFFFFu;

struct Node {
  Aabb bounds;                   // tight bounds of every point below
  std::uint32_t count = 0;       // points below
  std::uint32_t parent = kNone;
  std::uint32_t link = kNone;    // leaf: its point block (PointStore); inner: child block
  std::uint32_t oldest = kNone;  // smallest insertion stamp below (age limit); kNone if empty
  // leaf, Quantised mode: its occupied subcells (core/geometry/subcells.hpp), as two words so that the
  // node stays 4-byte aligned (52 B, not 56)
  std::array<std::uint32_t, 2> subcell_words{};
  std::uint8_t depth = 0;
  std::uint8_t octant = 0;       // which child of its parent
  bool leaf = true;

  [[nodiscard]] std::uint64_t subcells() const { return subcell_words[0] | std::uint64_t{subcell_words[1]} << 32; }
  void set_subcells(std::uint64_t bits) { subcell_words = {std::uint32_t(bits), std::uint32_t(bits >> 32)}; }
};
static_assert(sizeof(Node) == 52);

/// Eight child slots of an inner node; kNone marks an empty octant.
struct ChildBlock {
  std::array<std::uint32_t, 8> child{kNone, kNone, kNone, kNone, kNone, kNone, kNone, kNone};
};

class NodeStore {
 public:
  std::uint32_t make_leaf(std::uint32_t parent, int octant, int depth) {
    const std::uint32_t id = take(nodes_, free_nodes_);
    Node& n = nodes_[id];
    n = Node{};
    n.parent = parent;
    n.octant = static_cast<std::uint8_t>(octant);
    n.depth = static_cast<std::uint8_t>(depth);
    ++live_;
    return id;
  }
  /// Turns an empty-linked leaf into an inner node with no children.
  void make_inner(std::uint32_t id) {
    Node& n = nodes_[id];
    assert(n.leaf && n.link == kNone);
    n.link = take(blocks_, free_blocks_);
    blocks_[n.link] = ChildBlock{};
    n.leaf = false;
  }
  /// Turns a childless inner node back into an empty leaf.
  void make_leaf_of_inner(std::uint32_t id) {
    Node& n = nodes_[id];
    assert(!n.leaf);
    free_blocks_.push_back(n.link);
    n.link = kNone;
    n.leaf = true;
  }
  /// Releases one node whose points and children were already released.
  void release(std::uint32_t id) {
    Node& n = nodes_[id];
    if (!n.leaf) free_blocks_.push_back(n.link);
    n.leaf = true;
    n.link = kNone;
    free_nodes_.push_back(id);
    --live_;
  }

  const Node& operator[](std::uint32_t id) const { return nodes_[id]; }
  /// Node `id` to write.
  Node& edit(std::uint32_t id) { return nodes_[id]; }
  /// Child slot `octant` of inner node `id` to write.
  std::uint32_t& edit_child(std::uint32_t id, int octant) { return blocks_[nodes_[id].link].child[octant]; }
  [[nodiscard]] std::uint32_t child(std::uint32_t id, int octant) const {
    return blocks_[nodes_[id].link].child[octant];
  }

  void prefetch(std::uint32_t id) const { __builtin_prefetch(&nodes_[id]); }
  /// Asks the memory system for the children of inner node `id` ahead of a visit, so that
  /// their cache misses overlap instead of coming one after another.
  /// Calls f(octant, child) for each child of inner node `id`, in octant order. The block is
  /// read again for each child, so `f` may change the tree (create, release or unlink nodes).
  template <class F>
  void for_each_child(std::uint32_t id, F&& f) const {
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = child(id, o);
      if (ch != kNone) f(o, ch);
    }
  }
  void prefetch_children(std::uint32_t id) const {
    for (const std::uint32_t ch : blocks_[nodes_[id].link].child) {
      if (ch != kNone) __builtin_prefetch(&nodes_[ch]);
    }
  }

  [[nodiscard]] std::size_t live() const { return live_; }
  /// Every node's id is below this.
  [[nodiscard]] std::size_t id_bound() const { return nodes_.size(); }
  [[nodiscard]] std::size_t bytes() const {
    return nodes_.capacity() * sizeof(Node) + blocks_.capacity() * sizeof(ChildBlock) +
           (free_nodes_.capacity() + free_blocks_.capacity()) * sizeof(std::uint32_t);
  }

  /// A copy to be read only (a snapshot's), without free lists, made in `room` (a store let go
  /// of, whose arrays are reused when large enough: no fresh pages to fault). Nodes are a tenth of
  /// a map's bytes or less, and kept contiguous so that a query reads a node with one load.
  [[nodiscard]] NodeStore share(NodeStore room) const {
    room.nodes_.assign(nodes_.begin(), nodes_.end());
    room.blocks_.assign(blocks_.begin(), blocks_.end());
    room.free_nodes_.clear();
    room.free_blocks_.clear();
    room.live_ = live_;
    return room;
  }

 private:
  template <class T>
  static std::uint32_t take(MappedVector<T>& pool, MappedVector<std::uint32_t>& free) {
    if (!free.empty()) {
      const std::uint32_t id = free.back();
      free.pop_back();
      return id;
    }
    // grow by a quarter, not double: a map's nodes come to rest near their peak, and the
    // vector's spare room is memory held for nothing
    if (pool.size() == pool.capacity()) pool.reserve(pool.capacity() + pool.capacity() / 4 + 64);
    pool.emplace_back();
    return static_cast<std::uint32_t>(pool.size() - 1);
  }

  MappedVector<Node> nodes_;
  MappedVector<std::uint32_t> free_nodes_;
  MappedVector<ChildBlock> blocks_;
  MappedVector<std::uint32_t> free_blocks_;
  std::size_t live_ = 0;
};

/// The node store a snapshot let go of, kept for the next snapshot's copy (NodeStore::share) and
/// counted in the ledger meanwhile. Snapshots go on any thread, hence the lock.
class NodeShelf {
 public:
  explicit NodeShelf(std::shared_ptr<PageLedger> ledger) : ledger_(std::move(ledger)) {}
  void put(NodeStore&& store) {
    LedgerCharge charge(ledger_, store.bytes());
    const std::lock_guard lock(mutex_);
    kept_ = std::move(store);
    charge_ = std::move(charge);
  }
  /// The store kept (empty if none); the shelf is left empty.
  [[nodiscard]] NodeStore take() {
    LedgerCharge gone;
    const std::lock_guard lock(mutex_);
    gone = std::move(charge_);
    return std::exchange(kept_, NodeStore{});
  }

 private:
  std::shared_ptr<PageLedger> ledger_;
  std::mutex mutex_;
  NodeStore kept_;
  LedgerCharge charge_;
};

}  // namespace eco::detail
