// squared_distances, the KNN search's inner loop in vector code, against the scalar formula
// (dx^2 + dy^2) + dz^2 bit for bit, for every count up to a leaf's and beyond, with queries near
// and far from the points.

#include "query/distances.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace eco::detail {
namespace {

TEST(SquaredDistances, AreTheScalarFormulasBits) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> coordinate(-30.0f, 30.0f);
  std::uniform_real_distribution<double> query(-1e4, 1e4);
  for (std::size_t n = 0; n <= 70; ++n) {
    std::vector<float> x(n), y(n), z(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = coordinate(rng), y[i] = coordinate(rng), z[i] = coordinate(rng);
    for (const double scale : {1e-3, 1.0}) {
      const std::array<double, 3> q{scale * query(rng), scale * query(rng), scale * query(rng)};
      std::vector<double> out(n + 1, -1.0);
      squared_distances(x.data(), y.data(), z.data(), n, q, out.data());
      for (std::size_t i = 0; i < n; ++i) {
        const double dx = double(x[i]) - q[0], dy = double(y[i]) - q[1], dz = double(z[i]) - q[2];
        ASSERT_EQ(out[i], (dx * dx + dy * dy) + dz * dz) << n << " points, point " << i;
      }
      EXPECT_EQ(out[n], -1.0) << "wrote past the end";
    }
  }
}

}  // namespace
}  // namespace eco::detail
