// Free-space clearing (Config::clearing): the held points the new scan sees through leave the
// tree. The scan's returns are binned into the sensor's range image once; each held point is then
// projected into it and cleared when the nearest return around its pixel lies beyond it by more
// than the margin (the rule in include/eco/config.hpp).
//
// With clearing.arrivals, the state keeps the last update's scan too, against which insertion
// judges the points this one brings in (src/clearing/arrivals.cpp).
//
// Two passes. The first reads the tree: it notes the nodes the sensor may see (look_into), then
// streams their leaves' points into the pixel lookup in full groups across leaves, rotated into
// the sensor's frame in vector code (stream_points); the judge's screen rules out most of each
// group at once, and the numbers of the points seen through are kept. The second rewrites only
// the leaves that lost points, and the nodes above them (plan_clearing, Clearing).

#include "clearing/clearing.hpp"
#include "clearing/pixel_stream.hpp"
#include "clearing/scan_judge.hpp"
#include "core/tree/subtree_filter.hpp"

#include <algorithm>
#include <utility>

namespace eco::detail {
namespace {

/// A node the first pass looked into, in the order it did (preorder). A leaf's points (`points`
/// of them; 0, with stride 0, for an inner node) lie in its block's columns, x from `x`, y and z
/// `stride` floats further each (while the tree is unchanged: the first pass only), and are
/// numbered [first, first + points).
struct Visit {
  std::uint32_t id;
  std::uint32_t parent;  // its parent's Visit, kNone for the root
  std::uint32_t points;
  std::uint32_t first;
  std::uint32_t seen;    // points seen through in the subtree (filled after the pass)
  std::uint32_t stride;
  const float* x;
};
/// The numbers of the points seen through, in increasing order.
using SeenPoints = std::vector<std::uint32_t>;

/// Pass 1, the nodes: appends to `visits` the nodes under `id` whose bounds `sight` may see;
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
  t.nodes().for_each_child(id, [&](int, std::uint32_t child) { points += look_into(t, child, here, sight, visits, first + points); });
  return points;
}

/// Pass 1, the points: streams every visited leaf's points into `sink`, tagged with their
/// numbers, a group at a time across leaves; every line of the leaves' columns is asked for a few
/// leaves ahead, since between updates the caller's own work evicts them from the caches.
template <class Sink>
void stream_points(const std::vector<Visit>& visits, Sink& sink) {
  constexpr std::size_t kAhead = 8;
  constexpr std::uint32_t kFloatsPerLine = 64 / sizeof(float);
  for (std::size_t v = 0; v < visits.size(); ++v) {
    if (v + kAhead < visits.size()) {
      const Visit& ahead = visits[v + kAhead];
      for (std::uint32_t column = 0; column < 3 * ahead.stride; column += ahead.stride) {
        for (std::uint32_t at = 0; at < ahead.points; at += kFloatsPerLine) __builtin_prefetch(ahead.x + column + at);
        __builtin_prefetch(ahead.x + column + ahead.points - 1);  // the last line, where the first is not aligned
      }
    }
    const Visit& leaf = visits[v];
    const float* x = leaf.x;
    const float* y = x + leaf.stride;
    const float* z = y + leaf.stride;
    sink.add_columns(x, y, z, leaf.points);  // numbered on from the last leaf's: leaf.first
  }
  sink.flush();
}

/// Pass 2's plan from pass 1's visits and the points seen through: per node id, 0 where nothing
/// below was seen through, else its Visit + 1.
std::vector<std::uint32_t> plan_clearing(const Tree& t, std::vector<Visit>& visits, const SeenPoints& seen) {
  std::size_t k = 0;
  for (Visit& visit : visits) {  // preorder: the leaves' numbers rise
    const std::size_t before = k;
    while (k < seen.size() && seen[k] < visit.first + visit.points) ++k;
    visit.seen = std::uint32_t(k - before);
  }
  for (std::size_t v = visits.size(); v-- > 0;) {  // children before their parents
    if (visits[v].parent != kNone) visits[visits[v].parent].seen += visits[v].seen;
  }
  std::vector<std::uint32_t> plan(t.nodes().id_bound(), 0);
  for (std::size_t v = 0; v < visits.size(); ++v) {
    if (visits[v].seen > 0) plan[visits[v].id] = std::uint32_t(v + 1);
  }
  return plan;
}

/// Pass 2, as a filter of Tree::filter: looks only into the subtrees that lost points.
class Clearing {
 public:
  Clearing(Tree& tree, DensityCells* density, const std::vector<std::uint32_t>& plan, const std::vector<Visit>& visits,
           const SeenPoints& seen)
      : t_(tree), density_(density), plan_(plan), visits_(visits), seen_(seen) {}

  [[nodiscard]] Verdict judge(std::uint32_t id, const Node&) const {
    return plan_[id] != 0 ? Verdict::LookInside : Verdict::KeepAll;
  }
  bool filter_leaf(std::uint32_t id) {
    std::uint32_t i = visits_[plan_[id] - 1].first;  // retain() asks in order
    auto next = std::lower_bound(seen_.begin(), seen_.end(), i);
    t_.retain(id, [&](const StoredPoint&) {
      const bool through = next != seen_.end() && *next == i++;
      next += through ? 1 : 0;
      return !through;
    }, density_);
    return true;
  }

 private:
  Tree& t_;
  DensityCells* density_;
  const std::vector<std::uint32_t>& plan_;
  const std::vector<Visit>& visits_;
  const SeenPoints& seen_;
};

/// Clears from `tree` and `displaced` what `judge` sees through.
void clear_seen_through(Tree& tree, DensityCells* density, const PixelLookup& pixels, const Judge& judge,
                        std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  std::erase_if(displaced, [&](const StoredPoint& s) {
    if (!judge.sees_through(pixels, s.p)) return false;
    ++stats.cleared;
    if (density) density->forget(s.p);
    return true;
  });
  if (tree.root() == kNone) return;
  std::vector<Visit> visits;
  look_into(tree, tree.root(), kNone, judge.sight, visits, 0);
  SeenPoints seen;
  const auto take = [&](std::uint32_t tag, std::uint32_t pixel, double squared_range) {
    if (judge.seen_through(pixel, squared_range)) seen.push_back(tag);
  };
  PixelStream<decltype(take), PixelLookup::Reach::SquaredRange, SeenThrough> stream(pixels, take, judge.seen_through);
  Sink sink(judge.sight.pose(), stream);
  stream_points(visits, sink);
  stats.cleared += seen.size();
  if (seen.empty()) return;
  std::sort(seen.begin(), seen.end());  // tier 1's undecided points came later
  const std::vector<std::uint32_t> plan = plan_clearing(tree, visits, seen);
  Clearing clearing(tree, density, plan, visits, seen);
  tree.filter(clearing, stats, density);
}

}  // namespace

void clear_free_space(Tree& tree, DensityCells* density, ClearingState& state, const Motion& motion, ScanView scan,
                      std::vector<StoredPoint>& displaced, UpdateStats& stats) {
  const Config& config = tree.config();
  if (config.clearing.arrivals) std::swap(state.image, state.before);  // the last update's image; its old storage is reused
  state.image.frame = motion.frame;
  state.image.pose = motion.pose;
  const PixelLookup pixels(config.sensor, state.pixel_tables);
  const Judge judge{Sight(motion.pose, motion.anchor, config.sensor),
                    SeenThrough(RangeImage(pixels, scan, state.image.storage), config.clearing.margin)};
  clear_seen_through(tree, density, pixels, judge, displaced, stats);
}

}  // namespace eco::detail
