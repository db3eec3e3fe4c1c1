#pragma once
/// @file workload.hpp
/// A workload: frames of (sensor pose, points in the sensor frame), made on demand in any order,
/// ready for EgoOctree::update(frame.world_T_sensor, frame.points).

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace eco::workloads {

struct WorkloadFrame {
  std::size_t index = 0;
  Eigen::Isometry3d world_T_sensor = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3f> points;  ///< sensor frame
  std::vector<std::uint32_t> labels;    ///< SemanticKITTI label per point; empty when the source has none
};

class Workload {
 public:
  virtual ~Workload() = default;
  [[nodiscard]] virtual std::size_t size() const = 0;
  /// Frame `index` < size(); throws std::out_of_range past the end.
  [[nodiscard]] virtual WorkloadFrame frame(std::size_t index) const = 0;
  /// The sensor pose of frame `index` alone, without making its points.
  [[nodiscard]] virtual Eigen::Isometry3d pose(std::size_t index) const = 0;
  [[nodiscard]] virtual std::string name() const = 0;
};

}  // namespace eco::workloads
