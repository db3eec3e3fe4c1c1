#include "query/distances.hpp"

#include "core/vector_clones.hpp"

namespace eco::detail {

ECO_VECTOR_CLONES
void squared_distances(const float* x, const float* y, const float* z, std::size_t n, const std::array<double, 3>& q,
                       double* out) {
  const double qx = q[0], qy = q[1], qz = q[2];  // copies: `out` could alias q for all the compiler knows
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = double(x[i]) - qx, dy = double(y[i]) - qy, dz = double(z[i]) - qz;
    out[i] = dx * dx + dy * dy + dz * dz;
  }
}

}  // namespace eco::detail
