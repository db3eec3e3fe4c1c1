// The clearing judge's screen (SeenThrough::screen, vector code) against its rule lane by lane:
// it flags every point the rule sees through and every one tier 1 left undecided, rules out the
// others save those within rounding of the rule's line, and flags no lane past the group's size.

#include "clearing/scan_judge.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace eco::detail {
namespace {

TEST(SeenThrough, ScreenFlagsWhatTheRuleMaySeeThroughAndRulesOutTheRest) {
  SensorModel sensor;  // a small image: 10 columns, 5 rows
  sensor.horizontal_resolution = 36.0;
  sensor.vertical_resolution = 6.0;
  const PixelLookup lookup(sensor);
  const std::size_t pixels_in_image = std::size_t(sensor.rows() * sensor.columns());
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> range(0.0, 100.0), unit(0.0, 1.0);
  std::uniform_int_distribution<std::uint32_t> pixel(0, std::uint32_t(pixels_in_image) - 1);
  std::uniform_int_distribution<int> steps(-40, 40);
  std::size_t seen_lanes = 0, ruled_out = 0, near_line = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<double> storage(pixels_in_image);
    for (double& nearest : storage) {  // some pixels without a return, some within the margin
      nearest = unit(rng) < 0.1 ? RangeImage::kNoReturn : unit(rng) < 0.1 ? 0.3 * unit(rng) : range(rng);
    }
    const double margin = trial % 3 == 0 ? 0.0 : 0.3;
    const SeenThrough seen(RangeImage(lookup, storage), margin);
    std::array<std::uint32_t, PixelLookup::kGroup> pixels{};
    std::array<double, PixelLookup::kGroup> squared{};
    std::array<bool, PixelLookup::kGroup> on_line{};
    for (std::size_t i = 0; i < PixelLookup::kGroup; ++i) {
      const double u = unit(rng);
      pixels[i] = u < 0.08 ? PixelLookup::kOutside : u < 0.16 ? PixelLookup::kUndecided : pixel(rng);
      const double nearest = pixels[i] < pixels_in_image ? storage[pixels[i]] : 50.0;
      squared[i] = range(rng) * range(rng);
      on_line[i] = unit(rng) < 0.3 && std::isfinite(nearest) && nearest > margin;
      if (on_line[i]) {  // the line itself, then doubles either side
        squared[i] = (nearest - margin) * (nearest - margin);
        for (int k = steps(rng); k != 0; k += k > 0 ? -1 : 1) squared[i] = std::nextafter(squared[i], k > 0 ? 1e300 : 0.0);
      }
    }
    const std::size_t size = 1 + std::size_t(trial) % PixelLookup::kGroup;
    const std::uint32_t lanes = seen.screen(pixels, squared, size);
    for (std::size_t i = 0; i < PixelLookup::kGroup; ++i) {
      const bool flagged = (lanes >> i & 1u) != 0;
      if (i >= size) {
        ASSERT_FALSE(flagged) << i;
        continue;
      }
      const bool undecided = pixels[i] == PixelLookup::kUndecided;
      const bool through = !undecided && seen(pixels[i], squared[i]);
      if (undecided || through) {
        ASSERT_TRUE(flagged) << trial << " lane " << i;
      }
      if (!on_line[i]) {
        ASSERT_EQ(flagged, undecided || through) << trial << " lane " << i << " " << squared[i];
      }
      seen_lanes += through ? 1 : 0;
      ruled_out += !flagged ? 1 : 0;
      near_line += on_line[i] ? 1 : 0;
    }
  }
  EXPECT_GT(seen_lanes, 5000u);
  EXPECT_GT(ruled_out, 10000u);
  EXPECT_GT(near_line, 5000u);
}

}  // namespace
}  // namespace eco::detail
