#pragma once
// The points of a leaf as the tree stores them (StoredPoint; BarePoint where no column beside the
// coordinates is kept), the columns a store keeps, and a leaf's points read in place (PointSpan)
// or from a map file's bytes (ColumnBytes).

#include <array>
#include <cstddef>
#include <cstdint>

namespace eco::detail {

/// A point as the tree stores it: anchor-frame float coordinates, its insertion stamp, and the
/// scan's attributes (zero where not kept); `time` is seconds from the tree's time origin.
struct StoredPoint {
  std::array<float, 3> p{};
  std::uint32_t stamp = 0;
  std::uint32_t id = 0;
  float intensity = 0.0f;
  float time = 0.0f;
};

/// A new point of a store that keeps no column beside the coordinates (the robot's case):
/// insertion moves 12 B a point instead of a StoredPoint's 28.
struct BarePoint {
  std::array<float, 3> p{};
};

/// A point to insert as the tree stores it (the columns a BarePoint lacks are not kept: zero).
inline const StoredPoint& as_stored(const StoredPoint& s) { return s; }
inline StoredPoint as_stored(const BarePoint& b) { return {b.p}; }

/// The optional per-point columns of a PointStore.
struct Columns {
  bool stamps = false, ids = false, intensities = false, times = false;
  [[nodiscard]] int count() const { return int(stamps) + int(ids) + int(intensities) + int(times); }
};

/// The points of one leaf, read in place: coordinates by axis, then the kept columns (null when
/// not kept).
struct PointSpan {
  const float* x;
  const float* y;
  const float* z;
  const std::uint32_t* stamps;
  const std::uint32_t* ids;
  const float* intensities;
  const float* times;
  std::uint32_t size;

  [[nodiscard]] StoredPoint operator[](std::uint32_t i) const {
    return {{x[i], y[i], z[i]},
            stamps ? stamps[i] : 0u,
            ids ? ids[i] : 0u,
            intensities ? intensities[i] : 0.0f,
            times ? times[i] : 0.0f};
  }
};

/// Columns of 4-byte values in the machine's order, read where they lie at any alignment (a map
/// file's bytes): x, y, z, then the kept columns as in PointSpan; null when not there.
struct ColumnBytes {
  const std::byte* x = nullptr;
  const std::byte* y = nullptr;
  const std::byte* z = nullptr;
  const std::byte* stamps = nullptr;
  const std::byte* ids = nullptr;
  const std::byte* intensities = nullptr;
  const std::byte* times = nullptr;
};

/// Calls f(column, kept, name) for each column of `c` (a ColumnBytes, const or to fill) in their
/// order: x, y and z, always kept, then the others as `kept` says.
template <class Bytes, class F>
void for_each_column(Bytes& c, const Columns& kept, F&& f) {
  f(c.x, true, "x");
  f(c.y, true, "y");
  f(c.z, true, "z");
  f(c.stamps, kept.stamps, "stamps");
  f(c.ids, kept.ids, "ids");
  f(c.intensities, kept.intensities, "intensities");
  f(c.times, kept.times, "times");
}

}  // namespace eco::detail
