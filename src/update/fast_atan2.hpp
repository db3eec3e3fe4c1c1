#pragma once
// atan2 in degrees for four single-precision lanes at once (SSE2), with a stated error: the pixel
// lookup's fast tier computes elevation and azimuth with it and decides only farther than its
// error from every wall (src/update/pixel_lookup.hpp).

#if defined(__SSE2__)
#include <emmintrin.h>

namespace eco::detail {

/// [deg] fast_atan2_degrees' error bound on the values it is given: the polynomial's 7.2e-6 and
/// single precision's rounding (tests/core/pixel_lookup_test.cpp measures below 2.5e-5).
inline constexpr double kFastAtan2Error = 3e-5;

/// atan(t) ~ t * P(t^2) on [0, 1] in degrees: a weighted least-squares Chebyshev fit of degree 7
/// in t^2, 1.3e-7 rad (7.2e-6 deg) from atan at worst.
inline __m128 atan_degrees(__m128 t) {
  constexpr float kP[8] = {5.729574606e+01f, -1.909681109e+01f, 1.143114930e+01f, -7.983178629e+00f,
                           5.563121070e+00f, -3.259142418e+00f, 1.293063702e+00f, -2.439551336e-01f};
  // Estrin's scheme: pairs, then pairs of pairs, so that the chain of dependent steps is short
  const __m128 u = _mm_mul_ps(t, t), u2 = _mm_mul_ps(u, u), u4 = _mm_mul_ps(u2, u2);
  const auto pair = [&](int k) { return _mm_add_ps(_mm_set1_ps(kP[k]), _mm_mul_ps(_mm_set1_ps(kP[k + 1]), u)); };
  const __m128 low = _mm_add_ps(pair(0), _mm_mul_ps(pair(2), u2)), high = _mm_add_ps(pair(4), _mm_mul_ps(pair(6), u2));
  return _mm_mul_ps(_mm_add_ps(low, _mm_mul_ps(high, u4)), t);
}

/// atan2(y, x) in degrees, lane by lane, for (x, y) != (0, 0) (NaN there): atan of the smaller over
/// the larger of |x|, |y|, then the octant's symmetries.
inline __m128 fast_atan2_degrees(__m128 y, __m128 x) {
  const __m128 sign = _mm_set1_ps(-0.0f);
  const __m128 ax = _mm_andnot_ps(sign, x), ay = _mm_andnot_ps(sign, y);
  __m128 a = atan_degrees(_mm_div_ps(_mm_min_ps(ax, ay), _mm_max_ps(ax, ay)));
  const auto select = [](__m128 when, __m128 then, __m128 otherwise) {
    return _mm_or_ps(_mm_and_ps(when, then), _mm_andnot_ps(when, otherwise));
  };
  a = select(_mm_cmpgt_ps(ay, ax), _mm_sub_ps(_mm_set1_ps(90.0f), a), a);
  a = select(_mm_cmplt_ps(x, _mm_setzero_ps()), _mm_sub_ps(_mm_set1_ps(180.0f), a), a);
  return _mm_or_ps(a, _mm_and_ps(y, sign));  // the sign of y, as atan2's
}

}  // namespace eco::detail
#endif
