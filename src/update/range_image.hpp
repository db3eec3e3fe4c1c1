#pragma once
// The scan as free-space clearing sees it: its returns binned into the sensor's range image
// (SensorModel, include/eco/config.hpp), each pixel knowing the nearest return around it.

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace eco::detail {

/// A pixel of the range image.
struct Pixel {
  int row = 0;
  int column = 0;
};

/// For every pixel, the nearest return of a scan among that pixel and its 8 neighbours (columns
/// wrap around the circle, rows stop at the image's edge); infinity where none came back.
class RangeImage {
 public:
  /// Bins every finite return of `scan` (sensor frame) that pixel_of places in the image, in
  /// `storage` (resized to two images; the caller keeps it between frames, so that no frame pays
  /// for fresh pages, and while this image is read).
  RangeImage(const SensorModel& sensor, ScanView scan, std::vector<double>& storage);

  /// The pixel of the sensor-frame point `v` (SensorModel's formulas), none when it lies outside
  /// the vertical field of view or beyond max_range; `range` gets |v|. Exactly exact_pixel_of(),
  /// faster: the angles come from a polynomial, and any decision they take within its error of a
  /// wall (a pixel's, the field of view's) is taken again by exact_pixel_of().
  [[nodiscard]] std::optional<Pixel> pixel_of(const Eigen::Vector3d& v, double& range) const {
    const double horizontal = std::sqrt(v.x() * v.x() + v.y() * v.y());
    if (horizontal == 0.0) return exact_pixel_of(v, range);  // straight up or down, or the origin
    range = v.norm();
    if (!(range <= sensor_.max_range)) return std::nullopt;
    const double elevation = fast_atan2_degrees(v.z(), horizontal);
    if (near(elevation, sensor_.vertical_fov_min) || near(elevation, sensor_.vertical_fov_max)) {
      return exact_pixel_of(v, range);
    }
    if (elevation < sensor_.vertical_fov_min || elevation >= sensor_.vertical_fov_max) return std::nullopt;
    // reciprocals: their rounding is far inside the guards
    const double row = (elevation - sensor_.vertical_fov_min) * per_row_;
    const double column = (fast_atan2_degrees(v.y(), v.x()) + 180.0) * per_column_;
    if (near_whole(row, row_guard_) || near_whole(column, column_guard_)) return exact_pixel_of(v, range);
    return Pixel{std::min(rows_ - 1, int(row)), int(column) % columns_};
  }

  /// The pixel by the formulas themselves, with libm's atan2.
  [[nodiscard]] std::optional<Pixel> exact_pixel_of(const Eigen::Vector3d& v, double& range) const {
    constexpr double kPi = 3.14159265358979323846;
    range = v.norm();
    if (!(range <= sensor_.max_range)) return std::nullopt;
    const double elevation = std::atan2(v.z(), std::hypot(v.x(), v.y())) * 180.0 / kPi;
    if (elevation < sensor_.vertical_fov_min || elevation >= sensor_.vertical_fov_max) return std::nullopt;
    const double azimuth = std::atan2(v.y(), v.x()) * 180.0 / kPi;
    const int row = std::min(rows_ - 1, int((elevation - sensor_.vertical_fov_min) / sensor_.vertical_resolution));
    const int column = int((azimuth + 180.0) / sensor_.horizontal_resolution) % columns_;
    return Pixel{row, column};
  }

  /// atan2(y, x) in degrees for (x, y) != (0, 0), within kFastAtan2Error: atan of the smaller over
  /// the larger of |x|, |y| by Abramowitz & Stegun's polynomial 4.4.49 (|error| <= 2e-8 rad),
  /// then the octant's symmetries.
  static double fast_atan2_degrees(double y, double x) {
    constexpr double kPi = 3.14159265358979323846;
    const double ax = std::abs(x), ay = std::abs(y);
    const double t = std::min(ax, ay) / std::max(ax, ay);
    const double s = t * t;
    double a = t * (1.0 + s * (-0.3333314528 + s * (0.1999355085 + s * (-0.1420889944 + s * (0.1065626393 +
               s * (-0.0752896400 + s * (0.0429096138 + s * (-0.0161657367 + s * 0.0028662257))))))));
    if (ay > ax) a = kPi / 2 - a;
    if (x < 0.0) a = kPi - a;
    if (std::signbit(y)) a = -a;
    return a * (180.0 / kPi);
  }
  /// [deg] fast_atan2_degrees' error bound, with room: the polynomial's is below 1e-6 degrees
  /// (tests/core/free_space_test.cpp measures it).
  static constexpr double kFastAtan2Error = 1e-5;
  /// The nearest return around pixel `p` [m]; infinity when none came back there.
  [[nodiscard]] double nearest_around(Pixel p) const { return around_[index(p.row, p.column)]; }
  /// Whether any return came back around pixel `p`.
  [[nodiscard]] bool returned_around(Pixel p) const { return nearest_around(p) < kNoReturn; }

  static constexpr double kNoReturn = std::numeric_limits<double>::infinity();

 private:
  /// Whether angle `a` [deg] from fast_atan2_degrees may lie on the other side of `wall`.
  static bool near(double a, double wall) { return std::abs(a - wall) <= kFastAtan2Error; }
  /// Whether `u` lies within `guard` of a whole number (a pixel wall).
  static bool near_whole(double u, double guard) {
    const double f = u - std::floor(u);
    return f <= guard || f >= 1.0 - guard;
  }
  [[nodiscard]] std::size_t index(int row, int column) const { return std::size_t(row) * std::size_t(columns_) + std::size_t(column); }

  SensorModel sensor_;
  int rows_ = 0, columns_ = 0;
  double row_guard_ = 0.0, column_guard_ = 0.0;  // kFastAtan2Error in rows and columns, with room for rounding
  double per_row_ = 0.0, per_column_ = 0.0;       // 1 / the resolutions
  std::span<const double> around_;  // in the caller's storage
};

}  // namespace eco::detail
