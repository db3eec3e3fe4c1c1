#pragma once
// The pixel of a sensor-frame point in the sensor's range image (SensorModel's formulas), exactly
// as the formulas give it and much faster: free-space clearing looks one up for every return and
// every held point in range. Three tiers, each deciding only where its error cannot matter:
//
// 1. Groups of points in vector code (core/vector_clones.hpp: four lanes with SSE2, eight with
//    AVX2), in single precision: elevation and azimuth by a polynomial arctangent
//    (src/update/fast_atan2.hpp), row and column by truncation, wherever both angles lie farther
//    than kAngleGuard from every wall.
// 2. One point in double, without arctangents: the elevation replaced by its sine, z / |v|, and
//    the azimuth by a pseudo-angle that rises with it, 0 at -180 deg through 1, 2, 3 at -90, 0,
//    90 deg to 4 at 180 deg (y / (|x| + |y|), shifted by quadrant). Each wall is mapped into these
//    once; a coarse table gives the wall just below a value and one comparison the next. Both maps
//    have slope at most 1 per radian, so a value farther than kGuard from every wall lies on the
//    formulas' side of each.
// 3. The formulas themselves, with libm's atan2 (exact_pixel_of).

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
  /// |v|. Exactly exact_pixel_of(), faster (tier 2, then 3).
  [[nodiscard]] std::uint32_t pixel_of(const Eigen::Vector3d& v, double& range) const {
    range = v.norm();
    if (!(range <= sensor_.max_range)) return kOutside;
    if (v.x() == 0.0 && v.y() == 0.0) return exact_pixel_of(v);  // straight up or down, or the origin
    const double sine = v.z() / range;
    if (!(sine >= row_walls_.front() + kGuard && sine <= fov_top_ - kGuard)) {
      const bool outside = sine < row_walls_.front() - kGuard || sine > fov_top_ + kGuard;
      return outside ? kOutside : exact_pixel_of(v);  // clearly outside, or at the edge
    }
    const double pseudo = pseudo_angle(v.x(), v.y());
    const int row = between(row_walls_, row_start_, (sine - row_walls_.front()) * row_bins_per_unit_, sine);
    const int column = between(column_walls_, column_start_, pseudo * column_bins_per_unit_, pseudo);
    if ((row < 0) | (column < 0)) return exact_pixel_of(v);  // within kGuard of a wall
    return index(row, column);
  }

  /// Tier 2's stand-in for the azimuth of (x, y) != (0, 0): in [0, 4], rising with it.
  [[nodiscard]] static double pseudo_angle(double x, double y) {
    const double d = y / (std::abs(x) + std::abs(y));  // in [-1, 1], rising with the angle in each half-plane
    return x >= 0.0 ? 2.0 + d : (y >= 0.0 ? 4.0 - d : -d);
  }

  /// pixel_of for a group of points (tier 1, then 2 and 3 for the points it leaves).
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
  /// [deg] How far tier 1's angles must lie from a wall: above their error (fast_atan2's, and the
  /// rounding of the rows' and columns' arithmetic in single precision, below 2e-5 deg more),
  /// far below a pixel (HDL-64E: 0.42 x 0.2 deg). The test passes at 5e-5 and fails at 2e-5.
  static constexpr double kAngleGuard = 2e-4;

  /// How far tier 2's values must lie from a wall: above their error and the walls' (each a few
  /// units of 1e-16) and the formulas' (atan2 within an ulp, the degrees' arithmetic within
  /// 3e-14 deg: below 1e-15 rad), far below a pixel (HDL-64E: 7e-3 of sine, 2e-3 of
  /// pseudo-angle). The test passes at 1e-14 and fails at 0.
  static constexpr double kGuard = 1e-12;

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

  /// Tier 1's walls and guards in single precision [deg, and rows or columns].
  struct FirstTierWalls {
    float fov_min, low, high, below, above;  // the field of view's bottom, and it and its top with the guard inside and outside
    float per_row, per_column;
    float row_guard, row_room, column_guard, column_room;  // the guard in rows and columns, and 1 - it
    float seam;                                            // 360 deg in columns, less the guard
    std::uint32_t columns;
    double max_range;
  };
  /// Tier 1's verdict on a point it leaves to tiers 2 and 3 (no pixel has this index: kMaxPixels).
  static constexpr std::uint32_t kUndecided = kOutside - 1;
  /// Static, its walls handed in: a member's fields could alias the outputs for all the compiler
  /// knows, and it would not vectorise the loop.
  static void first_tier(const Group& points, const FirstTierWalls& walls, std::array<std::uint32_t, kGroup>& pixels,
                         std::array<double, kGroup>& ranges);

  SensorModel sensor_;
  FirstTierWalls fast_{};
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
