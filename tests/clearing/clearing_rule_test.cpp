// lies_beyond against the clearing rule's comparison written out (nearest > sqrt(squared) +
// margin in double): at random, and at every double around the line where the answer flips; and
// its screen, may_lie_beyond, never 0 where the rule holds.

#include "clearing/clearing_rule.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace eco::detail {
namespace {

bool as_written(double nearest, double squared, double margin) { return nearest > std::sqrt(squared) + margin; }

TEST(ClearingRule, LiesBeyondIsTheRuleAsWrittenEvenWhereRoundingDecides) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> range(0.0, 150.0), margin(0.01, 5.0), unit(0.0, 1.0);
  std::uniform_int_distribution<int> steps(-60, 60);
  std::size_t beyond = 0, near_line = 0, ruled_out = 0;
  for (int i = 0; i < 200000; ++i) {
    const double m = i % 7 == 0 ? 0.01 : margin(rng);
    double nearest = range(rng);
    if (i % 5 == 0) nearest = m + unit(rng) * 1e-6;  // room for a sliver only
    if (i % 11 == 0) nearest = std::nextafter(m, 1e9);
    // the line itself: the squared range whose root is nearest - margin, then doubles either side
    double squared = (nearest - m) * (nearest - m);
    for (int k = steps(rng); k != 0; k += k > 0 ? -1 : 1) squared = std::nextafter(squared, k > 0 ? 1e300 : 0.0);
    if (i % 3 == 0) squared = range(rng) * range(rng);  // anywhere
    ASSERT_EQ(lies_beyond(nearest, squared, m), as_written(nearest, squared, m))
        << std::hexfloat << nearest << " " << squared << " " << m;
    if (as_written(nearest, squared, m)) {
      ASSERT_EQ(may_lie_beyond(nearest, squared, m), 1u) << std::hexfloat << nearest << " " << squared << " " << m;
    }
    const double root = std::sqrt(squared);
    if (root + m > nearest * (1.0 + 1e-6)) {  // well short of the line: the screen rules it out
      ASSERT_EQ(may_lie_beyond(nearest, squared, m), 0u) << nearest << " " << squared << " " << m;
      ++ruled_out;
    }
    beyond += as_written(nearest, squared, m) ? 1 : 0;
    near_line += std::abs(root + m - nearest) < 1e-12 * nearest ? 1 : 0;
  }
  EXPECT_GT(beyond, 20000u);
  EXPECT_GT(ruled_out, 20000u);
  EXPECT_GT(near_line, 20000u);  // the cases rounding decides were reached
  constexpr double kInf = std::numeric_limits<double>::infinity(), kNaN = std::numeric_limits<double>::quiet_NaN();
  for (const double nearest : {0.0, 0.01, 0.3, 0.30000000000000004, 1.0, 80.0, kInf}) {
    for (const double squared : {0.0, 1e-300, 0.49, 1.0, 6400.0, 1e300, kInf, kNaN}) {
      for (const double m : {0.01, 0.3, 1e5}) {
        EXPECT_EQ(lies_beyond(nearest, squared, m), as_written(nearest, squared, m))
            << nearest << " " << squared << " " << m;
        if (as_written(nearest, squared, m)) {
          EXPECT_EQ(may_lie_beyond(nearest, squared, m), 1u) << nearest << " " << squared;
        }
      }
    }
  }
}

}  // namespace
}  // namespace eco::detail
