// Free-space clearing (Config::clearing): the held points the new scan sees through leave the
// tree. The scan's returns are binned into the sensor's range image once; each held point is then
// projected into it and cleared when the nearest return around its pixel lies beyond it by more
// than the margin (the rule in include/eco/config.hpp).
//
// With clearing.arrivals, the points the last update brought in are judged once more, against the
// scan before theirs from where it was taken: the tree keeps the last two updates' images.
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

#include <optional>
#include <type_traits>
#include <utility>

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
  SeenThrough(RangeImage image, double margin) : image_(image), margin_(margin) {}
  /// For a held point at `pixel` (or kOutside), |v|^2 = `squared_range` from the sensor: a pixel
  /// with no return around it (kNoReturn) is not evidence of free space.
  [[nodiscard]] bool operator()(std::uint32_t pixel, double squared_range) const {
    if (pixel == PixelLookup::kOutside) return false;
    const double nearest = image_.nearest_around(pixel);
    return nearest != RangeImage::kNoReturn && lies_beyond(nearest, squared_range, margin_);
  }

 private:
  RangeImage image_;  // a view of storage the tree keeps
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
  const std::uint32_t* stamps;  // null unless kept
};
using Verdicts = std::vector<char>;

/// A scan that judges held points: where it was taken from, and its image.
struct Judge {
  Sight sight;
  SeenThrough seen_through;
  /// Whether it sees through stored point `s`.
  [[nodiscard]] bool sees_through(const PixelLookup& pixels, const StoredPoint& s) const {
    const Eigen::Vector3d v = sight.pose().apply(s.p);
    double range = 0.0;
    return seen_through(pixels.pixel_of(v, range), v.squaredNorm());
  }
};

/// This update's scan, and (clearing.arrivals) the scan before the one that brought the points
/// stamped `arrived`.
struct Judges {
  Judge now;
  std::optional<Judge> before;
  std::uint32_t arrived = 0;
  /// Whether a point stamped `stamp` came in the last update and there is a scan before its own.
  [[nodiscard]] bool is_arrival(std::uint32_t stamp) const { return before && stamp == arrived; }
  /// Whether stored point `s` is seen through: by this scan, or (an arrival) by the one before.
  [[nodiscard]] bool clear(const PixelLookup& pixels, const StoredPoint& s) const {
    return now.sees_through(pixels, s) || (is_arrival(s.stamp) && before->sees_through(pixels, s));
  }
  [[nodiscard]] bool may_see(const Aabb& box) const {
    return now.sight.may_see(box) || (before && before->sight.may_see(box));
  }
};

/// Pass 1, the nodes: appends to `visits` the nodes under `id` whose bounds a judge may see;
/// returns the points their leaves hold, numbered from `first`.
std::uint32_t look_into(const Tree& t, std::uint32_t id, std::uint32_t parent, const Judges& judges,
                        std::vector<Visit>& visits, std::uint32_t first) {
  const Node& n = t.nodes()[id];
  if (n.count == 0 || !judges.may_see(n.bounds)) return 0;
  if (n.leaf) {
    const PointSpan points = t.points().span(n.link, n.count);
    visits.push_back({id, parent, n.count, first, 0, std::uint32_t(points.y - points.x), points.x, points.stamps});
    return n.count;
  }
  const std::uint32_t here = std::uint32_t(visits.size());
  visits.push_back({id, parent, 0, first, 0, 0, nullptr, nullptr});
  t.nodes().prefetch_children(id);  // their misses overlap
  std::uint32_t points = 0;
  for (int o = 0; o < 8; ++o) {
    const std::uint32_t child = t.nodes().child(id, o);
    if (child != kNone) points += look_into(t, child, here, judges, visits, first + points);
  }
  return points;
}

/// Pass 1, a judge's end of it: its pose and pixel stream, and the group of stored points being
/// filled for them.
template <class Stream>
class Sink {
 public:
  Sink(const SensorPose& pose, Stream& stream) : pose_(pose), stream_(stream) {}
  void add(float x, float y, float z, std::uint32_t tag) {
    const std::size_t k = stored_.size++;
    stored_.x[k] = x, stored_.y[k] = y, stored_.z[k] = z;
    tags_[k] = tag;
    if (stored_.size == PixelLookup::kGroup) send();
  }
  /// Sends what is left, then the stream's own leftovers.
  void flush() {
    send();
    stream_.flush();
  }

 private:
  void send() {
    to_sensor_frame(pose_, stored_, group_);
    stream_.push_group(group_, tags_);
    stored_.size = 0;
  }
  const SensorPose& pose_;
  Stream& stream_;
  StoredGroup stored_;
  PixelLookup::Group group_;
  std::array<std::uint32_t, PixelLookup::kGroup> tags_{};
};

