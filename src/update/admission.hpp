#pragma once
// Which scan points an update takes in (DESIGN.md §1): finite, inside Box(p_t), and — under
// ShiftInOnly — outside the previous box. Shared by ECO's shift-in stage and the baselines, so
// every method of the benchmark takes in the same points.

#include "core/geometry.hpp"
#include "core/motion.hpp"

#include <eco/config.hpp>
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

  /// Calls take(stored coordinates, scan index) for each admitted scan point; counts the refused
  /// ones in `stats`.
  ///
  /// Most points of a frame are decided by a float test in the ego frame (rotation only), which
  /// is exact for points farther than kMargin from every face of both boxes; the rest take the
  /// exact path: world coordinates in double, rounded once to the stored float, box tests on
  /// those.
  template <class Take>
  void for_each(ScanView scan, UpdateStats& stats, Take&& take) const {
    const Eigen::Matrix3d rotation = pose.linear();
    const Eigen::Matrix3f rotation_f = rotation.cast<float>();
    const Eigen::Vector3d centre = pose.translation() - anchor;  // the sensor, anchor frame
    const QuickBox outside = QuickBox::around(box, centre, -kMargin);  // beyond it: refused
    const QuickBox inside = QuickBox::around(box, centre, kMargin);    // within it: in the box
    const QuickBox seen = previous ? QuickBox::around(*previous, centre, kMargin) : QuickBox{};
    for (std::size_t i = 0; i < scan.count; ++i) {
      const Eigen::Vector3f sensor = scan[i];
      if (!sensor.allFinite()) {
        ++stats.skipped_nonfinite;
        continue;
      }
      const Eigen::Vector3f ego = rotation_f * sensor;
      if (!outside.holds(ego) || (previous && inside.holds(ego) && seen.holds(ego))) {
        ++stats.skipped_by_policy;
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
      take(p, i);
    }
  }

 private:
  /// [m] far beyond the float error of the quick test (points within 120 m: ~1e-5 m) and of
  /// the stored coordinates (within 4 km of the precision origin: ~2.5e-4 m).
  static constexpr double kMargin = 0.01;

  /// A box in the ego frame (world axes, origin at the sensor), shrunk by `margin` per face
  /// (grown when negative); an empty QuickBox holds nothing.
  struct QuickBox {
    std::array<float, 3> lo{1, 1, 1}, hi{0, 0, 0};
    static QuickBox around(const Box& b, const Eigen::Vector3d& centre, double margin) {
      QuickBox q;
      for (int a = 0; a < 3; ++a) {
        q.lo[a] = float(b.lo[a] - centre[a] + margin);
        q.hi[a] = float(b.hi[a] - centre[a] - margin);
      }
      return q;
    }
    [[nodiscard]] bool holds(const Eigen::Vector3f& e) const {
      return e[0] >= lo[0] && e[0] < hi[0] && e[1] >= lo[1] && e[1] < hi[1] && e[2] >= lo[2] && e[2] < hi[2];
    }
  };
};

/// The scan points the insert policy admits for `motion`: R_in = Box(p_t) minus Box(p_{t-1})
/// under ShiftInOnly once a previous box exists, all of Box(p_t) otherwise.
inline Admission admission(const Motion& motion, InsertPolicy policy) {
  return {motion.pose, motion.anchor, motion.box,
          policy == InsertPolicy::ShiftInOnly ? motion.previous : std::nullopt};
}

}  // namespace eco::detail
