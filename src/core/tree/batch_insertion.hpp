#pragma once
// Batch insertion (Tree::insert_batch, insert_collected): a batch grouped by start cell, each group
// partitioned by octant top-down from its start node (core/tree/insertion.cpp) or, when large, sorted by
// the cells it falls in a few levels down (core/tree/sorted_insert.cpp); full leaves split on the way.
// It works on a tree's storage (core/tree/tree_storage.hpp), one batch at a time.

#include "core/tree/tree.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace eco::detail {

class BatchInsertion {
 public:
  explicit BatchInsertion(TreeStorage& storage) : t_(storage) {}
  /// Inserts every point of `batch` (each in the root cell), reordering it.
  template <class Point>
  void insert(std::span<Point> batch);

 private:
  static constexpr std::uint32_t kSortedGroup = 64;  // points below one start node worth sorting (insert_sorted)
  /// Splits leaf `id` (cell `cell`); `incoming[o]` points are about to follow into octant o, and
  /// a child that will hold them all without splitting gets a block with room for them.
  void split(std::uint32_t id, const Cell& cell, const std::array<std::uint32_t, 8>& incoming = {});
  struct Added {  // what an insertion put below a node
    Aabb bounds;
    std::uint32_t oldest = kNone;
    void merge(const Added& more) {
      bounds.merge(more.bounds);
      oldest = std::min(oldest, more.oldest);
    }
    void add_to(Node& n) const {  // count aside: the caller knows how many
      n.bounds.merge(bounds);
      n.oldest = std::min(n.oldest, oldest);
    }
  };
  /// Inserts points [from, to), all inside `cell`, into the subtree at `id`, partitioning them
  /// into `temp` (room for as many; both ranges are overwritten); the caller adds them to the
  /// ancestors. Returns their bounds and oldest age key. `subcells`, where the caller knows them,
  /// are the points' subcells in `cell` (for a leaf that takes them all).
  template <class Point>
  Added insert_range(std::uint32_t id, const Cell& cell, Point* from, Point* to, Point* temp,
                     std::optional<std::uint64_t> subcells = std::nullopt);
  /// insert_range for many points (src/core/tree/sorted_insert.cpp): sorted by the cells they fall in
  /// a few levels down, found at once, so that those levels read their children's ranges instead
  /// of partitioning them. `codes` and `codes_temp` have room for as many points.
  template <class Point>
  Added insert_sorted(std::uint32_t id, const Cell& cell, Point* from, Point* to, Point* temp, std::uint32_t* codes,
                      std::uint32_t* codes_temp);
  /// insert_sorted's descent: points [from, to) sorted by `codes`, `level` levels below the sort's node.
  template <class Point>
  Added descend_sorted(std::uint32_t id, const Cell& cell, int level, Point* from, Point* to, Point* temp,
                       const std::uint32_t* codes);
  /// The node at the start depth holding `cell`'s points (created on the way), or the leaf above.
  std::uint32_t start_node(const Cell& cell, Cell& at);
  /// Prefetches the start node of the first non-empty group at or after `from` (groups of
  /// insert_batch, `first` their bounds), so its miss overlaps the work on the group before.
  void prefetch_start_node(std::size_t from, std::span<const std::uint32_t> first) const;

  TreeStorage& t_;
};

template <class Point, class Collect, class Look>
std::size_t Tree::insert_collected(Collect&& collect, Look&& look) {
  MappedVector<Point>& batch = s_.buffers().batch<Point>();
  std::size_t n = 0;
  const auto insert = [&] {
    n += batch.size();
    look(std::span<const Point>(batch));
    insert_points(std::span<Point>(batch));
    batch.clear();
  };
  batch.clear();
  collect([&](const Point& s) {
    batch.push_back(s);
    if (batch.size() == kInsertChunk) insert();
  });
  insert();
  s_.buffers().end_update(std::min(n, kInsertChunk));
  return n;
}

}  // namespace eco::detail
