// Free-space clearing (Config::clearing): the held points the new scan sees through leave the
// tree. The scan's returns are binned into the sensor's range image once; each held point is then
// projected into it and cleared when the nearest return around its pixel lies beyond it by more
// than the margin (the rule in include/eco/config.hpp).
//
// Two passes. The first reads the tree: it notes the nodes the sensor may see (look_into), then
// streams their leaves' points into the pixel lookup in full groups across leaves, rotated into
// the sensor's frame in vector code (stream_points), each point's verdict kept by its index. The
// second rewrites only the leaves that lost points, and the nodes above them (plan_clearing,
// Clearing).

#include "update/clearing_rule.hpp"
#include "update/pixel_stream.hpp"
#include "update/range_image.hpp"
#include "update/sensor_frame.hpp"
#include "update/stages.hpp"
#include "update/subtree_filter.hpp"

namespace eco::detail {
namespace {

constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

/// Where the sensor looks from this frame: held points in its frame, and which subtrees lie wholly
/// beyond its range or outside its vertical field of view (none of their points has a pixel).
class Sight {
 public:
  Sight(const Motion& motion, const SensorModel& sensor)
      : sensor_from_anchor_(motion.anchor - motion.pose.translation()),
        pose_(motion.pose.linear().transpose(), sensor_from_anchor_),
        up_(motion.pose.linear().col(2)),  // sensor_R_world's third row
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
 public:
  SeenThrough(const RangeImage& image, double margin) : image_(image), margin_(margin) {}
  /// For a held point at `pixel` (or kOutside), |v|^2 = `squared_range` from the sensor: a pixel
  /// with no return around it (kNoReturn) is not evidence of free space.
  [[nodiscard]] bool operator()(std::uint32_t pixel, double squared_range) const {
    if (pixel == PixelLookup::kOutside) return false;
    const double nearest = image_.nearest_around(pixel);
    return nearest != RangeImage::kNoReturn && lies_beyond(nearest, squared_range, margin_);
  }

 private:
  const RangeImage& image_;
  double margin_ = 0.0;
};

/// A node the first pass looked into, in the order it did (preorder). A leaf's points (`points`
/// of them; 0, with stride 0, for an inner node) lie in its block's columns, x from `x`, y and z
/// `stride` floats further each (while the tree is unchanged: the first pass only), and have
/// verdicts [first, first + points).
struct Visit {
  std::uint32_t id;
  std::uint32_t parent;  // its parent's Visit, kNone for the root
  std::uint32_t points;
  std::uint32_t first;
  std::uint32_t seen;    // points seen through in the subtree (filled after the pass)
  std::uint32_t stride;
  const float* x;
};
using Verdicts = std::vector<char>;

/// Pass 1, the nodes: appends to `visits` the nodes under `id` whose bounds the sensor may see;
/// returns the points their leaves hold, numbered from `first`.
std::uint32_t look_into(const Tree& t, std::uint32_t id, std::uint32_t parent, const Sight& sight,
                        std::vector<Visit>& visits, std::uint32_t first) {
  const Node& n = t.nodes()[id];
  if (n.count == 0 || !sight.may_see(n.bounds)) return 0;
  if (n.leaf) {
    const PointSpan points = t.points().span(n.link, n.count);
    visits.push_back({id, parent, n.count, first, 0, std::uint32_t(points.y - points.x), points.x});
    return n.count;
  }
  const std::uint32_t here = std::uint32_t(visits.size());
  visits.push_back({id, parent, 0, first, 0, 0, nullptr});
  t.nodes().prefetch_children(id);  // their misses overlap
  std::uint32_t points = 0;
  for (int o = 0; o < 8; ++o) {
    const std::uint32_t child = t.nodes().child(id, o);
    if (child != kNone) points += look_into(t, child, here, sight, visits, first + points);
  }
  return points;
}

/// Pass 1, the points: streams every visited leaf's points into `stream`, in the sensor's frame,
/// tagged with their verdicts' index, a group at a time across leaves; the leaves' columns are
/// asked for a few leaves ahead.
template <class Stream>
void stream_points(const std::vector<Visit>& visits, const SensorPose& pose, Stream& stream) {
  constexpr std::size_t kAhead = 8;
  StoredGroup stored;
  PixelLookup::Group group;
  std::array<std::uint32_t, PixelLookup::kGroup> tags{};
  const auto send = [&] {
    to_sensor_frame(pose, stored, group);
    stream.push_group(group, tags);
    stored.size = 0;
  };
  for (std::size_t v = 0; v < visits.size(); ++v) {
    if (v + kAhead < visits.size()) {
      const Visit& ahead = visits[v + kAhead];
      for (std::uint32_t column = 0; column < 3 * ahead.stride; column += ahead.stride) {
        __builtin_prefetch(ahead.x + column);
        __builtin_prefetch(ahead.x + column + ahead.points - 1);
      }
    }
    const Visit& leaf = visits[v];
    const float* x = leaf.x;
    const float* y = x + leaf.stride;
    const float* z = y + leaf.stride;
    for (std::uint32_t i = 0; i < leaf.points; ++i) {
      const std::size_t k = stored.size++;
      stored.x[k] = x[i], stored.y[k] = y[i], stored.z[k] = z[i];
      tags[k] = leaf.first + i;
      if (stored.size == PixelLookup::kGroup) send();
    }
  }
  send();
}

/// Pass 2's plan from pass 1's visits and verdicts: per node id, 0 where nothing below was seen
/// through, else its Visit + 1.
std::vector<std::uint32_t> plan_clearing(const Tree& t, std::vector<Visit>& visits, const Verdicts& verdicts) {
  for (std::size_t v = visits.size(); v-- > 0;) {  // children before their parents
    Visit& visit = visits[v];
    for (std::uint32_t i = 0; i < visit.points; ++i) visit.seen += std::uint32_t(verdicts[visit.first + i]);
    if (visit.parent != kNone) visits[visit.parent].seen += visit.seen;
  }
  std::vector<std::uint32_t> plan(t.nodes().id_bound(), 0);
  for (std::size_t v = 0; v < visits.size(); ++v) {
    if (visits[v].seen > 0) plan[visits[v].id] = std::uint32_t(v + 1);
  }
  return plan;
}

/// Pass 2, as a filter of filter_subtree: looks only into the subtrees that lost points.
class Clearing {
 public:
  Clearing(Tree& tree, const std::vector<std::uint32_t>& plan, const std::vector<Visit>& visits,
           const Verdicts& verdicts)
      : t_(tree), plan_(plan), visits_(visits), verdicts_(verdicts) {}

