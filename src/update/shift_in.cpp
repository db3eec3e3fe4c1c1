#include "clearing/clearing.hpp"
#include "core/tree/batch_insertion.hpp"
#include "core/density/density_gate.hpp"
#include "update/admission.hpp"
#include "update/stages.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace eco::detail {

namespace {

constexpr int kMaxStartDepth = 4;  // Exact mode: start table of at most 8^4 slots

/// The paper's movement-aware start depth, d = min(d_max, max(0, floor(log2(L / |v|)))); in
/// Quantised mode the lattice depth k, below which cells never move.
int start_depth(const Tree& t, const Motion& motion) {
  const Config& cfg = t.config();
  if (cfg.recentring == Recentring::Quantised) return int(cfg.quantum_levels);
  const int cap = std::min(t.lattice().max_depth, kMaxStartDepth);
  if (!motion.previous || motion.moved <= 0.0) return cap;
  const double d = std::floor(std::log2(cfg.box_side / motion.moved));
  return d <= 0.0 ? 0 : std::min(cap, int(d));
}

}  // namespace

void insert_shift_in(Tree& tree, DensityCells* density, const Motion& motion, ScanView scan,
                     std::vector<StoredPoint> displaced, ClearingState* clearing, UpdateStats& stats) {
  place_start_table(tree, motion);
  reinsert(tree, displaced, stats);
  insert_scan(tree, density, motion, scan, clearing, stats);
}

void place_start_table(Tree& tree, const Motion& motion) { tree.rebuild_start_table(start_depth(tree, motion)); }

void reinsert(Tree& tree, std::vector<StoredPoint>& points, UpdateStats& stats) {
  stats.reinserted_points += points.size();
  tree.insert_batch(points);
  points.clear();
}

namespace {

/// Takes out of `group` the points older than the age limit already (their times), keeping the
/// others' order; returns how many.
template <class Make>
std::size_t drop_aged(const Tree& tree, AdmittedGroup& group, const Make& make) {
  std::size_t kept = 0;
  for (std::size_t j = 0; j < group.size; ++j) {
    if (tree.age_limit().key(as_stored(make(group.points[j], group.index[j]))) < tree.age_limit().cutoff) continue;
    group.points[kept] = group.points[j];
    group.index[kept] = group.index[j];
    ++kept;
  }
  const std::size_t dropped = group.size - kept;
  group.size = kept;
  return dropped;
}

/// Inserts the scan points the policy admits and the density cap passes, each as
/// make(stored coordinates, scan index) makes it; returns how many.
template <class Make>
std::size_t take_in(Tree& tree, DensityCells* density, const Motion& motion, ScanView scan, ClearingState* clearing,
                    UpdateStats& stats, const Make& make) {
  static_assert(kAdmitGroup <= kDensityGroup, "an admitted group is judged whole");
  using Point = decltype(make(std::array<float, 3>{}, std::uint32_t{}));
  const bool timed_age = tree.config().max_age_seconds > 0.0;
  std::optional<ArrivalCheck> arrivals;
  if (clearing && judges_arrivals(tree.config(), *clearing, motion)) arrivals.emplace(tree.config(), *clearing, motion);
  const auto check = [&](std::span<const Point> batch) {
    if (arrivals) (*arrivals)(batch);
  };
  return tree.insert_collected<Point>([&](auto&& insert) {
    admission(motion, tree.config().insert_policy).for_each_group(scan, stats, [&](AdmittedGroup& group) {
      if (timed_age) stats.skipped_by_age += drop_aged(tree, group, make);
      // in scan order: the first points to reach a full cell are the ones kept
      std::array<std::uint8_t, kAdmitGroup> passed;
      if (density) {
        stats.skipped_by_density += density->judge(group.points.data(), group.size, passed.data());
      } else {
        std::fill_n(passed.begin(), group.size, std::uint8_t{1});
      }
      for_each_set(passed.data(), group.size, [&](std::size_t j) { insert(make(group.points[j], group.index[j])); });
    });
  }, check);
}

}  // namespace

void insert_scan(Tree& tree, DensityCells* density, const Motion& motion, ScanView scan, ClearingState* clearing,
                 UpdateStats& stats) {
  const Columns& kept = tree.points().columns();
  if (kept.count() == 0) {  // coordinates alone: the batches move less than half the bytes
    stats.inserted = take_in(tree, density, motion, scan, clearing, stats,
                             [](const std::array<float, 3>& p, std::uint32_t) { return BarePoint{p}; });
    return;
  }
  const std::uint32_t stamp = kept.stamps ? motion.frame : 0;
  stats.inserted = take_in(tree, density, motion, scan, clearing, stats, [&](const std::array<float, 3>& p, std::uint32_t i) {
    return StoredPoint{p, stamp, kept.ids ? scan.ids[i] : 0u, kept.intensities ? scan.intensities[i] : 0.0f,
                       kept.times ? float(scan.times[i] - motion.clock.origin) : 0.0f};
  });
}

}  // namespace eco::detail
