#pragma once
// The update's working arrays (insertion's batches and their groups, a split leaf's order, a
// collapsed subtree's points), kept between updates in the tree's own mapped memory
// (core/storage/mapped_memory.hpp): neither the update nor its caller pays for fresh pages each frame.
//
// They are kept at the high-water mark of the recent updates, with hysteresis: an update that
// needs less leaves them as they are; once each of the last kWindow updates has needed under a
// kSlack-th of what they hold (a map that shrank, or a one-off: a map's first scan, the whole map
// put back after the precision origin moved), they shrink to those updates' peak. What they hold is bounded by the
// largest batch a recent update put in: kInsertChunk points for a scan, the held points for a
// map put back whole.

#include "core/geometry/geometry.hpp"
#include "core/storage/mapped_memory.hpp"
#include "core/storage/point_store.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

namespace eco::detail {

class WorkingBuffers {
 public:
  static constexpr std::size_t kWindow = 4;  // updates
  static constexpr std::size_t kSlack = 2;  // a vector that outgrows its room doubles it

  /// Insertion's batch of new points (Point: StoredPoint or BarePoint), and room for as many
  /// partitioned.
  template <class Point>
  MappedVector<Point>& batch() { return std::get<Typed<Point>>(by_type_).batch; }
  template <class Point>
  MappedVector<Point>& partitioned() { return std::get<Typed<Point>>(by_type_).partitioned; }
  /// A batch's points' start-cell slots (then the groups' sorts' second array), their cell
  /// codes, and where each group starts.
  MappedVector<std::uint32_t>& slots() { return slots_; }
  MappedVector<std::uint32_t>& codes() { return codes_; }
  MappedVector<std::uint32_t>& group_starts() { return group_starts_; }
  /// The subtrees detached while the root re-centres (Quantised mode), with their cells.
  MappedVector<std::pair<std::uint32_t, Cell>>& detached() { return detached_; }
  /// A leaf being split: its points' octants, then their order.
  MappedVector<std::uint32_t>& split_order() { return split_order_; }
  /// The points of a subtree being collapsed (at most a leaf's: under a page, so from the heap).
  std::vector<StoredPoint>& collapsed() { return collapsed_; }

  /// Notes that an update is over, in which the largest batch held `points` points, and shrinks
  /// the buffers when each of the last kWindow updates needed under a kSlack-th of what they hold.
  void end_update(std::size_t points) {
    recent_[updates_ % kWindow] = points;
    if (++updates_ < kWindow) return;
    const std::size_t peak = *std::max_element(recent_.begin(), recent_.end());
    if (kSlack * peak >= held_points()) return;
    std::apply([&](auto&... typed) { ((shrink(typed.batch, peak), shrink(typed.partitioned, peak)), ...); }, by_type_);
    for (auto* indices : {&slots_, &codes_, &split_order_}) shrink(*indices, peak);
    shrink(collapsed_, peak);
  }

  /// Bytes held.
  [[nodiscard]] std::size_t bytes() const {
    const std::size_t batches =
        std::apply([](const auto&... typed) { return ((bytes_of(typed.batch) + bytes_of(typed.partitioned)) + ...); },
                   by_type_);
    return batches + bytes_of(slots_) + bytes_of(codes_) + bytes_of(group_starts_) + bytes_of(split_order_) +
           bytes_of(collapsed_) + bytes_of(detached_);
  }

 private:
  template <class Point>
  struct Typed {
    MappedVector<Point> batch, partitioned;
  };
  template <class Vector>
  static std::size_t bytes_of(const Vector& v) { return v.capacity() * sizeof(typename Vector::value_type); }
  /// Points the largest batch buffer has room for.
  [[nodiscard]] std::size_t held_points() const {
    return std::apply([](const auto&... typed) { return std::max({typed.batch.capacity()..., typed.partitioned.capacity()...}); },
                      by_type_);
  }
  /// Gives `v` room for `peak` (its contents are working values, not kept).
  template <class Vector>
  static void shrink(Vector& v, std::size_t peak) {
    if (v.capacity() <= peak) return;
    Vector().swap(v);
    v.reserve(peak);
  }

  std::tuple<Typed<StoredPoint>, Typed<BarePoint>> by_type_;
  MappedVector<std::uint32_t> slots_, codes_, group_starts_, split_order_;
  MappedVector<std::pair<std::uint32_t, Cell>> detached_;
  std::vector<StoredPoint> collapsed_;
  std::array<std::size_t, kWindow> recent_{};  // the largest batch of each of the last updates
  std::size_t updates_ = 0;
};

}  // namespace eco::detail
