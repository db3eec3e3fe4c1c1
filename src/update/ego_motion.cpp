#include "update/stages.hpp"

#include <cmath>

namespace eco::detail {
namespace {

constexpr double kOriginStep = 1024.0;   // the precision origin moves in whole steps of this [m]
constexpr double kOriginReach = 2048.0;  // ... once the sensor is farther than this from it [m]

Eigen::Vector3d nearest_origin(const Eigen::Vector3d& position) {
  return (position / kOriginStep).array().round().matrix() * kOriginStep;
}

/// Takes every held point out of the tree, re-expressed against the new origin (rounded once
/// more to float); points the rounding takes out of the box are pruned.
std::vector<StoredPoint> rebase(Tree& tree, const Motion& motion, UpdateStats& stats) {
  const Eigen::Vector3d shift = *motion.origin_shift;  // exact: multiples of kOriginStep
  std::vector<StoredPoint> held;
  tree.take_points(held);
  for (StoredPoint& s : held) s.p = rebased(s.p, shift);
  std::erase_if(held, [&](const StoredPoint& s) { return !tree.keeps(s, motion.box, stats); });
  tree.recount_density(held);  // every cell key moved with the origin
  stats.rebased = true;
  stats.rebuilt_subtrees += 1;
  return held;
}

}  // namespace

Eigen::Vector3d precision_origin_for(const Eigen::Vector3d& position, const Eigen::Vector3d& anchor,
                                     bool first) {
  if (first || (position - anchor).cwiseAbs().maxCoeff() > kOriginReach) return nearest_origin(position);
  return anchor;
}

Motion next_motion(const Eigen::Isometry3d& pose, const std::optional<Motion>& last, double box_side,
                   bool moves_origin) {
  Motion m;
  m.pose = pose;
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

EgoMotion advance_ego_motion(Tree& tree, const Eigen::Isometry3d& world_T_sensor, UpdateStats& stats) {
  EgoMotion out{next_motion(world_T_sensor, tree.motion(), tree.config().box_side), {}};
  tree.set_motion(out.motion);  // the density keys of the re-expressed points need the new origin
  if (out.motion.origin_shift) out.displaced = rebase(tree, out.motion, stats);
  return out;
}

Motion advance_ego_motion_fixed_origin(Tree& tree, const Eigen::Isometry3d& world_T_sensor) {
  tree.set_motion(next_motion(world_T_sensor, tree.motion(), tree.config().box_side, /*moves_origin=*/false));
  return *tree.motion();
}

}  // namespace eco::detail
