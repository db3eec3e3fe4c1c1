#pragma once
// Squared distances from a query to a leaf's points, in vector code (core/geometry/vector_clones.hpp): the
// KNN search's inner loop. The same bits as (dx^2 + dy^2) + dz^2 one point at a time.

#include <array>
#include <cstddef>
#include <cstdint>

namespace eco::detail {

/// Points measured by one call: their verdicts are one word's bits.
inline constexpr std::size_t kMaxDistances = 64;

/// out[i] = |(x[i], y[i], z[i]) - q|^2 for i < n (n <= kMaxDistances); returns bit i set where
/// out[i] < bound, so that the search visits only the points that may enter its results.
std::uint64_t squared_distances(const float* x, const float* y, const float* z, std::size_t n,
                                const std::array<double, 3>& q, double bound, double* out);

/// Groups kth_group_minimum takes its minima from.
inline constexpr std::size_t kGroups = 8;

/// An upper bound on the k-th smallest of d2[0, n) (1 <= k <= kGroups <= n): the k-th smallest of
/// the minima of the groups i mod kGroups, which are the distances of kGroups distinct points.
double kth_group_minimum(const double* d2, std::size_t n, std::size_t k);

/// Bit i set where d2[i] <= bound, for i < n <= kMaxDistances.
std::uint64_t at_most(const double* d2, std::size_t n, double bound);

}  // namespace eco::detail
