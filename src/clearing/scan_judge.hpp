#pragma once
// A scan as free-space clearing's judge of held points (the rule in include/eco/config.hpp): where
// it was taken from, and its range image. Shared by the clearing stage (src/clearing/free_space.cpp)
// and the arrivals' check at insertion (src/clearing/arrivals.cpp).

#include "core/geometry/geometry.hpp"
#include "clearing/clearing_rule.hpp"
#include "clearing/pixel_lookup.hpp"
#include "clearing/range_image.hpp"
#include "clearing/sensor_frame.hpp"

#include <eco/config.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace eco::detail {

/// Where the sensor looked from: held points in its frame, and which subtrees lie wholly beyond
/// its range or outside its vertical field of view (none of their points has a pixel).
class Sight {
 public:
  /// The sensor at `world_T_sensor`, for points stored against the precision origin `anchor`.
  Sight(const Eigen::Isometry3d& world_T_sensor, const Eigen::Vector3d& anchor, const SensorModel& sensor)
      : sensor_from_anchor_(anchor - world_T_sensor.translation()),
        pose_(world_T_sensor.linear().transpose(), sensor_from_anchor_),
        up_(world_T_sensor.linear().col(2)),  // sensor_R_world's third row
        sin_fov_min_(std::sin(sensor.vertical_fov_min * kRadiansPerDegree)),
        sin_fov_max_(std::sin(sensor.vertical_fov_max * kRadiansPerDegree)),
        max_range_(sensor.max_range) {}

  /// The sensor's frame: held points' stored coordinates into it.
  [[nodiscard]] const SensorPose& pose() const { return pose_; }
  /// Whether some point of `box` (anchor frame) may lie in the sensor's image.
  [[nodiscard]] bool may_see(const Aabb& box) const {
    const Eigen::Vector3d sensor = -sensor_from_anchor_;  // in the anchor frame
    const double squared_nearest = box.sq_dist({sensor[0], sensor[1], sensor[2]});
    // widened against rounding: a point's range is computed after the rotation
    const double reach = max_range_ * (1.0 + 1e-9) + 1e-9;
    return squared_nearest <= reach * reach && !outside_field_of_view(box, squared_nearest);
  }

 private:
  static constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

  /// Whether every point of `box` (anchor frame; the square of its distance from the sensor
  /// `squared_nearest`) lies below or above the vertical field of view: sin(elevation) = (p -
  /// sensor) . up / |p - sensor|, bounded over the box, with a slack far above the rounding of the
  /// pixel formulas.
  [[nodiscard]] bool outside_field_of_view(const Aabb& box, double squared_nearest) const {
    const Eigen::Vector3d lo(box.lo[0], box.lo[1], box.lo[2]), hi(box.hi[0], box.hi[1], box.hi[2]);
    const Eigen::Vector3d centre = 0.5 * (lo + hi) + sensor_from_anchor_;  // from the sensor, world axes
    const Eigen::Vector3d half = 0.5 * (hi - lo);
    const double height = up_.dot(centre), spread = up_.cwiseAbs().dot(half);  // (p - sensor) . up
    const double farthest = (centre.cwiseAbs() + half).norm();
    const double slack = 1e-6 * farthest;
    // the box's distance is needed for a field of view wholly above or below the horizon only
    if (height + spread + slack < sin_fov_min_ * (sin_fov_min_ <= 0.0 ? farthest : std::sqrt(squared_nearest))) {
      return true;
    }
    return height - spread - slack > sin_fov_max_ * (sin_fov_max_ >= 0.0 ? farthest : std::sqrt(squared_nearest));
  }

  Eigen::Vector3d sensor_from_anchor_;  // anchor - sensor position: stored point + this = sensor-relative, world axes
  SensorPose pose_;
  Eigen::Vector3d up_;                  // the sensor's z axis, world axes
  double sin_fov_min_ = 0.0, sin_fov_max_ = 0.0;
  double max_range_ = 0.0;
};

