#pragma once
// The four stages of one update, in the order update.cpp runs them (paper §IV, DESIGN.md §2).

#include "core/tree.hpp"

#include <eco/types.hpp>

#include <Eigen/Geometry>

namespace eco::detail {

/// 1. Ego-motion: take the new pose, move the precision origin if the sensor went far from it,
///    and place the new ego box. AABBs stay in the world; only the query box moves: O(1).
void advance_ego_motion(Tree& tree, const Eigen::Isometry3d& world_T_sensor);

/// 2. Shift-out (R_out): drop subtrees whose bounds left the box, filter the leaves that straddle
///    it, and drop points past the age limit. Subtrees wholly inside are not visited.
void prune_shift_out(Tree& tree);

/// 3. Overlap refinement (R_over): re-centre the root on the sensor. Quantised: re-link the
///    lattice-fixed depth-k subtrees under new top levels. Exact: rebuild the subtrees whose bounds
///    no longer fit their moved octant. Ends by re-inserting any points the stages set aside.
void refine_overlap(Tree& tree);

/// 4. Shift-in (R_in): transform the scan points the insert policy admits into the world, pass
///    them through the density cap (in scan order) and insert them as one batch, partitioned
///    top-down from the start-table depth rather than the root.
void insert_shift_in(Tree& tree, ScanView scan);

/// The scan points the insert policy admits this frame (after advance_ego_motion).
struct Admission;
Admission admission(const Tree& tree);

/// Throws std::invalid_argument naming the value unless `pose` is finite and rigid, `scan` is
/// readable and the density cap's grid can index the points around `pose` (Config's). `name`
/// names the pose argument in the message.
void check_update_arguments(const Eigen::Isometry3d& pose, const char* name, const ScanView& scan,
                            const Config& config);

/// The precision origin for a sensor at `position`: `anchor` while the sensor is near it, else
/// the nearest multiple of 1024 m (always that on the first frame, `first`).
Eigen::Vector3d precision_origin_for(const Eigen::Vector3d& position, const Eigen::Vector3d& anchor,
                                     bool first);

}  // namespace eco::detail
