// Stage 1: the frame's motion (core/geometry/motion.hpp) entered into the tree, and what an origin move
// re-expresses.

#include "update/stages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace eco::detail {
namespace {

/// Takes every held point out of the tree, re-expressed against the new precision origin (rounded
/// once more to float); points the rounding takes out of the box, or past the age limit, are
/// dropped. The density counts are made anew from those kept: every cell key moved with the origin.
std::vector<StoredPoint> rebase(Tree& tree, DensityCells* density, const Motion& motion, UpdateStats& stats) {
  std::vector<StoredPoint> held;
  tree.take_points(held);
  const Eigen::Vector3d shift = *motion.origin_shift;  // exact: multiples of kOriginStep
  for (StoredPoint& s : held) s.p = rebased(s.p, shift);
  std::erase_if(held, [&](const StoredPoint& s) { return leaves(tree, s, motion, stats); });
  if (density) density->recount([&](auto&& add) {
    for (const StoredPoint& s : held) add(s.p);
  });
  stats.rebased = true;
  stats.rebuilt_subtrees += 1;
  return held;
}

/// The latest finite time of `scan`'s points, kept or not; NaN when it has none.
double scan_time(ScanView scan) {
  double latest = std::numeric_limits<double>::quiet_NaN();
  if (scan.times == nullptr) return latest;
  for (std::size_t i = 0; i < scan.count; ++i) {
    if (std::isfinite(scan.times[i]) && !(scan.times[i] <= latest)) latest = scan.times[i];
  }
  return latest;
}

/// Config::region at `motion`'s pose, sized for its speed (the budget narrows it after the scan
/// is in), and whether it moved since the `last` frame's.
void place_region(Motion& motion, const Config& config, const Motion& last, ScanView scan) {
  // the scan's time only for the lookahead's speed: a pass over the scan's times the others skip
  const double time = config.region.lookahead > 0.0 ? scan_time(scan) : std::numeric_limits<double>::quiet_NaN();
  motion.region_size = next_region_size(config.region, last.region_size, motion.moved, time, config.box_side / 2);
  motion.region = EgoRegion::at(config.region, motion.region_size, motion.pose, motion.anchor);
  motion.region_moved = motion.region && !(last.region && *last.region == *motion.region);
}

/// The latest of the scan's times; -inf when it has none or the tree keeps none.
double latest_time(ScanView scan, const Config& config) {
  double latest = -std::numeric_limits<double>::infinity();
  if (scan.times == nullptr || !config.attributes.time) return latest;
  for (std::size_t i = 0; i < scan.count; ++i) latest = std::max(latest, scan.times[i]);
  return latest;
}

}  // namespace

EgoMotion advance_ego_motion(Tree& tree, DensityCells* density, const Eigen::Isometry3d& world_T_sensor, ScanView scan,
                             UpdateStats& stats) {
  EgoMotion out{next_motion(world_T_sensor, tree.motion(), tree.config().box_side, true,
                             latest_time(scan, tree.config())),
                 {}};
  place_region(out.motion, tree.config(), tree.motion(), scan);
  tree.set_motion(out.motion);
  if (density) density->enter(out.motion);  // the keys of the re-expressed points need the new origin
  if (out.motion.origin_shift) out.displaced = rebase(tree, density, out.motion, stats);
  return out;
}

Motion advance_ego_motion_fixed_origin(Tree& tree, DensityCells* density, const Eigen::Isometry3d& world_T_sensor,
                                       ScanView scan) {
  Motion motion = next_motion(world_T_sensor, tree.motion(), tree.config().box_side, /*moves_origin=*/false,
                              latest_time(scan, tree.config()));
  place_region(motion, tree.config(), tree.motion(), scan);
  tree.set_motion(motion);
  if (density) density->enter(motion);
  return tree.motion();
}

}  // namespace eco::detail
