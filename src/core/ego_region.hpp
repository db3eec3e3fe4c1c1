#pragma once
// Config::region at one frame, in the precision origin's frame the points are stored in: which
// points it holds (exactly, point by point) and, for the tree's walks, which node bounds it holds
// whole or misses whole (conservatively: a node near its surface is looked into).

#include "core/geometry.hpp"

#include <eco/config.hpp>

#include <Eigen/Geometry>

#include <array>
#include <optional>

namespace eco::detail {

class EgoRegion {
 public:
  /// The region at `world_T_sensor` seen from precision origin `anchor`; none for the cube (the
  /// ego box alone decides).
  [[nodiscard]] static std::optional<EgoRegion> at(const Region& region, const Eigen::Isometry3d& world_T_sensor,
                                                   const Eigen::Vector3d& anchor);

  /// Whether the stored point `p` lies in the region: d = p - centre in double, turned by R^T,
  /// tested against the extents (closed).
  [[nodiscard]] bool contains(const std::array<float, 3>& p) const;
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
