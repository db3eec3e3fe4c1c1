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
  admission(tree).for_each(scan, stats, [&](const std::array<float, 3>& p) {
    if (tree.cfg.density_cap.enabled() && !density_allows(tree, p)) {
      ++stats.skipped_by_density;
      return;
    }
    tree.insert({p, stamp});
    ++stats.inserted;
  });
}

}  // namespace eco::detail
