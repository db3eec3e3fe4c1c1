#pragma once
// Leaf point buckets: a chain of fixed-size structure-of-arrays chunks per leaf, pooled with a free
// list. The head chunk is the partly filled one, so appending is O(1); distance loops run over
// plain float arrays.

#include "core/node_store.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace eco::detail {

inline constexpr int kChunkPoints = 8;

struct Chunk {
  std::array<float, kChunkPoints> x{}, y{}, z{};
  std::uint32_t next = kNone;
};

/// A point as the tree stores it: anchor-frame float coordinates and its insertion stamp.
struct StoredPoint {
  std::array<float, 3> p{};
  std::uint32_t stamp = 0;
};

class PointStore {
 public:
  explicit PointStore(bool keep_stamps = false) : keep_stamps_(keep_stamps) {}

  /// Appends to the chain at `head` that holds `count` points.
  void push(std::uint32_t& head, std::uint32_t count, const StoredPoint& s) {
    int slot = static_cast<int>(count % kChunkPoints);
    if (slot == 0) {
      const std::uint32_t id = take();
      chunks_[id].next = head;
      head = id;
    }
    Chunk& c = chunks_[head];
    c.x[slot] = s.p[0];
    c.y[slot] = s.p[1];
    c.z[slot] = s.p[2];
    if (keep_stamps_) stamps_[std::size_t(head) * kChunkPoints + std::size_t(slot)] = s.stamp;
  }

  /// Calls f(chunk, stamps_or_null, n) for each chunk of the chain, n the points it holds.
  template <class F>
  void for_each_chunk(std::uint32_t head, std::uint32_t count, F&& f) const {
    std::uint32_t n = count % kChunkPoints == 0 ? kChunkPoints : count % kChunkPoints;
    for (std::uint32_t id = head; id != kNone && count > 0; id = chunks_[id].next) {
      f(chunks_[id], keep_stamps_ ? &stamps_[std::size_t(id) * kChunkPoints] : nullptr, int(n));
      count -= n;
      n = kChunkPoints;
    }
  }

  /// Calls f(const StoredPoint&) for each point of the chain.
  template <class F>
  void for_each(std::uint32_t head, std::uint32_t count, F&& f) const {
    for_each_chunk(head, count, [&](const Chunk& c, const std::uint32_t* stamps, int n) {
      for (int i = 0; i < n; ++i) f(StoredPoint{{c.x[i], c.y[i], c.z[i]}, stamps ? stamps[i] : 0u});
    });
  }

  /// Appends every point of the chain to `out` and releases the chain.
  void drain(std::uint32_t& head, std::uint32_t count, std::vector<StoredPoint>& out) {
    for_each(head, count, [&](const StoredPoint& s) { out.push_back(s); });
    release(head);
  }

  void release(std::uint32_t& head) {
    for (std::uint32_t id = head; id != kNone;) {
      const std::uint32_t next = chunks_[id].next;
      free_.push_back(id);
      id = next;
    }
    head = kNone;
  }

  [[nodiscard]] bool keeps_stamps() const { return keep_stamps_; }
  [[nodiscard]] std::size_t bytes() const {
    return chunks_.capacity() * sizeof(Chunk) + stamps_.capacity() * sizeof(std::uint32_t) +
           free_.capacity() * sizeof(std::uint32_t);
  }

 private:
  std::uint32_t take() {
    if (!free_.empty()) {
      const std::uint32_t id = free_.back();
      free_.pop_back();
      return id;
    }
    chunks_.emplace_back();
    if (keep_stamps_) stamps_.resize(chunks_.size() * kChunkPoints);
    return static_cast<std::uint32_t>(chunks_.size() - 1);
  }

  bool keep_stamps_;
  std::vector<Chunk> chunks_;
  std::vector<std::uint32_t> stamps_;  // kChunkPoints per chunk, only when keep_stamps_
  std::vector<std::uint32_t> free_;
};

}  // namespace eco::detail
