#pragma once
// atan2 in degrees in single precision, with a stated error and without branches, so that the
// compiler turns a loop of them into vector code: the pixel lookup's first tier computes
// elevation and azimuth with it and decides only farther than its error from every wall
// (src/clearing/pixel_lookup.hpp).

#include <algorithm>
#include <cmath>

namespace eco::detail {

/// [deg] fast_atan2_degrees' error bound: the polynomial's 7.2e-6 and single precision's rounding
/// (tests/clearing/pixel_lookup_test.cpp measures below 2.5e-5).
inline constexpr double kFastAtan2Error = 3e-5;

/// atan(t) ~ t * P(t^2) on [0, 1] in degrees: a weighted least-squares Chebyshev fit of degree 7
/// in t^2, 1.3e-7 rad (7.2e-6 deg) from atan at worst, evaluated by Estrin's scheme (pairs, then
/// pairs of pairs: a short chain of dependent steps).
inline float atan_degrees(float t) {
  const float u = t * t, u2 = u * u, u4 = u2 * u2;
  const float low = (5.729574606e+01f + -1.909681109e+01f * u) + (1.143114930e+01f + -7.983178629e+00f * u) * u2;
  const float high = (5.563121070e+00f + -3.259142418e+00f * u) + (1.293063702e+00f + -2.439551336e-01f * u) * u2;
  return (low + high * u4) * t;
}

/// atan2(y, x) in degrees for (x, y) != (0, 0) (NaN there): atan of the smaller over the larger of
/// |x|, |y|, then the octant's symmetries.
inline float fast_atan2_degrees(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  float a = atan_degrees(std::min(ax, ay) / std::max(ax, ay));
  a = ay > ax ? 90.0f - a : a;
  a = x < 0.0f ? 180.0f - a : a;
  return std::copysign(a, y);  // the sign of y, as atan2's
}

}  // namespace eco::detail
