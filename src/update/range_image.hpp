#pragma once
// The scan as free-space clearing sees it: its returns binned into the sensor's range image
// (SensorModel, include/eco/config.hpp), each pixel knowing the nearest return around it.

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
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
  /// Bins every finite return of `scan` (sensor frame) that pixel_of places in the image.
  RangeImage(const SensorModel& sensor, ScanView scan);

  /// The pixel of the sensor-frame point `v` (SensorModel's formulas), none when it lies outside
  /// the vertical field of view or beyond max_range; `range` gets |v|.
  [[nodiscard]] std::optional<Pixel> pixel_of(const Eigen::Vector3d& v, double& range) const {
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

  /// The nearest return around pixel `p` [m]; infinity when none came back there.
  [[nodiscard]] double nearest_around(Pixel p) const { return around_[index(p.row, p.column)]; }
  /// Whether any return came back around pixel `p`.
  [[nodiscard]] bool returned_around(Pixel p) const { return nearest_around(p) < kNoReturn; }

  static constexpr double kNoReturn = std::numeric_limits<double>::infinity();

 private:
  [[nodiscard]] std::size_t index(int row, int column) const { return std::size_t(row) * std::size_t(columns_) + std::size_t(column); }

  SensorModel sensor_;
  int rows_ = 0, columns_ = 0;
  std::vector<double> around_;
};

}  // namespace eco::detail
