#include "recording_workload.hpp"

#include <eco/io/error.hpp>

#include <stdexcept>

namespace eco::workloads {

RecordingWorkload::RecordingWorkload(io::Recording recording, std::optional<CloudPoses> poses)
    : recording_(std::move(recording)), given_(std::move(poses)) {
  const bool timed = given_ && given_->at_time;
  if (given_ && !timed && given_->in_order.size() < recording_.size()) {
    throw io::Error(recording_.describe(), "", std::to_string(given_->in_order.size()) + " poses for " +
                                                   std::to_string(recording_.size()) + " clouds: one pose a cloud, in order");
  }
  for (std::size_t i = 0; i < recording_.size(); ++i) {
    if (!timed) {
      clouds_.push_back(i);
      if (given_) poses_.push_back(given_->in_order[i]);
      continue;
    }
    if (const std::optional<Eigen::Isometry3d> pose = given_->at_time(double(recording_.stamp_ns(i)) * 1e-9)) {
      clouds_.push_back(i);
      poses_.push_back(*pose);
    }
  }
}

WorkloadFrame RecordingWorkload::frame(std::size_t index) const {
  io::RecordedScan scan = recording_.read(clouds_.at(index));
  WorkloadFrame out;
  out.index = index;
  out.world_T_sensor = pose(index);
  out.points = std::move(scan.cloud.points);
  out.intensities = std::move(scan.cloud.intensities);
  out.time = double(scan.stamp_ns) * 1e-9;
  out.point_times = std::move(scan.cloud.times);
  if (given_ && given_->at_time && given_->place_points) (void)place_frame_at_stamp(out, given_->at_time);
  return out;
}

Eigen::Isometry3d RecordingWorkload::pose(std::size_t index) const {
  if (index >= clouds_.size()) throw std::out_of_range("frame " + std::to_string(index) + " of " + std::to_string(clouds_.size()));
  return poses_.empty() ? Eigen::Isometry3d::Identity() : poses_[index];
}

}  // namespace eco::workloads
