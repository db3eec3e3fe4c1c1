#pragma once
// Points in the sensor's frame, a group at a time in vector code (core/geometry/vector_clones.hpp), for
// free-space clearing, which looks up the pixel of every return and of every held point in view,
// every frame: held points rotated into it, a scan's returns (already in it) loaded.

#include "clearing/pixel_lookup.hpp"

#include <Eigen/Core>

#include <array>
#include <cstddef>

namespace eco::detail {

/// The sensor's frame as plain numbers: v = rotation · (offset + p) for stored coordinates p.
struct SensorPose {
  std::array<std::array<double, 3>, 3> rotation{};  // sensor_R_world, by rows
  std::array<double, 3> offset{};                   // the precision origin less the sensor's position (world axes)

  SensorPose(const Eigen::Matrix3d& sensor_R_world, const Eigen::Vector3d& from_anchor);
  /// One point, by Eigen: the formula the group's lanes equal to the bit.
  [[nodiscard]] Eigen::Vector3d apply(const std::array<float, 3>& p) const {
    return matrix_ * (offset_ + Eigen::Vector3d(double(p[0]), double(p[1]), double(p[2])));
  }

 private:
  Eigen::Matrix3d matrix_;
  Eigen::Vector3d offset_;
};

/// Stored coordinates of up to PixelLookup::kGroup points.
struct StoredGroup {
  std::size_t size = 0;
  alignas(16) std::array<float, PixelLookup::kGroup> x{}, y{}, z{};
};

/// The next `n` <= PixelLookup::kGroup returns of a scan, from `data` (`stride` floats apart), into
/// `out` (out.size = n): they are in the sensor's frame already. A full group of packed points
/// (stride 3, the common layout) in vector code.
void load_returns(const float* data, std::size_t stride, std::size_t n, PixelLookup::Group& out);

/// `out` = pose.apply() of every lane of `in` (all kGroup of them; out.size = in.size), summed in
/// the order Eigen sums a 3×3 product (the first two rows left to right, the third right first;
/// tests/clearing/sensor_frame_test.cpp).
void to_sensor_frame(const SensorPose& pose, const StoredGroup& in, PixelLookup::Group& out);

}  // namespace eco::detail
