#pragma once
// The pixel of a sensor-frame point in the sensor's range image (SensorModel's formulas), found by
// comparisons rather than arctangents: free-space clearing looks one up for every return and every
// held point in range, and the two arctangents were most of that lookup.
//
// Elevation and azimuth are replaced by quantities that grow with them and cost a division each:
// the sine of the elevation, z / |v|, and a pseudo-angle of the azimuth, 0 at -180 deg rising
// through 1, 2, 3 at -90, 0, 90 deg to 4 at 180 deg (y / (|x| + |y|), shifted by quadrant). Each
// pixel wall is mapped into these once; a coarse table gives the wall just below a value and one
// comparison the next. Both maps have slope at most 1 per radian, so a value farther than kGuard
// from every wall lies on the same side of each wall as the angle the formulas compute (their
// rounding is ~1e-13 rad); nearer, the formulas decide.

#include <eco/config.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace eco::detail {

class PixelLookup {
 public:
  /// No pixel: the point lies outside the vertical field of view or beyond max_range.
  static constexpr std::uint32_t kOutside = std::numeric_limits<std::uint32_t>::max();

  explicit PixelLookup(const SensorModel& sensor);

  /// The pixel (row * columns + column) of the sensor-frame point `v`, or kOutside; `range` gets
  /// |v|. Exactly exact_pixel_of(), faster.
  [[nodiscard]] std::uint32_t pixel_of(const Eigen::Vector3d& v, double& range) const {
    range = v.norm();
    if (!(range <= sensor_.max_range)) return kOutside;
    if (v.x() == 0.0 && v.y() == 0.0) return exact_pixel_of(v, range);  // straight up or down, or the origin
    const double sine = v.z() / range;
    if (!(sine >= row_walls_.front() + kGuard && sine <= fov_top_ - kGuard)) {
      const bool outside = sine < row_walls_.front() - kGuard || sine > fov_top_ + kGuard;
      return outside ? kOutside : exact_pixel_of(v, range);  // clearly outside, or at the edge
    }
    const double ax = std::abs(v.x()), ay = std::abs(v.y());
    const double d = v.y() / (ax + ay);  // in [-1, 1], rising with the angle in each half-plane
    const double pseudo = v.x() >= 0.0 ? 2.0 + d : (v.y() >= 0.0 ? 4.0 - d : -d);
    const int row = between(row_walls_, row_start_, (sine - row_walls_.front()) * row_bins_per_unit_, sine);
    const int column = between(column_walls_, column_start_, pseudo * column_bins_per_unit_, pseudo);
    if ((row < 0) | (column < 0)) return exact_pixel_of(v, range);  // within kGuard of a wall
    return index(row, column);
  }

  /// The pixel by the formulas themselves, with libm's atan2.
  [[nodiscard]] std::uint32_t exact_pixel_of(const Eigen::Vector3d& v, double& range) const;

  [[nodiscard]] int rows() const { return rows_; }
  [[nodiscard]] int columns() const { return columns_; }
  [[nodiscard]] std::uint32_t index(int row, int column) const {
    return std::uint32_t(row) * std::uint32_t(columns_) + std::uint32_t(column);
  }

 private:
  /// Far above the rounding of the formulas' angles and of the walls' values, far below a pixel.
  static constexpr double kGuard = 1e-9;

  /// The i with walls[i] + kGuard <= value < walls[i + 1] - kGuard, or -1 when the value lies within
  /// kGuard of a wall (or the table's guess is off by more than one wall: a bin holding two).
  /// `bin` >= 0 is the value's position in start's bins (the last takes all beyond).
  [[nodiscard]] static int between(const std::vector<double>& walls, const std::vector<std::uint32_t>& start,
                                   double bin, double value) {
    const std::size_t b = std::min(std::size_t(bin), start.size() - 1);
    std::uint32_t i = start[b];
    i += value >= walls[i + 1] ? 1 : 0;
    const bool clear = (value - walls[i] >= kGuard) & (walls[i + 1] - value > kGuard);
    return clear ? int(i) : -1;
  }

  SensorModel sensor_;
  int rows_ = 0, columns_ = 0;
  // sin(elevation) of each row's lower wall, then of the field of view's top, then +infinity
  std::vector<double> row_walls_;
  // the pseudo-angle of each column's left wall, then 4 (the seam at 180 deg), then +infinity
  std::vector<double> column_walls_;
  std::vector<std::uint32_t> row_start_, column_start_;  // per bin: the wall at or below its lower end
  double fov_top_ = 0.0;  // sin(vertical_fov_max)
  double row_bins_per_unit_ = 0.0, column_bins_per_unit_ = 0.0;
};

}  // namespace eco::detail
