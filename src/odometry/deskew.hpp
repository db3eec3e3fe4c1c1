#pragma once
// A scan corrected for the sensor's motion during its sweep (the odometry's deskewing): constant
// velocity over the sweep, each point moved into the sensor's frame in the sweep's middle.

#include <Eigen/Geometry>

#include <span>
#include <vector>

namespace eco::odometry {

/// The part `s` of `motion` a sensor moving at constant velocity makes: slerp and lerp from the
/// identity.
[[nodiscard]] Eigen::Isometry3d part_of(const Eigen::Isometry3d& motion, double s);

/// Each point moved into the sensor's frame at the middle of the sweep its `times` span (from 0,
/// the stamp; one time a point), the sensor taken to move through `motion` over the sweep: a
/// point measured a part s into it was seen from part_of(motion, s). About the middle, as
/// KISS-ICP does: a scan corrected by a motion somewhat wrong is then smeared evenly about its
/// pose, not ahead of it, so the error does not feed the next frame's motion.
void deskew(std::vector<Eigen::Vector3f>& points, std::span<const double> times, const Eigen::Isometry3d& motion);

}  // namespace eco::odometry
