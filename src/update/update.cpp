// The update recipe (EgoOctree::update), stage by stage (paper §IV).

#include "update/stages.hpp"

#include "core/geometry/update_arguments.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace eco {
namespace {

RegionExtents extents_of(const Region& configured, const detail::RegionSize& size) {
  if (configured.shape == RegionShape::Cube) return {};
  const Region r = configured.sized(size.growth, size.scale);
  return {r.radius, r.ahead, r.behind, r.left, r.right, r.up, r.down, size.scale, size.speed};
}

}  // namespace

UpdateStats detail::begin_update(const Config& config, const Eigen::Isometry3d& world_T_sensor, ScanView scan) {
  check_update_arguments(world_T_sensor, "world_T_sensor", scan, config);
  UpdateStats stats;
  stats.scan_points = scan.count;
  return stats;
}

UpdateStats detail::run_update(Tree& tree, ClearingState* clearing, DensityCells* density,
                               const Eigen::Isometry3d& world_T_sensor, ScanView scan) {
  UpdateStats stats = begin_update(tree.config(), world_T_sensor, scan);
  if (clearing) release_arrivals(tree, density, *clearing, stats);                           // 0. held one update
  auto [motion, displaced] = advance_ego_motion(tree, density, world_T_sensor, scan, stats);  // 1. pose, box, clock
  prune_shift_out(tree, density, motion, stats);                                             // 2. R_out
  if (clearing) clear_free_space(tree, density, *clearing, motion, scan, displaced, stats);  //    seen through
  displaced = refine_overlap(tree, motion, std::move(displaced), stats);                     // 3. R_over
  insert_shift_in(tree, density, motion, scan, std::move(displaced), clearing, stats);       // 4. R_in
  keep_to_budget(tree, density, stats);                                                      // 5. budget
  tree.give_back_memory();                                                                   // 6. memory
  stats.region = extents_of(tree.config().region, tree.motion().region_size);
  return stats;
}

}  // namespace eco
