#pragma once
/// @file workload.hpp
/// A workload: frames of (sensor pose, points in the sensor frame), made on demand in any order,
/// ready for EgoOctree::update(frame.world_T_sensor, frame.points) — or, for a tree that keeps
/// per-point attributes, update(frame.world_T_sensor, AttributedScan(frame, first_id).view).

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace eco::workloads {

struct WorkloadFrame {
  std::size_t index = 0;
  Eigen::Isometry3d world_T_sensor = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3f> points;  ///< sensor frame
  std::vector<std::uint32_t> labels;    ///< SemanticKITTI label per point; empty when the source has none
  std::vector<float> intensities;       ///< intensity per point; empty when the source has none
  double time = 0.0;  ///< [s] when the frame was taken: the source's time, else index / 10 Hz
  std::vector<double> point_times;  ///< [s] after `time`, one per point, when the source times its points
};

/// A frame's points as a scan with per-point attributes, for a tree that keeps them: ids
/// numbered from `first_id`, the source's intensities (zero when it has none) and every point at
/// the frame's time. `view` reads `frame`'s points, which must outlive it.
struct AttributedScan {
  std::vector<std::uint32_t> ids;
  std::vector<float> intensities;
  std::vector<double> times;
  ScanView view;

  AttributedScan(const WorkloadFrame& frame, std::uint32_t first_id);
  AttributedScan(const AttributedScan&) = delete;  // `view` points into the arrays
  AttributedScan& operator=(const AttributedScan&) = delete;
};

/// The scan a tree keeping `kept` takes of `frame`: its points alone when it keeps no attribute,
/// else the view of an AttributedScan made in `attributed` (ids from frame.index * 2^20, unique
/// over a run of frames of up to a million points).
ScanView scan_for(const WorkloadFrame& frame, const KeptAttributes& kept, std::optional<AttributedScan>& attributed);

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
