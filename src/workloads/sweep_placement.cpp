#include <eco/workloads/sweep_placement.hpp>

#include <eco/io/pose_file.hpp>

#include <algorithm>

namespace eco::workloads {

std::size_t place_at_stamp(std::vector<Eigen::Vector3f>& points, std::span<const double> times, double stamp,
                           const PoseAtTime& pose_at) {
  if (times.empty()) return 0;
  const std::optional<Eigen::Isometry3d> at_stamp = pose_at(stamp);
  if (!at_stamp) return points.size();
  const Eigen::Isometry3d stamp_T_world = at_stamp->inverse();
  const auto [first, last] = std::ranges::minmax_element(times);
  constexpr int kSamples = 64;
  io::PoseTrack sweep;  // stamp_T_sensor(t) at times after the stamp where the poses reach
  for (int k = 0; k <= kSamples; ++k) {
    const double t = *first + (*last - *first) * double(k) / kSamples;
    if (const std::optional<Eigen::Isometry3d> pose = pose_at(stamp + t)) {
      sweep.times.push_back(t);
      sweep.poses.push_back(stamp_T_world * *pose);
    }
    if (*last == *first) break;
  }
  std::size_t unplaced = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::optional<Eigen::Isometry3d> stamp_T_sensor = io::pose_at(sweep, times[i]);
    if (!stamp_T_sensor) {
      ++unplaced;
      continue;
    }
    points[i] = (*stamp_T_sensor * points[i].cast<double>()).cast<float>();
  }
  return unplaced;
}

std::size_t place_frame_at_stamp(WorkloadFrame& frame, const PoseAtTime& pose_at) {
  if (frame.point_times.empty()) return 0;
  const std::size_t unplaced = place_at_stamp(frame.points, frame.point_times, frame.time, pose_at);
  frame.point_times.clear();
  return unplaced;
}

}  // namespace eco::workloads
