// Free-space clearing's arrivals (Config::clearing.arrivals): a point that comes in where the
// scan before its own saw empty space is something that moved in. Insertion judges each new point
// against that scan (ArrivalCheck); those it sees through are held for one update, then leave the
// tree (release_arrivals).

#include "clearing/clearing.hpp"
#include "clearing/pixel_stream.hpp"
#include "core/tree/subtree_filter.hpp"

#include <algorithm>
#include <bit>
#include <utility>

namespace eco::detail {

ArrivalCheck::ArrivalCheck(const Config& config, ClearingState& state, const Motion& motion)
    : pixels_(config.sensor, state.pixel_tables),
      judge_{Sight(state.before.pose, motion.anchor, config.sensor),
             SeenThrough(RangeImage(pixels_, state.before.storage), config.clearing.margin)},
      leaving_(state.leaving) {}

bool judges_arrivals(const Config& config, const ClearingState& state, const Motion& motion) {
  const bool last_update_seen = state.before.frame != 0 && state.before.frame + 1 == motion.frame;
  return config.clearing.arrivals && last_update_seen;
}

template <class Point>
void ArrivalCheck::operator()(std::span<const Point> batch) {
  const auto take = [&](std::uint32_t tag, std::uint32_t pixel, double squared_range) {
    if (judge_.seen_through(pixel, squared_range)) leaving_.push_back(as_stored(batch[tag]));
  };
  PixelStream<decltype(take), PixelLookup::Reach::SquaredRange, SeenThrough> stream(pixels_, take, judge_.seen_through);
  Sink sink(judge_.sight.pose(), stream);
  for (const Point& point : batch) sink.add(point.p[0], point.p[1], point.p[2]);  // tagged by index
  sink.flush();
}

template void ArrivalCheck::operator()(std::span<const StoredPoint>);
template void ArrivalCheck::operator()(std::span<const BarePoint>);

namespace {

/// Whether two stored points are the same to the bit, every column (an intensity may be NaN).
bool same(const StoredPoint& a, const StoredPoint& b) {
  const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
  return bits(a.p[0]) == bits(b.p[0]) && bits(a.p[1]) == bits(b.p[1]) && bits(a.p[2]) == bits(b.p[2]) &&
         a.stamp == b.stamp && a.id == b.id && bits(a.intensity) == bits(b.intensity) && bits(a.time) == bits(b.time);
}

/// The leaf whose cell holds stored coordinates `p`, or kNone.
std::uint32_t leaf_holding(const Tree& t, const std::array<float, 3>& p) {
  std::uint32_t id = t.root();
  Cell cell = t.root_cell();
  while (id != kNone && !t.nodes()[id].leaf) {
    const int o = t.lattice().octant(cell, p);
    id = t.nodes().child(id, o);
    cell = t.lattice().child(cell, o);
  }
  return id;
}

/// A filter of Tree::filter that takes the leaving points out of the leaves holding them:
/// `marked` (sorted) lists those leaves and their ancestors, `at` (sorted) each leaving point's
/// leaf and index.
class Release {
 public:
  Release(Tree& tree, DensityCells* density, const std::vector<StoredPoint>& leaving,
          const std::vector<std::uint32_t>& marked, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& at)
      : t_(tree), density_(density), leaving_(leaving), marked_(marked), at_(at), taken_(leaving.size(), 0) {}

  [[nodiscard]] Verdict judge(std::uint32_t id, const Node&) const {
    return std::binary_search(marked_.begin(), marked_.end(), id) ? Verdict::LookInside : Verdict::KeepAll;
  }
  bool filter_leaf(std::uint32_t id) {
    const auto leaf = std::equal_range(at_.begin(), at_.end(), id, ByLeaf{});
    const auto first = leaf.first, last = leaf.second;  // not a structured binding: the lambda captures them
    const std::size_t before = released_;
    // each leaving point takes one held point equal to it (equal ones are interchangeable)
    t_.retain(id, [&](const StoredPoint& s) {
      for (auto k = first; k != last; ++k) {
        if (taken_[k->second] == 0 && same(s, leaving_[k->second])) {
          taken_[k->second] = 1;
          ++released_;
          return false;
        }
      }
      return true;
    }, density_);
    return released_ != before;
  }
  [[nodiscard]] std::size_t released() const { return released_; }

 private:
  struct ByLeaf {  // orders `at` entries and leaf ids by leaf
    bool operator()(const std::pair<std::uint32_t, std::uint32_t>& a, std::uint32_t leaf) const { return a.first < leaf; }
    bool operator()(std::uint32_t leaf, const std::pair<std::uint32_t, std::uint32_t>& a) const { return leaf < a.first; }
  };
  Tree& t_;
  DensityCells* density_;
  const std::vector<StoredPoint>& leaving_;
  const std::vector<std::uint32_t>& marked_;
  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& at_;
  std::vector<char> taken_;  // per leaving point: found and taken out
  std::size_t released_ = 0;
};

}  // namespace

void release_arrivals(Tree& tree, DensityCells* density, ClearingState& state, UpdateStats& stats) {
  std::vector<StoredPoint>& leaving = state.leaving;
  if (leaving.empty()) return;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> at;
  std::vector<std::uint32_t> marked;
  for (std::size_t k = 0; k < leaving.size(); ++k) {
    const std::uint32_t leaf = leaf_holding(tree, leaving[k].p);
    if (leaf == kNone) continue;
    at.emplace_back(leaf, std::uint32_t(k));
    for (std::uint32_t id = leaf; id != kNone; id = tree.nodes()[id].parent) marked.push_back(id);
  }
  std::sort(at.begin(), at.end());
  std::sort(marked.begin(), marked.end());
  marked.erase(std::unique(marked.begin(), marked.end()), marked.end());
  Release release(tree, density, leaving, marked, at);
  tree.filter(release, stats, density);
  stats.cleared += release.released();
  leaving.clear();
}

}  // namespace eco::detail
