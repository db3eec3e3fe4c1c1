// The frame's motion (motion.hpp): the clock, the precision origin, the next Motion.

#include "core/geometry/motion.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace eco::detail {
namespace {

constexpr double kOriginStep = 1024.0;   // the precision origin moves in whole steps of this [m]
constexpr double kOriginReach = 2048.0;  // ... once the sensor is farther than this from it [m]
constexpr double kClockStep = 64.0;     // the time origin moves in whole steps of this [s]
constexpr double kClockReach = 128.0;   // ... once the latest time is farther than this from it [s]

Eigen::Vector3d nearest_origin(const Eigen::Vector3d& position) {
  return (position / kOriginStep).array().round().matrix() * kOriginStep;
}

}  // namespace

Clock Clock::after(double scan_latest, bool move) const {
  Clock next = *this;
  next.shift.reset();
  if (!(scan_latest > latest)) return next;
  const bool first = latest == -std::numeric_limits<double>::infinity();
  next.latest = scan_latest;
  if (first || (move && scan_latest - origin > kClockReach)) {
    next.origin = std::floor(scan_latest / kClockStep) * kClockStep;
    if (!first) next.shift = origin - next.origin;
  }
  return next;
}

Eigen::Vector3d precision_origin_for(const Eigen::Vector3d& position, const Eigen::Vector3d& anchor,
                                     bool first) {
  if (first || (position - anchor).cwiseAbs().maxCoeff() > kOriginReach) return nearest_origin(position);
  return anchor;
}

std::string describe_pose(const Eigen::Isometry3d& pose) {
  std::ostringstream s;
  s << "[" << pose.matrix().topRows<3>().format(Eigen::IOFormat(6, 0, ", ", "; ")) << "]";
  return s.str();
}

void check_pose(const Eigen::Isometry3d& pose, const char* name) {
  if (!pose.matrix().allFinite()) {
    throw std::invalid_argument(std::string("eco::EgoOctree: ") + name + " is not finite: " +
                                describe_pose(pose));
  }
  const Eigen::Matrix3d r = pose.linear();
  const double error = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (error > 1e-6 || r.determinant() < 0.0) {
    throw std::invalid_argument(std::string("eco::EgoOctree: ") + name +
                                " has a rotation that is not orthonormal (|R^T R - I| = " +
                                std::to_string(error) + "): " + describe_pose(pose));
  }
}

Motion next_motion(const Eigen::Isometry3d& pose, const Motion& last, double box_side, bool moves_origin,
                   double scan_latest) {
  Motion m;
  m.pose = pose;
  m.clock = last.clock.after(scan_latest, moves_origin);
  m.frame = last.frame + 1;
  const Eigen::Vector3d position = pose.translation();
  if (last.frame == 0) {
    m.anchor = precision_origin_for(position, Eigen::Vector3d::Zero(), true);
  } else {
    m.anchor = moves_origin ? precision_origin_for(position, last.anchor, false) : last.anchor;
    if (m.anchor != last.anchor) m.origin_shift = last.anchor - m.anchor;
    m.previous = ego_box(last.pose.translation(), m.anchor, box_side);
    m.moved = (position - last.pose.translation()).norm();
  }
  m.box = ego_box(position, m.anchor, box_side);
  return m;
}

std::pair<Cell, Lattice> root_placement(const Config& config, const Motion& motion) {
  Lattice lattice;
  lattice.max_depth = config.max_depth();
  Cell cell;
  const int depth = lattice.max_depth;
  if (config.recentring == Recentring::Quantised) {
    const int k = int(config.quantum_levels);
    const double q = config.quantum();
    lattice.unit = std::ldexp(q, k - depth);
    for (int a = 0; a < 3; ++a) {
      lattice.origin[std::size_t(a)] = -motion.anchor[a];
      const std::int64_t m = std::llround(motion.pose.translation()[a] / q);
      cell.lo[std::size_t(a)] = (m - (std::int64_t{1} << (k - 1))) * (std::int64_t{1} << (depth - k));
    }
  } else {
    lattice.unit = std::ldexp(config.box_side, -depth);
    lattice.origin = motion.box.lo;
  }
  return {cell, lattice};
}

}  // namespace eco::detail
