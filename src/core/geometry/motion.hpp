#pragma once
// Where the sensor is this frame, and what that means for the map. The update's stage 1 answers
// with it (src/update); stages 2-4 and the baselines read it instead of the tree's state, and the
// tree keeps the current frame's.

#include "core/geometry/ego_region.hpp"
#include "core/geometry/geometry.hpp"

#include <eco/config.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>

namespace eco::detail {

/// The ego box [p - L/2, p + L/2) around world position p, in the frame of precision origin
/// `anchor`.
inline Box ego_box(const Eigen::Vector3d& position, const Eigen::Vector3d& anchor, double side) {
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = (position[a] - anchor[a]) - side / 2;
    b.hi[a] = b.lo[a] + side;
  }
  return b;
}

/// The map's clock, kept while Config::attributes.time is on: stored times are float offsets
/// from `origin`, which follows the latest time in steps of 64 s (as the precision origin follows
/// the sensor), so a recent time is stored to within 2^-24 * 128 s.
struct Clock {
  double latest = -std::numeric_limits<double>::infinity();  ///< [s] the latest time taken in; -inf before any
  double origin = 0.0;           ///< [s] a multiple of 64 s
  std::optional<double> shift;   ///< old origin - new origin when the origin moved this frame (exact)

  /// The clock once a scan whose latest time is `scan_latest` (-inf: no times) is taken in; a
  /// clock that does not `move` keeps its first origin for good.
  [[nodiscard]] Clock after(double scan_latest, bool move = true) const;
  /// A stored time [s], as the caller gave it to within the clock's precision.
  [[nodiscard]] double seconds(float stored) const { return origin + double(stored); }
};

/// Throws std::invalid_argument naming `name` and the value unless `pose` is finite and rigid
/// (a rotation orthonormal to 1e-6, no reflection).
void check_pose(const Eigen::Isometry3d& pose, const char* name);
/// The pose's first three rows, for messages: "[r00, r01, r02, t0; ...]".
std::string describe_pose(const Eigen::Isometry3d& pose);

/// A frame's motion; the default one is the map's before its first frame (frame 0).
struct Motion {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< world_T_sensor
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();        ///< the precision origin, world
  Box box;                                                 ///< Box(p_t), anchor frame
  std::optional<Box> previous;  ///< Box(p_{t-1}) in the same frame; none on the first frame
  double moved = 0.0;           ///< |p_t - p_{t-1}| [m]
  std::uint32_t frame = 0;      ///< this frame's number, 1 for the first (insertion stamps)
  /// (old origin - new origin) when the precision origin moved this frame: held points move by it.
  std::optional<Eigen::Vector3d> origin_shift;
  Clock clock;                  ///< the map's clock after this frame's scan
  std::optional<EgoRegion> region;  ///< Config::region this frame, anchor frame; none for the cube
  RegionSize region_size;           ///< its lookahead growth and budget scale this frame
  /// The region is not the last frame's (held points, all in that one, need testing against it):
  /// a ball spinning in place, or a box standing still, touches no point.
  bool region_moved = false;

  /// The world point of stored (anchor-frame float) coordinates.
  [[nodiscard]] Eigen::Vector3d to_world(const std::array<float, 3>& stored) const {
    return {anchor[0] + double(stored[0]), anchor[1] + double(stored[1]), anchor[2] + double(stored[2])};
  }
};

/// Stored point `p` re-expressed against a moved precision origin (`shift` = old origin - new
/// origin, a multiple of 1024 m: exact), rounded once more to float.
inline std::array<float, 3> rebased(const std::array<float, 3>& p, const Eigen::Vector3d& shift) {
  return {float(double(p[0]) + shift[0]), float(double(p[1]) + shift[1]), float(double(p[2]) + shift[2])};
}

/// The density cap's cells (`cap`'s world grid) seen from `m`'s precision origin, its guesses
/// made in single precision around the ego box (the points a frame takes in or drops lie in it
/// or next to it). A cap that is off has no cells: a placeholder grid, whatever its cell size.
inline WorldGrid ego_grid(const Motion& m, const DensityCap& cap) {
  if (!cap.enabled()) return WorldGrid({0, 0, 0}, 1.0);
  const double size = cap.cell_size;
  std::array<double, 3> centre{};
  double reach = 0.0;
  for (int a = 0; a < 3; ++a) {
    centre[std::size_t(a)] = (m.box.lo[std::size_t(a)] + m.box.hi[std::size_t(a)]) / 2;
    reach = std::max(reach, (m.box.hi[std::size_t(a)] - m.box.lo[std::size_t(a)]) / 2);
  }
  return WorldGrid({m.anchor[0], m.anchor[1], m.anchor[2]}, size, centre, reach);
}

/// The precision origin for a sensor at `position`: `anchor` while the sensor is near it, else
/// the nearest multiple of 1024 m (always that on the first frame, `first`).
Eigen::Vector3d precision_origin_for(const Eigen::Vector3d& position, const Eigen::Vector3d& anchor,
                                     bool first);

/// The motion to `pose` after `last` (frame 0: this is the first frame), with a scan whose latest time is
/// `scan_latest` (-inf: none). `moves_origin` false keeps the first frame's precision and time
/// origins for good (a global map that never re-expresses its points).
Motion next_motion(const Eigen::Isometry3d& pose, const Motion& last, double box_side,
                   bool moves_origin = true,
                   double scan_latest = -std::numeric_limits<double>::infinity());

/// Where the root cell and the lattice lie for `motion` (stage 3 puts them there; a tree at rest
/// has them there). Quantised: the root moves in whole quanta on the world lattice. Exact: the
/// lattice's origin is the box's lower corner.
std::pair<Cell, Lattice> root_placement(const Config& config, const Motion& motion);

}  // namespace eco::detail
