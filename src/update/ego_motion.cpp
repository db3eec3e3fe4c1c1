#include "update/stages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace eco::detail {
namespace {

constexpr double kOriginStep = 1024.0;   // the precision origin moves in whole steps of this [m]
constexpr double kOriginReach = 2048.0;  // ... once the sensor is farther than this from it [m]
constexpr double kClockStep = 64.0;     // the time origin moves in whole steps of this [s]
constexpr double kClockReach = 128.0;   // ... once the latest time is farther than this from it [s]

Eigen::Vector3d nearest_origin(const Eigen::Vector3d& position) {
  return (position / kOriginStep).array().round().matrix() * kOriginStep;
}

/// Takes every held point out of the tree, re-expressed against the new precision origin (rounded
/// once more to float); points the rounding takes out of the box, or past the age limit, are
/// dropped.
std::vector<StoredPoint> rebase(Tree& tree, const Motion& motion, UpdateStats& stats) {
  std::vector<StoredPoint> held;
  tree.take_points(held);
  const Eigen::Vector3d shift = *motion.origin_shift;  // exact: multiples of kOriginStep
  for (StoredPoint& s : held) s.p = rebased(s.p, shift);
  std::erase_if(held, [&](const StoredPoint& s) { return !tree.keeps(s, motion.box, stats); });
  tree.recount_density(held);  // every cell key moved with the origin
  stats.rebased = true;
  stats.rebuilt_subtrees += 1;
  return held;
}

/// The latest of the scan's times; -inf when it has none or the tree keeps none.
double latest_time(ScanView scan, const Config& config) {
  double latest = -std::numeric_limits<double>::infinity();
  if (scan.times == nullptr || !config.attributes.time) return latest;
  for (std::size_t i = 0; i < scan.count; ++i) latest = std::max(latest, scan.times[i]);
  return latest;
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

Motion next_motion(const Eigen::Isometry3d& pose, const std::optional<Motion>& last, double box_side,
                   bool moves_origin, double scan_latest) {
  Motion m;
  m.pose = pose;
  m.clock = (last ? last->clock : Clock{}).after(scan_latest, moves_origin);
  const Eigen::Vector3d position = pose.translation();
  if (!last) {
    m.anchor = precision_origin_for(position, Eigen::Vector3d::Zero(), true);
  } else {
    m.anchor = moves_origin ? precision_origin_for(position, last->anchor, false) : last->anchor;
    if (m.anchor != last->anchor) m.origin_shift = last->anchor - m.anchor;
    m.previous = ego_box(last->pose.translation(), m.anchor, box_side);
    m.moved = (position - last->pose.translation()).norm();
    m.frame = last->frame + 1;
  }
  m.box = ego_box(position, m.anchor, box_side);
  return m;
}

EgoMotion advance_ego_motion(Tree& tree, const Eigen::Isometry3d& world_T_sensor, ScanView scan,
                             UpdateStats& stats) {
  EgoMotion out{next_motion(world_T_sensor, tree.motion(), tree.config().box_side, true,
                             latest_time(scan, tree.config())),
                 {}};
  tree.set_motion(out.motion);  // the density keys of the re-expressed points need the new origin
  if (out.motion.clock.shift) tree.shift_times(*out.motion.clock.shift);  // in place, nothing moves
  if (out.motion.origin_shift) out.displaced = rebase(tree, out.motion, stats);
  return out;
}

Motion advance_ego_motion_fixed_origin(Tree& tree, const Eigen::Isometry3d& world_T_sensor, ScanView scan) {
  tree.set_motion(next_motion(world_T_sensor, tree.motion(), tree.config().box_side, /*moves_origin=*/false,
                              latest_time(scan, tree.config())));
  return *tree.motion();
}

}  // namespace eco::detail
