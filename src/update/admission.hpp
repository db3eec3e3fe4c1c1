#pragma once
// Which scan points an update takes in (DESIGN.md §1): finite, inside Box(p_t), and — under
// ShiftInOnly — outside the previous box. Shared by ECO's shift-in stage and the baselines, so
// every method of the benchmark takes in the same points.

#include "core/geometry.hpp"

#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <array>
#include <optional>

namespace eco::detail {

struct Admission {
  Eigen::Isometry3d pose;    // world_T_sensor
  Eigen::Vector3d anchor;    // the precision origin
  Box box;                   // Box(p_t), anchor frame
  std::optional<Box> previous;  // set under ShiftInOnly once a previous box exists

  /// Calls take(stored point) for each admitted scan point; counts the refused ones in `stats`.
  template <class Take>
  void for_each(ScanView scan, UpdateStats& stats, Take&& take) const {
    const Eigen::Matrix3d rotation = pose.linear();
    for (std::size_t i = 0; i < scan.count; ++i) {
      const Eigen::Vector3f sensor = scan[i];
      if (!sensor.allFinite()) {
        ++stats.skipped_nonfinite;
        continue;
      }
      // world - anchor, rounded once to float: exactly what to_stored() gives
      const Eigen::Vector3d world = rotation * sensor.cast<double>() + pose.translation();
      const std::array<float, 3> p{float(world[0] - anchor[0]), float(world[1] - anchor[1]),
                                   float(world[2] - anchor[2])};
      if (!box.contains(p[0], p[1], p[2]) || (previous && previous->contains(p[0], p[1], p[2]))) {
        ++stats.skipped_by_policy;
        continue;
      }
      take(p);
    }
  }
};

}  // namespace eco::detail
