#pragma once
// The pixel of a sensor-frame point in the sensor's range image (SensorModel's formulas), found by
// comparisons rather than arctangents: free-space clearing looks one up for every return and every
// held point in range, and the two arctangents were most of that lookup.
//
// Elevation and azimuth are replaced by quantities that grow with them and cost a division each:
// the sine of the elevation, z / |v|, and a pseudo-angle of the azimuth, 0 at -180 deg rising
// through 1, 2, 3 at -90, 0, 90 deg to 4 at 180 deg (y / (|x| + |y|), shifted by quadrant).
// Each pixel wall is mapped into these once; a coarse table gives the wall just below a value and
// one comparison the next. Both maps have slope at most 1 per radian, so a value farther from
// every wall than its error (kGuard) lies on the same side of each wall as the angle the formulas
// compute; nearer, a more precise computation decides.

#include <eco/config.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
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
    return decide(v, range, direction_of(v.x(), v.y(), v.z(), range));
  }

  /// pixel_of for a group of points: their directions first, four at a time in single precision
  /// where the processor has vectors of four floats, then the walls; a point that single precision
  /// leaves undecided is looked up alone.
  static constexpr std::size_t kGroup = 16;
  struct Group {
    std::size_t size = 0;  // at most kGroup
    alignas(16) std::array<double, kGroup> x{}, y{}, z{};
  };
  void pixels_of(const Group& points, std::array<std::uint32_t, kGroup>& pixels,
                 std::array<double, kGroup>& ranges) const;

  /// The pixel by the formulas themselves, with libm's atan2; `range` gets |v|.
  [[nodiscard]] std::uint32_t exact_pixel_of(const Eigen::Vector3d& v, double& range) const;
  [[nodiscard]] std::uint32_t exact_pixel_of(const Eigen::Vector3d& v) const {
    double range = 0.0;
    return exact_pixel_of(v, range);
  }

  [[nodiscard]] int rows() const { return rows_; }
  [[nodiscard]] int columns() const { return columns_; }
  [[nodiscard]] std::uint32_t index(int row, int column) const {
    return std::uint32_t(row) * std::uint32_t(columns_) + std::uint32_t(column);
  }

 private:
  /// A point's sine of elevation and pseudo-angle, computed in Real.
  template <typename Real>
  struct Direction {
    Real sine;    // z / |v|
    Real pseudo;  // in [0, 4]
  };
  template <typename Real>
  [[nodiscard]] static Direction<Real> direction_of(Real x, Real y, Real z, Real range) {
    const Real d = y / (std::abs(x) + std::abs(y));  // in [-1, 1], rising with the angle in each half-plane
    return {z / range, x >= Real(0) ? Real(2) + d : (y >= Real(0) ? Real(4) - d : -d)};
  }

  /// How far a direction's value must lie from a wall to decide on which side of it the formulas'
  /// angle lies: above its error and the formulas' (~1e-13 rad), far below a pixel (HDL-64E: 7e-3
  /// of sine, 2e-3 of pseudo-angle). In double, the error is a few units of 1e-16; in single
  /// precision below 6 * 2^-24 = 3.6e-7 for the sine and 8 * 2^-24 = 4.8e-7 for the pseudo-angle,
  /// counting the rounding of v to float (tests/core/pixel_lookup_test.cpp fails at 1e-7).
  template <typename Real>
  static constexpr double kGuard = sizeof(Real) == sizeof(double) ? 1e-9 : 2e-6;

  /// The pixel of `v` from |v| and its direction; where Real leaves it undecided, double decides,
  /// and where double does, the formulas.
  template <typename Real>
  [[nodiscard]] std::uint32_t decide(const Eigen::Vector3d& v, double range, Direction<Real> direction) const {
    constexpr double guard = kGuard<Real>;
    const auto undecided = [&] {
      if constexpr (sizeof(Real) == sizeof(double)) {
        return exact_pixel_of(v);
      } else {
        return decide(v, range, direction_of(v.x(), v.y(), v.z(), range));
      }
    };
    const double sine = direction.sine, pseudo = direction.pseudo;
    if (!(range <= sensor_.max_range)) return kOutside;
    if (v.x() == 0.0 && v.y() == 0.0) return exact_pixel_of(v);  // straight up or down, or the origin
    if (!(sine >= row_walls_.front() + guard && sine <= fov_top_ - guard)) {
      const bool outside = sine < row_walls_.front() - guard || sine > fov_top_ + guard;
      return outside ? kOutside : undecided();  // clearly outside, or at the edge
    }
    const int row = between(row_walls_, row_start_, (sine - row_walls_.front()) * row_bins_per_unit_, sine, guard);
    const int column = between(column_walls_, column_start_, pseudo * column_bins_per_unit_, pseudo, guard);
    if ((row < 0) | (column < 0)) return undecided();  // within the guard of a wall
    return index(row, column);
  }

  /// The i with walls[i] + guard <= value < walls[i + 1] - guard, or -1 when the value lies within
  /// the guard of a wall (or the table's guess is off by more than one wall: a bin holding two).
  /// `bin` >= 0 is the value's position in start's bins (the last takes all beyond).
  [[nodiscard]] static int between(const std::vector<double>& walls, const std::vector<std::uint32_t>& start,
                                   double bin, double value, double guard) {
    const std::size_t b = std::min(std::size_t(bin), start.size() - 1);
    std::uint32_t i = start[b];
    i += value >= walls[i + 1] ? 1 : 0;
    const bool clear = (value - walls[i] >= guard) & (walls[i + 1] - value > guard);
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
