#include "update/admission.hpp"

#include "core/geometry/vector_clones.hpp"

#include <cmath>
#include <limits>

namespace eco::detail {

FloatBox FloatBox::of(const Box& b) {
  FloatBox f;
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (std::size_t a = 0; a < 3; ++a) {
    float lo = float(b.lo[a]), hi = float(b.hi[a]);
    if (double(lo) < b.lo[a]) lo = std::nextafter(lo, kInf);
    if (double(hi) > b.hi[a] || (b.half_open && double(hi) == b.hi[a])) hi = std::nextafter(hi, -kInf);
    f.lo[a] = lo;
    f.hi[a] = hi;
  }
  return f;
}

namespace {

/// 1 when lo <= v <= hi on every axis (0 for NaN).
inline std::uint32_t within(const FloatBox& b, float x, float y, float z) {
  return std::uint32_t(x >= b.lo[0]) & std::uint32_t(x <= b.hi[0]) & std::uint32_t(y >= b.lo[1]) &
         std::uint32_t(y <= b.hi[1]) & std::uint32_t(z >= b.lo[2]) & std::uint32_t(z <= b.hi[2]);
}

/// admit_group for points `kStride` floats apart (0: scan.stride, known only at run time), with or
/// without a previous box to leave out (AllInBox has none: its test is not computed); inlined, so
/// that each of admit_group's clones gets its own vector code.
template <std::size_t kStride, bool kPrevious>
[[gnu::always_inline]] inline void admit_lanes(const AdmissionFrame& frame, ScanView scan, std::size_t begin, std::size_t n, AdmittedGroup& out) {
  const std::size_t stride = kStride != 0 ? kStride : scan.stride;
  const float* data = scan.data + begin * stride;
  std::array<std::array<float, kAdmitGroup>, 3> stored;
  std::array<std::uint8_t, kAdmitGroup> admitted;
  std::uint32_t finite = 0, taken = 0;
  const auto& r = frame.rotation;
  for (std::size_t i = 0; i < n; ++i) {
    const float* s = data + i * stride;
    const double x = s[0], y = s[1], z = s[2];
    // Eigen's order for a 3×3 product: the first two rows left to right, the third right first
    const double w0 = (r[0][0] * x + r[0][1] * y) + r[0][2] * z + frame.translation[0];
    const double w1 = (r[1][0] * x + r[1][1] * y) + r[1][2] * z + frame.translation[1];
    const double w2 = r[2][0] * x + (r[2][1] * y + r[2][2] * z) + frame.translation[2];
    const float p0 = float(w0 - frame.anchor[0]), p1 = float(w1 - frame.anchor[1]), p2 = float(w2 - frame.anchor[2]);
    stored[0][i] = p0;
    stored[1][i] = p1;
    stored[2][i] = p2;
    // s - s is 0 for a finite s, NaN otherwise
    const std::uint32_t is_finite =
        std::uint32_t(s[0] - s[0] == 0.0f) & std::uint32_t(s[1] - s[1] == 0.0f) & std::uint32_t(s[2] - s[2] == 0.0f);
    const std::uint32_t fresh = kPrevious ? ~within(frame.previous, p0, p1, p2) & 1u : 1u;
    const std::uint32_t in = is_finite & within(frame.box, p0, p1, p2) & fresh;
    admitted[i] = std::uint8_t(in);
    finite += is_finite;
    taken += in;
  }
  std::size_t size = 0;
  if (taken != 0) {  // far groups take nothing
    for (std::size_t i = 0; i < n; ++i) {  // compacted without branches: a slot is kept when admitted
      out.points[size] = {stored[0][i], stored[1][i], stored[2][i]};
      out.index[size] = std::uint32_t(begin + i);
      size += admitted[i];
    }
  }
  out.size = size;
  out.nonfinite = n - finite;
  out.refused = finite - size;
}

}  // namespace

ECO_WIDE_VECTOR_CLONES
void admit_group(const AdmissionFrame& frame, ScanView scan, std::size_t begin, std::size_t n, AdmittedGroup& out) {
  if (!frame.previous.empty()) {  // a box of positive side holds floats: only "no previous box" is empty
    switch (scan.stride) {
      case 3: return admit_lanes<3, true>(frame, scan, begin, n, out);
      case 4: return admit_lanes<4, true>(frame, scan, begin, n, out);
      default: return admit_lanes<0, true>(frame, scan, begin, n, out);
    }
  }
  switch (scan.stride) {
    case 3: return admit_lanes<3, false>(frame, scan, begin, n, out);
    case 4: return admit_lanes<4, false>(frame, scan, begin, n, out);
    default: return admit_lanes<0, false>(frame, scan, begin, n, out);
  }
}

}  // namespace eco::detail
