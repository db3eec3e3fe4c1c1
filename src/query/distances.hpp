#pragma once
// Squared distances from a query to a leaf's points, in vector code (core/vector_clones.hpp): the
// KNN search's inner loop. The same bits as (dx^2 + dy^2) + dz^2 one point at a time.

#include <array>
#include <cstddef>

namespace eco::detail {

/// out[i] = |(x[i], y[i], z[i]) - q|^2 for i < n.
void squared_distances(const float* x, const float* y, const float* z, std::size_t n, const std::array<double, 3>& q,
                       double* out);

}  // namespace eco::detail
