#pragma once
/// @file trajectory_errors.hpp
/// How far an estimated trajectory is from a reference one, as LiDAR odometry is judged:
/// KITTI's relative errors over 100–800 m segments, the absolute trajectory error after a rigid
/// alignment, and the frame-to-frame relative pose error. Poses are world_T_sensor, both lists
/// of the same frames.

#include <Eigen/Geometry>

#include <cstddef>
#include <span>
#include <vector>

namespace eco::odometry {

/// KITTI's relative error over the segments of one length: from every 10th frame to the first
/// frame `length` metres farther along the reference path.
struct SegmentError {
  double length = 0.0;             ///< [m]
  std::size_t segments = 0;
  double translation_pct = 0.0;    ///< mean translational error / length [%]
  double rotation_deg_per_100m = 0.0;
};

struct TrajectoryErrors {
  std::size_t frames = 0;
  double path_length = 0.0;        ///< [m] along the reference
  /// Lengths 100, 200, ..., 800 m that fit in the drive (none for a drive under 100 m).
  std::vector<SegmentError> by_length;
  /// KITTI's figures: the mean over every segment of every length (0 without segments).
  double translation_pct = 0.0;
  double rotation_deg_per_100m = 0.0;
  /// [m] RMS position error after the rigid motion that best lays the estimate on the reference.
  double ate_rmse = 0.0;
  /// Frame-to-frame relative pose error, RMS: translation [m] and rotation [deg].
  double rpe_translation_rmse = 0.0;
  double rpe_rotation_rmse_deg = 0.0;
};

/// Throws std::invalid_argument unless both lists have the same number of poses, at least two.
[[nodiscard]] TrajectoryErrors trajectory_errors(std::span<const Eigen::Isometry3d> estimate,
                                                 std::span<const Eigen::Isometry3d> reference);

}  // namespace eco::odometry