/// A sink that takes nothing (no arrivals to judge).
struct NoSink {
  void add(float, float, float, std::uint32_t) {}
  void flush() {}
};

/// Pass 1, the points: streams every visited leaf's points into `now`, and those stamped
/// `arrived` into `arrivals` too, tagged with their verdicts' index, a group at a time across
/// leaves; the leaves' columns are asked for a few leaves ahead.
template <class Now, class Arrivals>
void stream_points(const std::vector<Visit>& visits, Now& now, Arrivals& arrivals, std::uint32_t arrived) {
  constexpr std::size_t kAhead = 8;
  constexpr bool kArrivals = !std::is_same_v<Arrivals, NoSink>;
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
    for (std::uint32_t i = 0; i < leaf.points; ++i) now.add(x[i], y[i], z[i], leaf.first + i);
    if constexpr (kArrivals) {
      for (std::uint32_t i = 0; i < leaf.points; ++i) {
        if (leaf.stamps[i] == arrived) arrivals.add(x[i], y[i], z[i], leaf.first + i);
      }
    }
  }
  now.flush();
  arrivals.flush();
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

/// Clears from `tree` and `displaced` what the judges see through.
void clear_seen_through(Tree& tree, const PixelLookup& pixels, const Judges& judges,
                        std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  std::erase_if(displaced, [&](const StoredPoint& s) {
    if (!judges.clear(pixels, s)) return false;
    ++stats.cleared;
    tree.forget(s);
    return true;
  });
  if (tree.root() == kNone) return;
  std::vector<Visit> visits;
  Verdicts verdicts;
  std::size_t seen = 0;
  verdicts.resize(look_into(tree, tree.root(), kNone, judges, visits, 0));
  // The two scans' groups go out interleaved: a point either sees through is marked and counted once.
  const auto judged_by = [&](const SeenThrough& seen_through) {
    return [&](std::uint32_t tag, std::uint32_t pixel, double squared_range) {
      if (!seen_through(pixel, squared_range) || verdicts[tag] != 0) return;
      verdicts[tag] = 1;
      ++seen;
    };
  };
  const auto by_now = judged_by(judges.now.seen_through);
  PixelStream<decltype(by_now), PixelLookup::Reach::SquaredRange> now_stream(pixels, by_now);
  Sink now(judges.now.sight.pose(), now_stream);
  if (judges.before) {
    const auto by_before = judged_by(judges.before->seen_through);
    PixelStream<decltype(by_before), PixelLookup::Reach::SquaredRange> before_stream(pixels, by_before);
    Sink arrivals(judges.before->sight.pose(), before_stream);
    stream_points(visits, now, arrivals, judges.arrived);
  } else {
    NoSink none;
    stream_points(visits, now, none, 0);
  }
  stats.cleared += seen;
  if (seen == 0) return;
  const std::vector<std::uint32_t> plan = plan_clearing(tree, visits, verdicts);
  Clearing clearing(tree, plan, visits, verdicts);
  if (filter_subtree(tree, tree.root(), clearing) == Filtered::Gone) {
    tree.place_root(tree.root_cell(), tree.lattice());
  }
}

/// Keeps this update's image (in `memory.image`) as the last one, the last as the one before.
void keep_image(Tree::ClearingMemory& memory, const Motion& motion) {
  std::swap(memory.earlier[0], memory.earlier[1]);
  std::swap(memory.earlier[0].storage, memory.image);  // the oldest's storage is reused
  memory.earlier[0].frame = motion.frame;
  memory.earlier[0].pose = motion.pose;
}

}  // namespace

void clear_free_space(Tree& tree, const Motion& motion, ScanView scan, std::vector<StoredPoint>& displaced,
                      UpdateStats& stats) {
  const Config& config = tree.config();
  if (!config.clearing.enabled) return;
  Tree::ClearingMemory& memory = tree.clearing_memory();
  const PixelLookup pixels(config.sensor, memory.pixel_tables);
  const double margin = config.clearing.margin;
  Judges judges{{Sight(motion, config.sensor), SeenThrough(RangeImage(pixels, scan, memory.image), margin)},
                std::nullopt, motion.frame - 1};
  // the points the last update brought in were stamped frame - 1; the scan before theirs, frame - 2
  const Tree::EarlierImage& before = memory.earlier[1];
  const bool arrivals = judges_arrivals(config);
  if (arrivals && motion.frame > 2 && before.frame == motion.frame - 2) {
    Motion then = motion;
    then.pose = before.pose;
    judges.before.emplace(Judge{Sight(then, config.sensor), SeenThrough(RangeImage(pixels, before.storage), margin)});
  }
  clear_seen_through(tree, pixels, judges, displaced, stats);
  if (arrivals) keep_image(memory, motion);
}

}  // namespace eco::detail
