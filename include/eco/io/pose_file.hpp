#pragma once
/// @file pose_file.hpp
/// A trajectory file as `--poses` takes it: KITTI's format (12 numbers a line, row-major 3x4, a
/// line per scan) or TUM's (`timestamp tx ty tz qx qy qz qw`, `#` comments), told apart by the
/// count of numbers on the first line.

#include <Eigen/Geometry>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace eco::io {

struct PoseTrack {
  std::vector<Eigen::Isometry3d> poses;
  std::vector<double> times;  ///< [s] one per pose (TUM), or empty (KITTI)
  [[nodiscard]] bool timed() const { return !times.empty(); }
};

/// A position and an orientation (a unit quaternion, normalised once more) as a pose: how a TUM
/// line, a ROS pose or transform message and eco_node's poses are read.
[[nodiscard]] Eigen::Isometry3d pose_of(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation);

/// The pose at `time` of a timed track: translations interpolated linearly and rotations by
/// slerp between the poses either side; nullopt outside the track's span (or for a track
/// without times).
[[nodiscard]] std::optional<Eigen::Isometry3d> pose_at(const PoseTrack& track, double time);

/// Throws eco::io::Error naming the file and line: a line of another length, a number that is not
/// one, a quaternion far from unit length, times that go back.
[[nodiscard]] PoseTrack read_pose_file(const std::filesystem::path& path);
[[nodiscard]] PoseTrack parse_pose_file(std::string_view text, const std::string& source);

}  // namespace eco::io
