#pragma once
// The scan as free-space clearing sees it: its returns binned into the sensor's range image
// (SensorModel, include/eco/config.hpp), each pixel knowing the nearest return around it.

#include <eco/config.hpp>
#include <eco/types.hpp>

#include "update/fast_atan2.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace eco::detail {

/// For every pixel, the nearest return of a scan among that pixel and its 8 neighbours (columns
/// wrap around the circle, rows stop at the image's edge); infinity where none came back. Pixels
/// are named by their index, row * columns + column.
class RangeImage {
 public:
  /// No pixel: the point lies outside the vertical field of view or beyond max_range.
  static constexpr std::uint32_t kOutside = std::numeric_limits<std::uint32_t>::max();
  static constexpr double kNoReturn = std::numeric_limits<double>::infinity();

  /// Bins every finite return of `scan` (sensor frame) that pixel_of places in the image, in
  /// `storage` (resized to two images; the caller keeps it between frames, so that no frame pays
  /// for fresh pages, and while this image is read).
  RangeImage(const SensorModel& sensor, ScanView scan, std::vector<double>& storage);

  /// The pixel of the sensor-frame point `v` by SensorModel's formulas, or kOutside; `range` gets
  /// |v|. Exactly exact_pixel_of(), faster: the angles come from fast_atan2_degrees (a table), and
  /// wherever they may err across a wall (a pixel's, the field of view's) the formulas decide.
  [[nodiscard]] std::uint32_t pixel_of(const Eigen::Vector3d& v, double& range) const {
    const double horizontal = std::sqrt(v.x() * v.x() + v.y() * v.y());
    if (horizontal == 0.0) return exact_pixel_of(v, range);  // straight up or down, or the origin
    range = v.norm();  // not from `horizontal`: the formulas' own rounding, as exact_pixel_of's
    if (!(range <= sensor_.max_range)) return kOutside;
    // in rows and columns (reciprocals: their rounding is far inside the guards)
    const double row = (fast_atan2_degrees(v.z(), horizontal) - sensor_.vertical_fov_min) * per_row_;
    const double column = (fast_atan2_degrees(v.y(), v.x()) + 180.0) * per_column_;
    // One test for every wall: both ends of each guarded interval in the same row and column,
    // inside the field of view (truncation is floor there: both are >= 0). The rows are clamped
    // first: a point far below a narrow field of view lies more rows away than an int holds.
    const double low = row - row_guard_, high = row + row_guard_;
    const double left = column - column_guard_, right = column + column_guard_;
    const int low_row = int(std::clamp(low, -1.0, top_row_)), high_row = int(std::clamp(high, -1.0, top_row_));
    if ((low >= 0.0) & (high < top_row_) & (low_row == high_row) & (left >= 0.0) & (int(left) == int(right))) {
      return index(std::min(rows_ - 1, low_row), wrapped(int(left)));
    }
    if (high < 0.0 || low >= top_row_) return kOutside;  // clearly below or above the field of view
    return exact_pixel_of(v, range);
  }

  /// The pixel by the formulas themselves, with libm's atan2.
  [[nodiscard]] std::uint32_t exact_pixel_of(const Eigen::Vector3d& v, double& range) const {
    constexpr double kPi = 3.14159265358979323846;
    range = v.norm();
    if (!(range <= sensor_.max_range)) return kOutside;
    const double elevation = std::atan2(v.z(), std::hypot(v.x(), v.y())) * 180.0 / kPi;
    if (elevation < sensor_.vertical_fov_min || elevation >= sensor_.vertical_fov_max) return kOutside;
    const double azimuth = std::atan2(v.y(), v.x()) * 180.0 / kPi;
    const int row = std::min(rows_ - 1, int((elevation - sensor_.vertical_fov_min) / sensor_.vertical_resolution));
    const int column = int((azimuth + 180.0) / sensor_.horizontal_resolution) % columns_;
    return index(row, column);
  }

  /// The nearest return around `pixel` (not kOutside) [m]; kNoReturn when none came back there.
  [[nodiscard]] double nearest_around(std::uint32_t pixel) const { return around_[pixel]; }

 private:
  /// `column` in [0, 2 columns) back on the circle: the formulas' `% columns` without a division.
  [[nodiscard]] int wrapped(int column) const { return column >= columns_ ? column - columns_ : column; }
  [[nodiscard]] std::uint32_t index(int row, int column) const {
    return std::uint32_t(row) * std::uint32_t(columns_) + std::uint32_t(column);
  }

  SensorModel sensor_;
  int rows_ = 0, columns_ = 0;
  double row_guard_ = 0.0, column_guard_ = 0.0;  // kFastAtan2Error in rows and columns, with room for rounding
  double top_row_ = 0.0;                          // the field of view's top, in rows
  double per_row_ = 0.0, per_column_ = 0.0;       // 1 / the resolutions
  std::span<const double> around_;  // in the caller's storage
};

}  // namespace eco::detail
