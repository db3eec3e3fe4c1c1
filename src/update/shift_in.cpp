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
  if (t.cfg.recentring == Recentring::Quantised) return int(t.cfg.quantum_levels);
  const int cap = std::min(t.lattice.max_depth, kMaxStartDepth);
  if (!motion.previous || motion.moved <= 0.0) return cap;
  const double d = std::floor(std::log2(t.cfg.box_side / motion.moved));
  return d <= 0.0 ? 0 : std::min(cap, int(d));
}

}  // namespace

void insert_shift_in(Tree& tree, const Motion& motion, ScanView scan, std::vector<StoredPoint> displaced) {
  place_start_table(tree, motion);
  reinsert(tree, displaced);
  insert_scan(tree, motion, scan);
}

void place_start_table(Tree& tree, const Motion& motion) { tree.rebuild_start_table(start_depth(tree, motion)); }

void reinsert(Tree& tree, std::vector<StoredPoint>& points) {
  tree.last.reinserted_points += points.size();
  tree.insert_batch(points);
  points.clear();
}

void insert_scan(Tree& tree, const Motion& motion, ScanView scan) {
  const std::uint32_t stamp = tree.points.keeps_stamps() ? motion.frame : 0;
  UpdateStats& stats = tree.last;
  std::vector<StoredPoint>& batch = tree.batch_buffers.scan;  // kept: no fresh pages per frame
  batch.clear();
  const DensityCap& cap = tree.cfg.density_cap;
  admission(motion, tree.cfg.insert_policy).for_each(scan, stats, [&](const std::array<float, 3>& p) {
    // in scan order: the first points to reach a full cell are the ones kept
    if (cap.enabled() && !tree.density.add_below(tree.density_key(p), cap.max_points)) {
      ++stats.skipped_by_density;
      return;
    }
    batch.push_back({p, stamp});
  });
  stats.inserted = batch.size();
  tree.insert_batch(batch);
  tree.trim_buffers(batch.size());
  batch.clear();
}

}  // namespace eco::detail
