#include "core/geometry/ego_region.hpp"

#include <algorithm>
#include <cmath>

namespace eco::detail {
namespace {

// [m] how far inside (or outside) a node's bounds must lie for a whole verdict: far above the
// rounding of d = p - centre and of its turn, so that a verdict on the bounds is the verdict each
// point would get
constexpr double kMargin = 1e-6;

Eigen::Vector3d as_vector(const std::array<float, 3>& p) { return {double(p[0]), double(p[1]), double(p[2])}; }

// the lookahead's speed: each frame's weight in the smoothed speed (a time constant of ~3 frames)
constexpr double kSpeedWeight = 0.3;
// the growth is set this much above what the speed asks, and kept until the speed asks for less
// than 1 / kHeadroom^2 of it
constexpr double kHeadroom = 1.25;

}  // namespace

RegionSize next_region_size(const Region& region, const RegionSize& last, double moved, double scan_time,
                            double half_side) {
  RegionSize size = last;
  size.scale = 1.0;
  size.time = scan_time;
  if (region.lookahead == 0.0) return size;
  const bool timed = std::isfinite(scan_time) && std::isfinite(last.time) && scan_time > last.time;
  const double speed = moved / (timed ? scan_time - last.time : region.frame_period);
  size.speed = last.speed + kSpeedWeight * (speed - last.speed);
  const double asked = size.speed * region.lookahead;
  if (asked > last.growth || asked * kHeadroom * kHeadroom < last.growth) {
    size.growth = std::min(asked * kHeadroom, region.max_growth(half_side));
  }
  return size;
}

std::optional<EgoRegion> EgoRegion::at(const Region& region, const Eigen::Isometry3d& world_T_sensor,
                                       const Eigen::Vector3d& anchor) {
  if (region.shape == RegionShape::Cube) return std::nullopt;
  EgoRegion r;
  r.shape_ = region.shape;
  r.centre_ = world_T_sensor.translation() - anchor;
  r.radius_ = region.radius;
  if (region.shape == RegionShape::OrientedBox) {
    const Eigen::Matrix3d turn = world_T_sensor.linear();
    if (region.turn_with == TurnWith::Full) {
      r.to_local_ = turn.transpose();
    } else {  // the heading alone: the sensor's x axis projected on the ground
      const double heading = std::atan2(turn(1, 0), turn(0, 0));
      r.to_local_ = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix().transpose();
    }
    r.lo_ = {-region.behind, -region.right, -region.down};
    r.hi_ = {region.ahead, region.left, region.up};
  }
  return r;
}

bool EgoRegion::contains(const std::array<float, 3>& p) const {
  const Eigen::Vector3d d = as_vector(p) - centre_;
  if (shape_ == RegionShape::Ball) return d.squaredNorm() <= radius_ * radius_;
  const Eigen::Vector3d l = to_local_ * d;
  return (l.array() >= lo_.array()).all() && (l.array() <= hi_.array()).all();
}

double EgoRegion::gauge(const std::array<float, 3>& p) const {
  const Eigen::Vector3d d = as_vector(p) - centre_;
  if (shape_ == RegionShape::Ball) return d.norm() / radius_;
  const Eigen::Vector3d l = to_local_ * d;
  double g = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (l[a] > 0.0) g = std::max(g, l[a] / hi_[a]);  // an extent of 0: infinite, held at no scale
    if (l[a] < 0.0) g = std::max(g, l[a] / lo_[a]);
  }
  return g;
}

std::optional<EgoRegion> EgoRegion::at(const Region& configured, const RegionSize& size,
                                       const Eigen::Isometry3d& world_T_sensor, const Eigen::Vector3d& anchor) {
  if (configured.shape == RegionShape::Cube) return std::nullopt;
  if (size.scale == 0.0) return nothing();
  return at(configured.sized(size.growth, size.scale), world_T_sensor, anchor);
}

EgoRegion EgoRegion::oriented_box(const Eigen::Isometry3d& world_T_box, const Eigen::Vector3d& lo,
                                  const Eigen::Vector3d& hi, const Eigen::Vector3d& anchor) {
  EgoRegion r;
  r.shape_ = RegionShape::OrientedBox;
  r.centre_ = world_T_box.translation() - anchor;
  r.to_local_ = world_T_box.linear().transpose();
  r.lo_ = lo;
  r.hi_ = hi;
  return r;
}

EgoRegion EgoRegion::nothing() {
  EgoRegion r;
  r.shape_ = RegionShape::OrientedBox;
  r.lo_ = Eigen::Vector3d::Constant(1.0);
  r.hi_ = Eigen::Vector3d::Constant(-1.0);
  return r;
}

bool EgoRegion::contains_all(const Aabb& b) const {
  if (b.empty()) return true;
  // the region is convex: it holds the box when it holds the box's eight corners
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d c(corner & 1 ? b.hi[0] : b.lo[0], corner & 2 ? b.hi[1] : b.lo[1], corner & 4 ? b.hi[2] : b.lo[2]);
    const Eigen::Vector3d d = c - centre_;
    if (shape_ == RegionShape::Ball) {
      if (!(d.norm() <= radius_ - kMargin)) return false;
      continue;
    }
    const Eigen::Vector3d l = to_local_ * d;
    if (!((l.array() >= lo_.array() + kMargin).all() && (l.array() <= hi_.array() - kMargin).all())) return false;
  }
  return true;
}

bool EgoRegion::misses(const Aabb& b) const {
  if (b.empty()) return true;
  if (shape_ == RegionShape::Ball) {
    const std::array<double, 3> q{centre_[0], centre_[1], centre_[2]};
    return std::sqrt(b.sq_dist(q)) > radius_ + kMargin;
  }
  // separated along one of the region's axes: the bounds turned into them, as a box about their centre
  const Eigen::Vector3d lo = as_vector(b.lo), hi = as_vector(b.hi);
  const Eigen::Vector3d middle = to_local_ * ((lo + hi) / 2 - centre_);
  const Eigen::Vector3d half = to_local_.cwiseAbs() * ((hi - lo) / 2);
  return ((middle + half).array() < lo_.array() - kMargin).any() || ((middle - half).array() > hi_.array() + kMargin).any();
}

}  // namespace eco::detail
