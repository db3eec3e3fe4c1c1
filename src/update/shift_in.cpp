#include "update/admission.hpp"
#include "update/stages.hpp"

#include <algorithm>
#include <cmath>

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

void insert_shift_in(Tree& tree, const Motion& motion, ScanView scan, std::vector<StoredPoint> displaced,
                     UpdateStats& stats) {
  place_start_table(tree, motion);
  reinsert(tree, displaced, stats);
  insert_scan(tree, motion, scan, stats);
}

void place_start_table(Tree& tree, const Motion& motion) { tree.rebuild_start_table(start_depth(tree, motion)); }

void reinsert(Tree& tree, std::vector<StoredPoint>& points, UpdateStats& stats) {
  stats.reinserted_points += points.size();
  tree.insert_batch(points);
  points.clear();
}

namespace {

/// A scan point the policy admits: its stored coordinates and its index in the scan.
struct Candidate {
  std::array<float, 3> p;
  std::uint32_t index;
};

}  // namespace

void insert_scan(Tree& tree, const Motion& motion, ScanView scan, UpdateStats& stats) {
  const Columns& kept = tree.points().columns();
  const std::uint32_t stamp = kept.stamps ? motion.frame : 0;
  const bool timed_age = tree.config().max_age_seconds > 0.0;
  const auto stored = [&](const Candidate& c) {
    const std::uint32_t i = c.index;
    return StoredPoint{c.p, stamp, kept.ids ? scan.ids[i] : 0u, kept.intensities ? scan.intensities[i] : 0.0f,
                       kept.times ? float(scan.times[i] - motion.clock.origin) : 0.0f};
  };
  // offer(candidate, coordinates) for each scan point the policy admits, in scan order
  const auto admitted = [&](auto&& offer) {
    admission(motion, tree.config().insert_policy)
        .for_each(scan, stats, [&](const std::array<float, 3>& p, std::size_t i) {
          const Candidate c{p, std::uint32_t(i)};
          if (timed_age && tree.age_key(stored(c)) < tree.age_cutoff()) {  // older than the limit already
            ++stats.skipped_by_age;
            return;
          }
          offer(c, p);
        });
  };
  stats.inserted = tree.insert_collected([&](auto&& insert) {
    // in scan order: the first points to reach a full cell are the ones kept
    stats.skipped_by_density +=
        tree.pass_density_cap<Candidate>(admitted, [&](const Candidate& c) { insert(stored(c)); });
  });
}

}  // namespace eco::detail
