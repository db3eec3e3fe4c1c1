#pragma once
// A robot's recording (io::Recording) as frames: a cloud a frame, its points in the sensor's
// frame with their times, placed by a timed trajectory when one is given (interpolated at the
// cloud's stamp; clouds outside it are left out and counted).

#include <eco/io/pose_file.hpp>
#include <eco/io/recording.hpp>
#include <eco/workloads/workload.hpp>

#include <optional>
#include <vector>

namespace eco::workloads {

class RecordingWorkload final : public Workload {
 public:
  /// With a timed `track` (TUM), reads each cloud's stamp once to place it; an untimed one (KITTI)
  /// gives a pose a cloud, in order.
  RecordingWorkload(io::Recording recording, std::optional<io::PoseTrack> track);

  [[nodiscard]] std::size_t size() const override { return clouds_.size(); }
  /// Reads and decodes the cloud (not safe from several threads at once).
  [[nodiscard]] WorkloadFrame frame(std::size_t index) const override;
  [[nodiscard]] Eigen::Isometry3d pose(std::size_t index) const override;
  [[nodiscard]] std::string name() const override { return "dynamic"; }

  [[nodiscard]] const io::Recording& recording() const { return recording_; }
  /// Clouds left out for lying outside the trajectory's span.
  [[nodiscard]] std::size_t outside_poses() const { return recording_.size() - clouds_.size(); }

 private:
  mutable io::Recording recording_;
  std::vector<std::size_t> clouds_;          // the recording's clouds kept, in order
  std::vector<Eigen::Isometry3d> poses_;     // one a kept cloud, with a trajectory
};

}  // namespace eco::workloads
