#pragma once
// Which scan points an update takes in (the contract, include/eco/ego_octree.hpp): finite, inside
// Box(p_t) and the region (Config::region), and — under ShiftInOnly — outside the previous box.
// Shared by ECO's shift-in stage and the baselines, so every method of the benchmark takes in the
// same points.

#include "core/geometry/geometry.hpp"
#include "core/geometry/motion.hpp"

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace eco::detail {

/// Scan points judged together by admit_group: its loops run in vector code over them.
inline constexpr std::size_t kAdmitGroup = 64;

/// A Box as the stored floats it holds: lo <= p <= hi in float is exactly Box::contains(p) for
/// every float p (lo the least float not below the box's lo, hi the greatest float it holds). The
/// default holds nothing.
struct FloatBox {
  std::array<float, 3> lo{1, 1, 1}, hi{0, 0, 0};
  static FloatBox of(const Box& b);
  [[nodiscard]] bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
};

/// What admit_group needs of a frame, as plain numbers.
struct AdmissionFrame {
  std::array<std::array<double, 3>, 3> rotation{};  // world_R_sensor, by rows
  std::array<double, 3> translation{};              // the sensor's world position
  std::array<double, 3> anchor{};                   // the precision origin
  FloatBox box;                                     // Box(p_t), anchor frame
  FloatBox previous;                                // Box(p_{t-1}) under ShiftInOnly, else empty
};

/// One group's verdicts: the admitted points' stored coordinates and scan indices, in scan
/// order, and how many were refused for what.
struct AdmittedGroup {
  std::array<std::array<float, 3>, kAdmitGroup> points;
  std::array<std::uint32_t, kAdmitGroup> index;
  std::size_t size = 0;
  std::size_t nonfinite = 0;
  std::size_t refused = 0;
};

/// Judges scan points [begin, begin + n) (n <= kAdmitGroup) in vector code
/// (core/geometry/vector_clones.hpp). A point's stored coordinates are exactly the scalar formula's:
/// world = R·s + t in double, summed as Eigen sums a 3×3 product (tests/update/admission_test.cpp),
/// minus the anchor, rounded once to float; it is admitted when they lie in the box and not in
/// the previous one.
void admit_group(const AdmissionFrame& frame, ScanView scan, std::size_t begin, std::size_t n, AdmittedGroup& out);

struct Admission {
  Eigen::Isometry3d pose;    // world_T_sensor
  Eigen::Vector3d anchor;    // the precision origin
  Box box;                   // Box(p_t), anchor frame
  std::optional<Box> previous;  // set under ShiftInOnly once a previous box exists
  std::optional<EgoRegion> region;  // Config::region this frame; none for the cube

  /// Calls take_group(AdmittedGroup&) for each group of scan points that admits some, in scan
  /// order (the group may be changed: it is the caller's until the next call); counts the
  /// refused points in `stats`.
  template <class TakeGroup>
  void for_each_group(ScanView scan, UpdateStats& stats, TakeGroup&& take_group) const {
    const AdmissionFrame f = frame();
    AdmittedGroup group;
    for (std::size_t begin = 0; begin < scan.count; begin += kAdmitGroup) {
      admit_group(f, scan, begin, std::min(kAdmitGroup, scan.count - begin), group);
      if (region) keep_in_region(group);
      stats.skipped_nonfinite += group.nonfinite;
      stats.skipped_by_policy += group.refused;
      if (group.size > 0) take_group(group);
    }
  }
  /// Calls take(stored coordinates, scan index) for each admitted scan point, in scan order;
  /// counts the refused ones in `stats`.
  template <class Take>
  void for_each(ScanView scan, UpdateStats& stats, Take&& take) const {
    for_each_group(scan, stats, [&](const AdmittedGroup& group) {
      for (std::size_t j = 0; j < group.size; ++j) take(group.points[j], std::size_t(group.index[j]));
    });
  }

  /// The group's points in the region, in order; the others counted as refused.
  void keep_in_region(AdmittedGroup& group) const {
    std::size_t kept = 0;
    for (std::size_t j = 0; j < group.size; ++j) {
      if (!region->contains(group.points[j])) continue;
      group.points[kept] = group.points[j];
      group.index[kept] = group.index[j];
      ++kept;
    }
    group.refused += group.size - kept;
    group.size = kept;
  }

  [[nodiscard]] AdmissionFrame frame() const {
    AdmissionFrame f;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) f.rotation[std::size_t(r)][std::size_t(c)] = pose.linear()(r, c);
      f.translation[std::size_t(r)] = pose.translation()[r];
      f.anchor[std::size_t(r)] = anchor[r];
    }
    f.box = FloatBox::of(box);
    if (previous) f.previous = FloatBox::of(*previous);
    return f;
  }
};

/// The scan points the insert policy admits for `motion`: R_in = Box(p_t) minus Box(p_{t-1})
/// under ShiftInOnly once a previous box exists, all of Box(p_t) otherwise.
inline Admission admission(const Motion& motion, InsertPolicy policy) {
  return {motion.pose, motion.anchor, motion.box,
          policy == InsertPolicy::ShiftInOnly ? motion.previous : std::nullopt, motion.region};
}

}  // namespace eco::detail
