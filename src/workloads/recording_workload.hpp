#pragma once
// A robot's recording (io::Recording) as frames: a cloud a frame, its points in the sensor's
// frame with their times, placed by the poses given: one a cloud in order, or a pose at any time
// (interpolated at the cloud's stamp; clouds outside the poses' span are left out and counted).

#include <eco/io/recording.hpp>
#include <eco/workloads/sweep_placement.hpp>
#include <eco/workloads/workload.hpp>

#include <vector>

namespace eco::workloads {

/// Where a recording's clouds were taken.
struct CloudPoses {
  std::vector<Eigen::Isometry3d> in_order;  ///< a pose a cloud, in order (a KITTI-format file); or
  PoseAtTime at_time;                       ///< the LiDAR's pose at any time (a TUM file, a pose topic, tf)
  /// With at_time and per-point times: each point placed by the pose at its own time, the frame's
  /// points then held in the sensor's frame at the stamp, without the sweep's smear (and without
  /// times: there is nothing left to deskew). Off where the poses are only a reference to compare
  /// an estimate with.
  bool place_points = true;
};

class RecordingWorkload final : public Workload {
 public:
  /// With poses at_time, reads each cloud's stamp once to place it. Throws eco::io::Error when
  /// in-order poses are fewer than the clouds.
  RecordingWorkload(io::Recording recording, std::optional<CloudPoses> poses);

  [[nodiscard]] std::size_t size() const override { return clouds_.size(); }
  /// Reads and decodes the cloud (not safe from several threads at once).
  [[nodiscard]] WorkloadFrame frame(std::size_t index) const override;
  [[nodiscard]] Eigen::Isometry3d pose(std::size_t index) const override;
  [[nodiscard]] std::string name() const override { return "dynamic"; }

  [[nodiscard]] const io::Recording& recording() const { return recording_; }
  /// Clouds left out for lying outside the poses' span.
  [[nodiscard]] std::size_t outside_poses() const { return recording_.size() - clouds_.size(); }

 private:
  mutable io::Recording recording_;
  std::optional<CloudPoses> given_;
  std::vector<std::size_t> clouds_;       // the recording's clouds kept, in order
  std::vector<Eigen::Isometry3d> poses_;  // one a kept cloud, when poses are given
};

}  // namespace eco::workloads
