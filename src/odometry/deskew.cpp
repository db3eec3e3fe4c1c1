#include "odometry/deskew.hpp"

#include <algorithm>

namespace eco::odometry {

Eigen::Isometry3d part_of(const Eigen::Isometry3d& motion, double s) {
  Eigen::Isometry3d part = Eigen::Isometry3d::Identity();
  part.linear() = Eigen::Quaterniond::Identity().slerp(s, Eigen::Quaterniond(motion.linear())).toRotationMatrix();
  part.translation() = s * motion.translation();
  return part;
}

void deskew(std::vector<Eigen::Vector3f>& points, std::span<const double> times, const Eigen::Isometry3d& motion) {
  if (times.empty()) return;
  const auto [first, last] = std::ranges::minmax_element(times);
  const double sweep = *last - std::min(0.0, *first);
  if (!(sweep > 0.0)) return;
  const Eigen::Isometry3d from_middle = part_of(motion, 0.5).inverse();
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = (from_middle * part_of(motion, times[i] / sweep) * points[i].cast<double>()).cast<float>();
  }
}

}  // namespace eco::odometry
