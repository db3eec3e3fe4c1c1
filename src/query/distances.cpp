#include "query/distances.hpp"

#include "core/geometry/set_flags.hpp"
#include "core/geometry/vector_clones.hpp"

#include <algorithm>
#include <cassert>

namespace eco::detail {

ECO_VECTOR_CLONES
std::uint64_t squared_distances(const float* x, const float* y, const float* z, std::size_t n,
                                const std::array<double, 3>& q, double bound, double* out) {
  assert(n <= kMaxDistances);
  const double qx = q[0], qy = q[1], qz = q[2];  // copies: `out` could alias q for all the compiler knows
  std::uint8_t below[kMaxDistances] = {};        // flags past n stay 0
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = double(x[i]) - qx, dy = double(y[i]) - qy, dz = double(z[i]) - qz;
    const double d2 = dx * dx + dy * dy + dz * dz;
    out[i] = d2;
    below[i] = std::uint8_t(d2 < bound);
  }
  return flags_as_bits(below, n);
}

ECO_VECTOR_CLONES
double kth_group_minimum(const double* d2, std::size_t n, std::size_t k) {
  assert(1 <= k && k <= kGroups && kGroups <= n);
  static_assert(kGroups == 8, "the sorting network below sorts eight");
  std::array<double, kGroups> minima;
  std::copy(d2, d2 + kGroups, minima.begin());
  std::size_t i = kGroups;
  for (; i + kGroups <= n; i += kGroups) {
    for (std::size_t g = 0; g < kGroups; ++g) minima[g] = std::min(minima[g], d2[i + g]);
  }
  for (std::size_t g = 0; i + g < n; ++g) minima[g] = std::min(minima[g], d2[i + g]);
  // sorted by a network of 19 compare-exchanges (min and max: no branch to mispredict)
  constexpr std::array<std::array<std::uint8_t, 2>, 19> kNetwork{{{0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6},
                                                                 {3, 7}, {0, 1}, {2, 3}, {4, 5}, {6, 7}, {2, 4}, {3, 5},
                                                                 {1, 4}, {3, 6}, {1, 2}, {3, 4}, {5, 6}}};
  for (const auto& [a, b] : kNetwork) {
    const double low = std::min(minima[a], minima[b]), high = std::max(minima[a], minima[b]);
    minima[a] = low;
    minima[b] = high;
  }
  return minima[k - 1];
}

ECO_VECTOR_CLONES
std::uint64_t at_most(const double* d2, std::size_t n, double bound) {
  assert(n <= kMaxDistances);
  std::uint8_t flags[kMaxDistances] = {};
  for (std::size_t i = 0; i < n; ++i) flags[i] = std::uint8_t(d2[i] <= bound);
  return flags_as_bits(flags, n);
}

}  // namespace eco::detail