/// The scan's verdict on held points: seen through or not.
class SeenThrough {
  static_assert(PixelLookup::kGroup <= 32, "a group's lanes are the bits of a 32-bit mask");
 public:
  SeenThrough(RangeImage image, double margin) : image_(image), margin_(margin) {}
  /// For a held point at `pixel` (or kOutside), |v|^2 = `squared_range` from the sensor: a pixel
  /// with no return around it (kNoReturn) is not evidence of free space.
  [[nodiscard]] bool operator()(std::uint32_t pixel, double squared_range) const {
    if (pixel == PixelLookup::kOutside) return false;
    const double nearest = image_.nearest_around(pixel);
    return nearest != RangeImage::kNoReturn && lies_beyond(nearest, squared_range, margin_);
  }
  /// As a PixelStream's screen: of a group's lanes [0, `size`) from tier 1 (`pixels`, squared ranges
  /// `squared`), as bits (lane i on bit i), those tier 1 left undecided and those this verdict may
  /// call seen through; it calls no other lane seen through. In vector code (scan_judge.cpp).
  [[nodiscard]] std::uint32_t screen(const std::array<std::uint32_t, PixelLookup::kGroup>& pixels,
                                     const std::array<double, PixelLookup::kGroup>& squared, std::size_t size) const;

 private:
  /// screen's lanes, every one of them (those from `size` up flagged 0), over the image's
  /// `pixel_count` pixels: a lane whose pixel is not in the image reads pixel 0, and is flagged
  /// only where tier 1 left it undecided. Static, its inputs handed in, for the compiler to
  /// vectorise.
  static std::uint32_t screen_group(const double* image, std::uint32_t pixel_count, double margin,
                                    const std::array<std::uint32_t, PixelLookup::kGroup>& pixels,
                                    const std::array<double, PixelLookup::kGroup>& squared, std::size_t size);

  RangeImage image_;  // a view of storage the tree keeps
  double margin_ = 0.0;
};

/// A scan that judges held points: where it was taken from, and its image.
struct Judge {
  Sight sight;
  SeenThrough seen_through;
  /// Whether it sees through the point stored at `p`.
  [[nodiscard]] bool sees_through(const PixelLookup& pixels, const std::array<float, 3>& p) const {
    const Eigen::Vector3d v = sight.pose().apply(p);
    double range = 0.0;
    return seen_through(pixels.pixel_of(v, range), v.squaredNorm());
  }
};

/// A judge's end of a pixel stream: stored points, rotated into the sensor's frame a group at a time
/// (in vector code) and handed to `stream` (a PixelStream), which tags them in the order added.
template <class Stream>
class Sink {
 public:
  Sink(const SensorPose& pose, Stream& stream) : pose_(pose), stream_(stream) {}
  /// One point (the arrivals' batches, which hold whole points, not columns).
  void add(float x, float y, float z) { add_columns(&x, &y, &z, 1); }
  /// Points (x[i], y[i], z[i]) for i in [0, n): a leaf's columns, a group's room at a time (no test
  /// per point of whether the group is full).
  void add_columns(const float* x, const float* y, const float* z, std::uint32_t n) {
    while (n > 0) {
      const std::size_t k = stored_.size;
      const auto take = std::uint32_t(std::min<std::size_t>(n, PixelLookup::kGroup - k));
      for (std::uint32_t i = 0; i < take; ++i) {  // a plain loop: a call to memmove a column cost more
        stored_.x[k + i] = x[i], stored_.y[k + i] = y[i], stored_.z[k + i] = z[i];
      }
      stored_.size += take;
      if (stored_.size == PixelLookup::kGroup) send();
      x += take, y += take, z += take;
      n -= take;
    }
  }
  /// Sends what is left, then the stream's own leftovers.
  void flush() {
    send();
    stream_.flush();
  }

 private:
  void send() {
    to_sensor_frame(pose_, stored_, group_);
    stream_.push_group(group_);
    stored_.size = 0;
  }
  const SensorPose& pose_;
  Stream& stream_;
  StoredGroup stored_;
  PixelLookup::Group group_;
};

}  // namespace eco::detail
