#include <eco/odometry/trajectory_errors.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace eco::odometry {
namespace {

constexpr std::size_t kSegmentStep = 10;  // KITTI's devkit starts a segment every 10th frame
constexpr double kDegrees = 180.0 / std::numbers::pi;

double angle_of(const Eigen::Isometry3d& motion) { return Eigen::AngleAxisd(motion.linear()).angle(); }

/// The motion from frame i to frame j, as `poses` see it.
Eigen::Isometry3d between(std::span<const Eigen::Isometry3d> poses, std::size_t i, std::size_t j) {
  return poses[i].inverse() * poses[j];
}

std::vector<double> distances_along(std::span<const Eigen::Isometry3d> poses) {
  std::vector<double> along(poses.size(), 0.0);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    along[i] = along[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm();
  }
  return along;
}

}  // namespace

TrajectoryErrors trajectory_errors(std::span<const Eigen::Isometry3d> estimate,
                                   std::span<const Eigen::Isometry3d> reference) {
  if (estimate.size() != reference.size() || estimate.size() < 2) {
    throw std::invalid_argument("trajectory errors need two lists of the same frames, at least two: got " +
                                std::to_string(estimate.size()) + " estimated and " +
                                std::to_string(reference.size()) + " reference poses");
  }
  TrajectoryErrors errors;
  const std::size_t n = estimate.size();
  errors.frames = n;
  const std::vector<double> along = distances_along(reference);
  errors.path_length = along.back();

  std::size_t all_segments = 0;
  for (int hundreds = 1; hundreds <= 8; ++hundreds) {
    SegmentError s;
    s.length = 100.0 * hundreds;
    std::size_t last = 0;
    for (std::size_t first = 0; first < n; first += kSegmentStep) {
      last = std::max(last, first);
      while (last < n && along[last] < along[first] + s.length) ++last;
      if (last == n) break;
      const Eigen::Isometry3d error = between(estimate, first, last).inverse() * between(reference, first, last);
      s.translation_pct += error.translation().norm() / s.length * 100.0;
      s.rotation_deg_per_100m += angle_of(error) * kDegrees / s.length * 100.0;
      ++s.segments;
    }
    if (s.segments == 0) continue;
    errors.translation_pct += s.translation_pct;
    errors.rotation_deg_per_100m += s.rotation_deg_per_100m;
    all_segments += s.segments;
    s.translation_pct /= double(s.segments);
    s.rotation_deg_per_100m /= double(s.segments);
    errors.by_length.push_back(s);
  }
  if (all_segments > 0) {
    errors.translation_pct /= double(all_segments);
    errors.rotation_deg_per_100m /= double(all_segments);
  }

  Eigen::Matrix3Xd from(3, n), to(3, n);
  for (std::size_t i = 0; i < n; ++i) {
    from.col(Eigen::Index(i)) = estimate[i].translation();
    to.col(Eigen::Index(i)) = reference[i].translation();
  }
  const Eigen::Matrix4d align = Eigen::umeyama(from, to, false);
  const Eigen::Matrix3Xd laid = (align.topLeftCorner<3, 3>() * from).colwise() + align.topRightCorner<3, 1>();
  errors.ate_rmse = std::sqrt((laid - to).colwise().squaredNorm().mean());

  double sq_translation = 0.0;
  double sq_rotation = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    const Eigen::Isometry3d error = between(estimate, i - 1, i).inverse() * between(reference, i - 1, i);
    sq_translation += error.translation().squaredNorm();
    sq_rotation += std::pow(angle_of(error) * kDegrees, 2);
  }
  errors.rpe_translation_rmse = std::sqrt(sq_translation / double(n - 1));
  errors.rpe_rotation_rmse_deg = std::sqrt(sq_rotation / double(n - 1));
  return errors;
}

}  // namespace eco::odometry