  [[nodiscard]] Verdict judge(std::uint32_t id, const Node&) const {
    return plan_[id] != 0 ? Verdict::LookInside : Verdict::KeepAll;
  }
  void drop(std::uint32_t) {}  // never judged DropAll
  bool filter_leaf(std::uint32_t id) {
    std::uint32_t i = visits_[plan_[id] - 1].first;  // retain() asks in order
    t_.retain(id, [&](const StoredPoint&) { return verdicts_[i++] == 0; });
    return true;
  }

 private:
  Tree& t_;
  const std::vector<std::uint32_t>& plan_;
  const std::vector<Visit>& visits_;
  const Verdicts& verdicts_;
};

}  // namespace

void clear_free_space(Tree& tree, const Motion& motion, ScanView scan, std::vector<StoredPoint>& displaced,
                      UpdateStats& stats) {
  if (!tree.config().clearing.enabled) return;
  Tree::ClearingMemory& memory = tree.clearing_memory();
  const PixelLookup pixels(tree.config().sensor, memory.pixel_tables);
  const RangeImage image(pixels, scan, memory.image);
  const Sight sight(motion, tree.config().sensor);
  const SeenThrough seen_through(image, tree.config().clearing.margin);
  std::erase_if(displaced, [&](const StoredPoint& s) {
    const Eigen::Vector3d v = sight.pose().apply(s.p);
    double range = 0.0;
    const std::uint32_t pixel = pixels.pixel_of(v, range);
    if (!seen_through(pixel, v.squaredNorm())) return false;
    ++stats.cleared;
    tree.forget(s);
    return true;
  });
  if (tree.root() == kNone) return;
  std::vector<Visit> visits;
  Verdicts verdicts;
  std::size_t seen = 0;
  const auto judge = [&](std::uint32_t tag, std::uint32_t pixel, double squared_range) {
    const bool through = seen_through(pixel, squared_range);
    verdicts[tag] = through ? 1 : 0;
    seen += through ? 1 : 0;
  };
  PixelStream<decltype(judge), PixelLookup::Reach::SquaredRange> stream(pixels, judge);
  verdicts.resize(look_into(tree, tree.root(), kNone, sight, visits, 0));
  stream_points(visits, sight.pose(), stream);
  stream.flush();
  stats.cleared += seen;
  if (seen == 0) return;
  const std::vector<std::uint32_t> plan = plan_clearing(tree, visits, verdicts);
  Clearing clearing(tree, plan, visits, verdicts);
  if (filter_subtree(tree, tree.root(), clearing) == Filtered::Gone) {
    tree.place_root(tree.root_cell(), tree.lattice());
  }
}

}  // namespace eco::detail
