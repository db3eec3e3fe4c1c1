// Free-space clearing (Config::clearing): the held points the new scan sees through leave the
// tree. The scan's returns are binned into the sensor's range image once; each held point is then
// projected into it and cleared when the nearest return around its pixel lies beyond it by more
// than the margin (the rule in include/eco/config.hpp).

#include "update/range_image.hpp"
#include "update/stages.hpp"
#include "update/subtree_filter.hpp"

namespace eco::detail {
namespace {

constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

/// Clearing's judgement: subtrees wholly beyond the sensor's range or outside its vertical field of
/// view stay whole; the others are looked into point by point.
class Clearer {
 public:
  Clearer(Tree& tree, const Motion& motion, ScanView scan, UpdateStats& stats)
      : t_(tree),
        pixels_(tree.config().sensor),
        image_(pixels_, scan, tree.range_image_buffer()),
        sensor_R_world_(motion.pose.linear().transpose()),
        sensor_from_anchor_(motion.anchor - motion.pose.translation()),
        up_(sensor_R_world_.row(2).transpose()),
        sin_fov_min_(std::sin(tree.config().sensor.vertical_fov_min * kRadiansPerDegree)),
        sin_fov_max_(std::sin(tree.config().sensor.vertical_fov_max * kRadiansPerDegree)),
        margin_(tree.config().clearing.margin),
        max_range_(tree.config().sensor.max_range),
        stats_(stats) {}

  [[nodiscard]] Verdict judge(const Node& n) const {
    const Eigen::Vector3d sensor = -sensor_from_anchor_;  // in the anchor frame
    const double nearest = std::sqrt(n.bounds.sq_dist({sensor[0], sensor[1], sensor[2]}));
    // widened against rounding: a point's range is computed after the rotation
    const bool beyond_range = nearest > max_range_ * (1.0 + 1e-9) + 1e-9;
    return beyond_range || outside_field_of_view(n.bounds, nearest) ? Verdict::KeepAll : Verdict::LookInside;
  }
  /// Whether every point of `box` (anchor frame; `nearest` [m] from the sensor) lies below or
  /// above the vertical field of view: sin(elevation) = (p - sensor) . up / |p - sensor|, bounded
  /// over the box, with a slack far above the rounding of the pixel formulas.
  [[nodiscard]] bool outside_field_of_view(const Aabb& box, double nearest) const {
    const Eigen::Vector3d lo(box.lo[0], box.lo[1], box.lo[2]), hi(box.hi[0], box.hi[1], box.hi[2]);
    const Eigen::Vector3d centre = 0.5 * (lo + hi) + sensor_from_anchor_;  // from the sensor, world axes
    const Eigen::Vector3d half = 0.5 * (hi - lo);
    const double height = up_.dot(centre), spread = up_.cwiseAbs().dot(half);  // (p - sensor) . up
    const double farthest = (centre.cwiseAbs() + half).norm();
    const double slack = 1e-6 * farthest;
    if (height + spread + slack < sin_fov_min_ * (sin_fov_min_ <= 0.0 ? farthest : nearest)) return true;
    return height - spread - slack > sin_fov_max_ * (sin_fov_max_ >= 0.0 ? farthest : nearest);
  }
  void drop(std::uint32_t) {}  // never judged DropAll
  /// Judges the leaf's points first, a group at a time, and rewrites the leaf only when the scan
  /// saw through some: most leaves lose nothing.
  bool filter_leaf(std::uint32_t id) {
    const Node& n = t_.nodes()[id];
    const PointSpan points = t_.points().span(n.link, n.count);
    seen_through_.resize(points.size);
    std::size_t seen = 0;
    PixelLookup::Group& group = group_;
    std::array<std::uint32_t, PixelLookup::kGroup> pixels;
    std::array<double, PixelLookup::kGroup> ranges;
    for (std::uint32_t begin = 0; begin < points.size; begin += std::uint32_t(group.size)) {
      group.size = std::min<std::size_t>(PixelLookup::kGroup, points.size - begin);
      for (std::size_t i = 0; i < group.size; ++i) {
        const Eigen::Vector3d v = sensor_frame({points.x[begin + i], points.y[begin + i], points.z[begin + i]});
        group.x[i] = v.x(), group.y[i] = v.y(), group.z[i] = v.z();
      }
      pixels_.pixels_of(group, pixels, ranges);
      for (std::size_t i = 0; i < group.size; ++i) {
        seen_through_[begin + i] = seen_through(pixels[i], ranges[i]) ? 1 : 0;
        seen += seen_through_[begin + i];
      }
    }
    stats_.cleared += seen;
    if (seen == 0) return false;
    std::uint32_t i = 0;  // retain() asks in order
    t_.retain(id, [&](const StoredPoint&) { return seen_through_[i++] == 0; });
    return true;
  }

  /// Whether the scan sees through the held point at stored coordinates `p` (counted).
  bool cleared(const std::array<float, 3>& p) {
    const Eigen::Vector3d v = sensor_frame(p);
    double range = 0.0;
    const std::uint32_t pixel = pixels_.pixel_of(v, range);
    const bool seen = seen_through(pixel, range);
    stats_.cleared += seen ? 1 : 0;
    return seen;
  }

 private:
  /// The held point at stored coordinates `p` in the sensor's frame.
  [[nodiscard]] Eigen::Vector3d sensor_frame(const std::array<float, 3>& p) const {
    return sensor_R_world_ * (sensor_from_anchor_ + Eigen::Vector3d(double(p[0]), double(p[1]), double(p[2])));
  }
  /// Whether the scan sees through a held point at `pixel` (or kOutside), `range` from the sensor:
  /// a pixel with no return around it (kNoReturn) is not evidence of free space.
  [[nodiscard]] bool seen_through(std::uint32_t pixel, double range) const {
    const double nearest = pixel == PixelLookup::kOutside ? RangeImage::kNoReturn : image_.nearest_around(pixel);
    return nearest != RangeImage::kNoReturn && nearest > range + margin_;
  }

  Tree& t_;
  PixelLookup pixels_;
  RangeImage image_;
  Eigen::Matrix3d sensor_R_world_;
  Eigen::Vector3d sensor_from_anchor_;  // anchor - sensor position: stored point + this = sensor-relative, world axes
  Eigen::Vector3d up_;                  // the sensor's z axis, world axes
  double sin_fov_min_ = 0.0, sin_fov_max_ = 0.0;
  double margin_ = 0.0;
  double max_range_ = 0.0;
  UpdateStats& stats_;
  std::vector<char> seen_through_;  // filter_leaf's verdicts, per point of the leaf
  PixelLookup::Group group_;        // filter_leaf's, kept: zeroing a group for every leaf cost more than its use
};

}  // namespace

void clear_free_space(Tree& tree, const Motion& motion, ScanView scan, std::vector<StoredPoint>& displaced,
                      UpdateStats& stats) {
  if (!tree.config().clearing.enabled) return;
  Clearer clearer(tree, motion, scan, stats);
  std::erase_if(displaced, [&](const StoredPoint& s) {
    if (!clearer.cleared(s.p)) return false;
    tree.forget(s);
    return true;
  });
  if (tree.root() != kNone && filter_subtree(tree, tree.root(), clearer) == Filtered::Gone) {
    tree.place_root(tree.root_cell(), tree.lattice());
  }
}

}  // namespace eco::detail
