#pragma once
// Point-to-plane ICP against a LocalMap: each iteration asks the map for the k nearest points of
// every source point under the current pose, fits a plane to each set that is flat enough, and
// takes one Gauss–Newton step on the robust (Geman–McClure) sum of squared point-to-plane
// distances. The buffers live between calls: no allocation per iteration once warm.

#include <eco/odometry/local_map.hpp>

#include <Eigen/Geometry>

#include <cstddef>
#include <span>
#include <vector>

namespace eco::odometry {

struct AlignSettings {
  std::size_t neighbours = 5;     // k
  double max_distance = 1.0;      // [m] a source point farther than this from its nearest map point is left out
  double kernel_scale = 0.1;      // [m] the Geman–McClure kernel's scale
  double plane_tolerance = 0.2;   // [m] every neighbour this close to the fitted plane
  double plane_reach = 1.0;       // [m] every neighbour this close to the point registered
  int max_iterations = 50;
  double convergence = 1e-4;      // [m, rad] a step smaller than this ends the iterations
  double fit_distance = 0.1;      // [m] a correspondence this close to its plane counts as an inlier
};

struct Alignment {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  int iterations = 0;
  std::size_t correspondences = 0;  // in the last iteration
  std::size_t inliers = 0;          // of those, within fit_distance of their plane
  double query_ms = 0.0;
  double solve_ms = 0.0;
};

/// `pose` with its rotation made orthonormal again: products of rotations drift in the last bits,
/// and the maps check poses to 1e-6.
[[nodiscard]] inline Eigen::Isometry3d orthonormal(Eigen::Isometry3d pose) {
  pose.linear() = Eigen::Quaterniond(pose.linear()).normalized().toRotationMatrix();
  return pose;
}

class PointToPlane {
 public:
  /// `source` (sensor frame) aligned to `map`, from `guess` (world_T_sensor). With fewer than six
  /// planes found the pose stays where the last step left it.
  Alignment align(const LocalMap& map, std::span<const Eigen::Vector3d> source, const Eigen::Isometry3d& guess,
                  const AlignSettings& settings);

 private:
  std::vector<Eigen::Vector3d> moved_;  // the source under the current pose
  std::vector<Neighbor> neighbours_;
  std::vector<std::size_t> found_;
};

}  // namespace eco::odometry
