#include "odometry/point_to_plane.hpp"

#include "odometry/stopwatch.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

namespace eco::odometry {
namespace {

struct Plane {
  Eigen::Vector3d normal;
  Eigen::Vector3d centroid;
};

/// The plane through `points` (least squares), when every point lies within `tolerance` of it.
bool fit_plane(std::span<const Neighbor> points, double tolerance, Plane& plane) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Neighbor& n : points) centroid += n.point;
  centroid /= double(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Neighbor& n : points) {
    const Eigen::Vector3d d = n.point - centroid;
    scatter += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(scatter);
  const Eigen::Vector3d normal = solver.eigenvectors().col(0);  // of the smallest eigenvalue
  for (const Neighbor& n : points) {
    if (std::abs(normal.dot(n.point - centroid)) > tolerance) return false;
  }
  plane = {normal, centroid};
  return true;
}

/// `pose` moved by the small motion `step` (rotation vector, then translation) in the sensor's
/// own frame: linearised about the sensor, not the world's origin, which may lie kilometres away.
Eigen::Isometry3d moved_by(const Eigen::Isometry3d& pose, const Eigen::Matrix<double, 6, 1>& step) {
  const Eigen::Vector3d omega = step.head<3>();
  const double angle = omega.norm();
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  if (angle > 0.0) delta.linear() = Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
  delta.translation() = step.tail<3>();
  return orthonormal(pose * delta);
}

/// How far apart two poses are, as a step is measured: translation [m] plus rotation [rad].
double apart(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Isometry3d d = a.inverse() * b;
  return d.translation().norm() + Eigen::AngleAxisd(d.linear()).angle();
}

}  // namespace

Alignment PointToPlane::align(const LocalMap& map, std::span<const Eigen::Vector3d> source,
                              const Eigen::Isometry3d& guess, const AlignSettings& settings) {
  Alignment result;
  result.pose = guess;
  const std::size_t k = settings.neighbours;
  moved_.resize(source.size());
  neighbours_.resize(source.size() * k);
  found_.resize(source.size());
  const double max_sq = settings.max_distance * settings.max_distance;
  const double reach_sq = settings.plane_reach * settings.plane_reach;
  std::array<Eigen::Isometry3d, 8> recent;  // the poses after the last eight steps
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    result.iterations = iteration + 1;
    Stopwatch query;
    for (std::size_t i = 0; i < source.size(); ++i) moved_[i] = result.pose * source[i];
    map.knn(moved_, k, neighbours_, found_);
    result.query_ms += query.ms();

    Stopwatch solve;
    const double scale_sq = settings.kernel_scale * settings.kernel_scale;
    Eigen::Matrix<double, 6, 6> hessian = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
    std::size_t used = 0;
    std::size_t inliers = 0;
    for (std::size_t i = 0; i < source.size(); ++i) {
      const std::span<const Neighbor> near(neighbours_.data() + i * k, found_[i]);
      Plane plane;
      if (found_[i] < k || near.front().sq_dist > max_sq || near.back().sq_dist > reach_sq ||
          !fit_plane(near, settings.plane_tolerance, plane)) {
        continue;
      }
      const double residual = plane.normal.dot(moved_[i] - plane.centroid);
      const double ratio = residual * residual / scale_sq;
      const double weight = 1.0 / ((1.0 + ratio) * (1.0 + ratio));  // Geman–McClure
      const Eigen::Vector3d normal = result.pose.linear().transpose() * plane.normal;  // in the sensor frame
      Eigen::Matrix<double, 6, 1> jacobian;
      jacobian << source[i].cross(normal), normal;
      hessian.noalias() += weight * jacobian * jacobian.transpose();
      gradient.noalias() += weight * residual * jacobian;
      ++used;
      inliers += std::abs(residual) <= settings.fit_distance;
    }
    result.correspondences = used;
    result.inliers = inliers;
    if (used < 6) {
      result.solve_ms += solve.ms();
      break;
    }
    const Eigen::Matrix<double, 6, 1> step = -hessian.ldlt().solve(gradient);
    result.pose = moved_by(result.pose, step);
    result.solve_ms += solve.ms();
    if (step.norm() < settings.convergence) break;
    // a cycle: a few neighbours swapping back and forth as the pose moves a fraction of a
    // millimetre lead back to where the pose stood a few steps ago
    const std::size_t seen = std::min<std::size_t>(std::size_t(iteration), recent.size());
    const bool cycled = std::any_of(recent.begin(), recent.begin() + std::ptrdiff_t(seen), [&](const Eigen::Isometry3d& p) {
      return apart(result.pose, p) < settings.convergence;
    });
    if (cycled) break;
    recent[std::size_t(iteration) % recent.size()] = result.pose;
  }
  return result;
}

}  // namespace eco::odometry
