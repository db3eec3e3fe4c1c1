#pragma once
/// @file point_cloud.hpp
/// A scan or map as read from or written to a file: points and, optionally, one intensity each.

#include <eco/types.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace eco::io {

struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<float> intensity;  ///< empty, or one value per point (KITTI: reflectance in [0, 1])

  [[nodiscard]] std::size_t size() const { return points.size(); }
  [[nodiscard]] bool has_intensity() const { return !intensity.empty(); }
  /// The points as an ECO scan (valid while the cloud is alive and unchanged).
  [[nodiscard]] ScanView view() const { return ScanView(points); }
};

}  // namespace eco::io
