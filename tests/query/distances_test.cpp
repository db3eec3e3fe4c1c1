// squared_distances, the KNN search's inner loop in vector code, against the scalar formula
// (dx^2 + dy^2) + dz^2 bit for bit, and its verdicts against the scalar comparison with the bound,
// for every count up to one call's, with queries near and far from the points; the bound on the
// k-th distance the search takes from eight groups' minima, and the points at or below it.

#include "query/distances.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

TEST(SquaredDistances, AreTheScalarFormulasBitsAndSayWhichLieBelowTheBound) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> coordinate(-30.0f, 30.0f);
  std::uniform_real_distribution<double> query(-1e4, 1e4);
  for (std::size_t n = 0; n <= kMaxDistances; ++n) {
    std::vector<float> x(n), y(n), z(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = coordinate(rng), y[i] = coordinate(rng), z[i] = coordinate(rng);
    for (const double scale : {1e-3, 1.0}) {
      const std::array<double, 3> q{scale * query(rng), scale * query(rng), scale * query(rng)};
      std::vector<double> expected(n);
      for (std::size_t i = 0; i < n; ++i) {
        const double dx = double(x[i]) - q[0], dy = double(y[i]) - q[1], dz = double(z[i]) - q[2];
        expected[i] = (dx * dx + dy * dy) + dz * dz;
      }
      // bounds: none passes, all pass, and each point's own distance (strictly below: not itself)
      std::vector<double> bounds{0.0, std::numeric_limits<double>::infinity()};
      if (n > 0) bounds.push_back(expected[n / 2]);
      for (const double bound : bounds) {
        std::vector<double> out(n + 1, -1.0);
        const std::uint64_t below = squared_distances(x.data(), y.data(), z.data(), n, q, bound, out.data());
        for (std::size_t i = 0; i < n; ++i) {
          ASSERT_EQ(out[i], expected[i]) << n << " points, point " << i;
          ASSERT_EQ(below >> i & 1u, expected[i] < bound ? 1u : 0u) << n << " points, point " << i << ", bound " << bound;
        }
        EXPECT_EQ(n == 64 ? 0 : below >> n, 0u) << "bits past the points";
        EXPECT_EQ(out[n], -1.0) << "wrote past the end";
      }
    }
  }
}

TEST(KthGroupMinimum, IsTheKthOfTheGroupsMinimaAndBoundsTheKthDistance) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> distance(0.0, 4.0);
  std::uniform_int_distribution<int> tie(0, 3);
  for (std::size_t n = kGroups; n <= kMaxDistances; ++n) {
    for (int round = 0; round < 4; ++round) {
      std::vector<double> d2(n);
      for (double& d : d2) d = round == 0 ? double(tie(rng)) : distance(rng);  // round 0: many ties
      std::vector<double> minima(kGroups, std::numeric_limits<double>::infinity());
      for (std::size_t i = 0; i < n; ++i) minima[i % kGroups] = std::min(minima[i % kGroups], d2[i]);
      std::sort(minima.begin(), minima.end());
      std::vector<double> all = d2;
      std::sort(all.begin(), all.end());
      for (std::size_t k = 1; k <= kGroups; ++k) {
        const double bound = kth_group_minimum(d2.data(), n, k);
        ASSERT_EQ(bound, minima[k - 1]) << n << " distances, k = " << k;
        ASSERT_GE(bound, all[k - 1]) << n << " distances, k = " << k;
        // the points at or below it are the k nearest and perhaps more, never fewer
        const std::uint64_t kept = at_most(d2.data(), n, bound);
        std::size_t count = 0;
        for (std::size_t i = 0; i < n; ++i) {
          ASSERT_EQ(kept >> i & 1u, d2[i] <= bound ? 1u : 0u) << n << " distances, point " << i;
          count += d2[i] <= bound;
        }
        ASSERT_GE(count, k);
        EXPECT_EQ(n == 64 ? 0 : kept >> n, 0u) << "bits past the distances";
      }
    }
  }
}

}  // namespace
}  // namespace eco::detail
