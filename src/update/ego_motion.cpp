#include "update/stages.hpp"

#include <cmath>

namespace eco::detail {
namespace {

constexpr double kOriginStep = 1024.0;   // the precision origin moves in whole steps of this [m]
constexpr double kOriginReach = 2048.0;  // ... once the sensor is farther than this from it [m]

Eigen::Vector3d nearest_origin(const Eigen::Vector3d& position) {
  return (position / kOriginStep).array().round().matrix() * kOriginStep;
}

/// Moves the precision origin: every held point is re-expressed against the new origin (rounded
/// once more to float) and set aside for re-insertion; points the rounding takes out of the box
/// are pruned. Happens once per ~2 km travelled.
void rebase(Tree& tree, const Eigen::Vector3d& new_anchor) {
  const Eigen::Vector3d shift = tree.anchor - new_anchor;  // exact: multiples of kOriginStep
  tree.anchor = new_anchor;
  tree.box = tree.box_around(tree.pose.translation());
  std::vector<StoredPoint> held;
  tree.dissolve(tree.root, &held);
  tree.root = kNone;
  tree.density.clear();  // cells are counted anew from the re-rounded points
  for (StoredPoint s : held) {
    for (int a = 0; a < 3; ++a) s.p[a] = float(double(s.p[a]) + shift[a]);
    if (!tree.keeps(s)) continue;
    tree.moving.push_back(s);
    if (tree.cfg.density_cap.enabled()) tree.density.add(tree.density_key(s.p));
  }
  tree.last.rebased = true;
  tree.last.rebuilt_subtrees += 1;
}

}  // namespace

void advance_ego_motion(Tree& tree, const Eigen::Isometry3d& world_T_sensor) {
  tree.has_previous = tree.frame > 0;
  tree.previous_position = tree.pose.translation();
  tree.pose = world_T_sensor;
  ++tree.frame;
  const Eigen::Vector3d position = world_T_sensor.translation();
  const Eigen::Vector3d anchor = precision_origin_for(position, tree.anchor, !tree.has_previous);
  if (!tree.has_previous) {
    tree.anchor = anchor;
  } else if (anchor != tree.anchor) {
    rebase(tree, anchor);
  }
  tree.box = tree.box_around(position);
}

Eigen::Vector3d precision_origin_for(const Eigen::Vector3d& position, const Eigen::Vector3d& anchor,
                                     bool first) {
  if (first || (position - anchor).cwiseAbs().maxCoeff() > kOriginReach) return nearest_origin(position);
  return anchor;
}

}  // namespace eco::detail
