#include "update/admission.hpp"
#include "update/stages.hpp"

namespace eco::detail {

Admission admission(const Tree& tree) {
  Admission a{tree.pose, tree.anchor, tree.box, std::nullopt};
  if (tree.cfg.insert_policy == InsertPolicy::ShiftInOnly && tree.has_previous) {
    a.previous = tree.box_around(tree.previous_position);  // R_in = box minus previous box
  }
  return a;
}

void insert_shift_in(Tree& tree, ScanView scan) {
  const std::uint32_t stamp = tree.points.keeps_stamps() ? tree.frame : 0;
  UpdateStats& stats = tree.last;
  std::vector<StoredPoint>& batch = tree.moving;  // empty between stages
  batch.clear();
  const DensityCap& cap = tree.cfg.density_cap;
  admission(tree).for_each(scan, stats, [&](const std::array<float, 3>& p) {
    // in scan order: the first points to reach a full cell are the ones kept
    if (cap.enabled() && !tree.density.add_below(tree.density_key(p), cap.max_points)) {
      ++stats.skipped_by_density;
      return;
    }
    batch.push_back({p, stamp});
  });
  stats.inserted = batch.size();
  tree.insert_batch(batch);
  batch.clear();
}

}  // namespace eco::detail
