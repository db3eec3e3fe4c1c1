#pragma once
// Config::region at one frame, in the precision origin's frame the points are stored in: which
// points it holds (exactly, point by point) and, for the tree's walks, which node bounds it holds
// whole or misses whole (conservatively: a node near its surface is looked into).

#include "core/geometry/geometry.hpp"

#include <eco/config.hpp>

#include <Eigen/Geometry>

#include <array>
#include <limits>
#include <optional>

namespace eco::detail {

/// Config::region's size after a frame: the lookahead's growth from the smoothed speed (with
/// hysteresis) and the budget's scale.
struct RegionSize {
  double speed = 0.0;   ///< [m/s] smoothed over the last frames
  double growth = 0.0;  ///< [m] added ahead (a ball: all round) by the lookahead
  double scale = 1.0;   ///< the budget's (1: the whole region)
  double time = std::numeric_limits<double>::quiet_NaN();  ///< [s] the scan's latest point time; NaN: none

  [[nodiscard]] bool operator==(const RegionSize&) const = default;
};

/// The size of `region` for a frame that `moved` [m] since the `last` one, whose scan's latest
/// point time is `scan_time` (NaN: none), in a cube of half side `half_side`: the speed smoothed,
/// the growth following it with hysteresis, the scale back to 1 (the budget narrows it after).
[[nodiscard]] RegionSize next_region_size(const Region& region, const RegionSize& last, double moved, double scan_time,
                                          double half_side);

class EgoRegion {
 public:
  /// The region at `world_T_sensor` seen from precision origin `anchor`; none for the cube (the
  /// ego box alone decides).
  [[nodiscard]] static std::optional<EgoRegion> at(const Region& region, const Eigen::Isometry3d& world_T_sensor,
                                                   const Eigen::Vector3d& anchor);

  /// Whether the stored point `p` lies in the region: d = p - centre in double, turned by R^T,
  /// tested against the extents (closed).
  [[nodiscard]] bool contains(const std::array<float, 3>& p) const;
  /// The least scale about the sensor at which the region holds `p` (the ball's |d| / radius, the
  /// box's largest ratio of a coordinate to its extent), rounded as computed: a guess that
  /// contains() at the scaled extents confirms.
  [[nodiscard]] double gauge(const std::array<float, 3>& p) const;
  /// Config::region `configured` at `size` (grown, then scaled; a scale of 0 holds nothing), at
  /// `world_T_sensor` from `anchor`; none for the cube.
  [[nodiscard]] static std::optional<EgoRegion> at(const Region& configured, const RegionSize& size,
                                                   const Eigen::Isometry3d& world_T_sensor, const Eigen::Vector3d& anchor);
  /// A region that holds nothing (a budget below what 1 % of the region holds).
  [[nodiscard]] static EgoRegion nothing();
  /// The closed box [lo, hi] in the axes `world_T_box` places (an oriented box query's), seen
  /// from `anchor`.
  [[nodiscard]] static EgoRegion oriented_box(const Eigen::Isometry3d& world_T_box, const Eigen::Vector3d& lo,
                                              const Eigen::Vector3d& hi, const Eigen::Vector3d& anchor);
  /// Every point of `b` inside, with a margin (a point near the surface is tested on its own).
  [[nodiscard]] bool contains_all(const Aabb& b) const;
  /// No point of `b` inside, with the same margin.
  [[nodiscard]] bool misses(const Aabb& b) const;
  /// The same region, to the bit: a map that held this one's points holds no point outside it.
  [[nodiscard]] bool operator==(const EgoRegion& o) const {
    return shape_ == o.shape_ && centre_ == o.centre_ && to_local_ == o.to_local_ && radius_ == o.radius_ && lo_ == o.lo_ &&
           hi_ == o.hi_;
  }

 private:
  [[nodiscard]] Eigen::Vector3d local(const Eigen::Vector3d& stored) const { return to_local_ * (stored - centre_); }

  RegionShape shape_ = RegionShape::Ball;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();       // the sensor, anchor frame
  Eigen::Matrix3d to_local_ = Eigen::Matrix3d::Identity();  // R^T: anchor axes into the region's
  double radius_ = 0.0;
  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero(), hi_ = Eigen::Vector3d::Zero();  // the box's extents, local
};

}  // namespace eco::detail
