#pragma once
// The four stages of one update, in the order update.cpp runs them (paper §IV), with free-space
// clearing's (src/clearing/) between them.
// Stage 1 answers with the frame's Motion, which the others read; points a stage takes out of the
// tree to put back (a precision-origin move, a rebuilt subtree) are handed on, not parked. The
// density cap's counts (`density`, null while the cap is off) are handed to every stage that
// takes points in or out, as clearing's state is to clearing's.

#include "clearing/clearing.hpp"
#include "core/density/density_cells.hpp"
#include "core/geometry/motion.hpp"
#include "core/tree/tree.hpp"

#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <vector>

namespace eco::detail {

/// Every stage counts what it does in the frame's `stats`.
///
/// 1. Ego-motion: the new pose, precision origin and ego box (AABBs stay in the world; only the
///    query box moves), and the clock after `scan`'s times. When the precision origin moved (once
///    per ~2 km), every held point is re-expressed and handed back in `displaced`; when the time
///    origin did (once per ~64 s, with attributes.time), the held times are re-expressed in place.
///    Enters the motion into the tree and `density` (whose counts are made anew after an origin move).
struct EgoMotion {
  Motion motion;
  std::vector<StoredPoint> displaced;
};
EgoMotion advance_ego_motion(Tree& tree, DensityCells* density, const Eigen::Isometry3d& world_T_sensor, ScanView scan,
                             UpdateStats& stats);
/// The same for a map that keeps its first precision and time origins for good (`moves_origin`
/// false in next_motion): nothing is ever displaced.
Motion advance_ego_motion_fixed_origin(Tree& tree, DensityCells* density, const Eigen::Isometry3d& world_T_sensor,
                                       ScanView scan);

/// 2. Shift-out (R_out): drop subtrees whose bounds left motion.box (or motion.region), filter the
///    leaves that straddle their surface, and drop points past the age limit. Subtrees wholly
///    inside are not visited.
void prune_shift_out(Tree& tree, DensityCells* density, const Motion& motion, UpdateStats& stats);
/// Whether point `s` leaves the map this frame: outside motion.box or motion.region, or past the
/// age limit; one that does is counted in `stats`, as pruned when outside, else as aged out.
bool leaves(const Tree& tree, const StoredPoint& s, const Motion& motion, UpdateStats& stats);

/// 2b. Free-space clearing (Config::clearing, off by default; src/clearing/clearing.hpp): the held
///    points the scan sees through leave, from the tree and from `displaced`.

/// 3. Overlap refinement (R_over): re-centre the root on the sensor. Quantised: re-link the
///    lattice-fixed depth-k subtrees under new top levels. Exact: rebuild the subtrees whose bounds
///    no longer fit their moved octant. Returns `displaced` with the points of the subtrees it
///    took apart, for stage 4 to put back.
std::vector<StoredPoint> refine_overlap(Tree& tree, const Motion& motion, std::vector<StoredPoint> displaced,
                                        UpdateStats& stats);

/// 4. Shift-in (R_in): put `displaced` back, then transform the scan points the insert policy
///    admits, pass them through the density cap (in scan order) and insert them in batches,
///    partitioned top-down from the movement-aware start depth rather than the root. With
///    `clearing` (null while it is off), the new points the last update's scan saw through are
///    noted in it to leave at the next update (stage 0).
void insert_shift_in(Tree& tree, DensityCells* density, const Motion& motion, ScanView scan,
                     std::vector<StoredPoint> displaced, ClearingState* clearing, UpdateStats& stats);
/// Stage 4's parts, for the baselines: where insertion starts (the movement-aware start depth
/// for `motion`), putting `points` back (left empty, capacity kept), and taking in the scan.
void place_start_table(Tree& tree, const Motion& motion);
void reinsert(Tree& tree, std::vector<StoredPoint>& points, UpdateStats& stats);
void insert_scan(Tree& tree, DensityCells* density, const Motion& motion, ScanView scan, ClearingState* clearing,
                 UpdateStats& stats);

/// 5. The budget (Config::region.max_points): when the tree holds more, the region shrinks about
///    the sensor to the largest scale in steps of 1 % at which the held points fit (none: it
///    holds nothing), the points outside leave (counted as over_budget), and the tree's motion
///    ends the frame with the narrowed region.
void keep_to_budget(Tree& tree, DensityCells* density, UpdateStats& stats);

/// One update (EgoOctree::update): begin_update(), then the four stages (with free-space
/// clearing's, reading and writing `clearing`, when it is given), the budget, then 6., the
/// memory a map that shrank holds free given back (Tree::give_back_memory). Returns the frame's
/// statistics, with the region the frame ends with.
UpdateStats run_update(Tree& tree, ClearingState* clearing, DensityCells* density, const Eigen::Isometry3d& world_T_sensor,
                       ScanView scan);
/// Every update's preamble (ECO's and the baselines'): checks the arguments against the
/// configuration — throwing std::invalid_argument, the tree unchanged, when they are refused —
/// and returns the frame's statistics, counting the scan.
UpdateStats begin_update(const Config& config, const Eigen::Isometry3d& world_T_sensor, ScanView scan);

}  // namespace eco::detail
