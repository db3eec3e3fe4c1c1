#pragma once
// atan2 in degrees, fast and with a known error bound: free-space clearing looks up a pixel for
// every return and every held point in range, and its two arctangents were most of that lookup.
// Callers take the formulas again wherever a decision lies within kFastAtan2Error of a wall.

#include <array>
#include <cmath>

namespace eco::detail {

/// [deg] fast_atan2_degrees' error bound, with room: the interpolation's is below 1.2e-6 degrees
/// (tests/core/range_image_test.cpp measures it).
inline constexpr double kFastAtan2Error = 1e-5;

/// atan(i / kAtanIntervals) in degrees for i = 0 .. kAtanIntervals: a linear interpolation
/// between them is within h^2/8 * max|atan''| = 2e-8 rad of atan on [0, 1] (h = 1/2048).
inline constexpr int kAtanIntervals = 2048;
inline constexpr double kDegreesPerRadian = 57.295779513082320876798;
inline const std::array<double, kAtanIntervals + 1> kAtanDegrees = [] {
  std::array<double, kAtanIntervals + 1> table{};
  for (int i = 0; i <= kAtanIntervals; ++i) table[i] = std::atan(double(i) / kAtanIntervals) * kDegreesPerRadian;
  return table;
}();

/// atan2(y, x) in degrees for (x, y) != (0, 0), within kFastAtan2Error: atan of the smaller over
/// the larger of |x|, |y| from the table, then the octant's symmetries (signed zeros as atan2's).
inline double fast_atan2_degrees(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double u = std::min(ax, ay) / std::max(ax, ay) * kAtanIntervals;  // in [0, kAtanIntervals]
  const int i = std::min(int(u), kAtanIntervals - 1);
  double a = kAtanDegrees[i] + (u - i) * (kAtanDegrees[i + 1] - kAtanDegrees[i]);
  if (ay > ax) a = 90.0 - a;
  if (x < 0.0) a = 180.0 - a;
  return std::signbit(y) ? -a : a;
}

}  // namespace eco::detail
