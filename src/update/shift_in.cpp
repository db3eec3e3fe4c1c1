#include "update/stages.hpp"

#include <cmath>
#include <optional>

namespace eco::detail {

void insert_shift_in(Tree& tree, ScanView scan) {
  const Eigen::Matrix3d rotation = tree.pose.linear();
  const Eigen::Vector3d translation = tree.pose.translation();
  const std::uint32_t stamp = tree.points.keeps_stamps() ? tree.frame : 0;
  std::optional<Box> previous;  // R_in = box minus previous box
  if (tree.cfg.insert_policy == InsertPolicy::ShiftInOnly && tree.has_previous) {
    previous = tree.box_around(tree.previous_position);
  }
  UpdateStats& stats = tree.last;
  for (std::size_t i = 0; i < scan.count; ++i) {
    const Eigen::Vector3f sensor = scan[i];
    if (!sensor.allFinite()) {
      ++stats.skipped_nonfinite;
      continue;
    }
    const Eigen::Vector3d world = rotation * sensor.cast<double>() + translation;
    const StoredPoint s{tree.to_stored(world), stamp};
    if (!tree.box.contains(s.p[0], s.p[1], s.p[2]) ||
        (previous && previous->contains(s.p[0], s.p[1], s.p[2]))) {
      ++stats.skipped_by_policy;
      continue;
    }
    if (tree.cfg.density_cap.enabled() && !density_allows(tree, s.p)) {
      ++stats.skipped_by_density;
      continue;
    }
    tree.insert(s);
    ++stats.inserted;
  }
}

}  // namespace eco::detail
