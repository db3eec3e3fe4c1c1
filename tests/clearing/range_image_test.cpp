// The range image against the rule written out: each pixel's nearest return around it.

#include "clearing/range_image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace eco::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// nearest_around against the rule written out: the minimum range of the returns binned (by
/// exact_pixel_of) into the pixel and its 8 neighbours, columns wrapping around, rows not — or no
/// return when one of those rows got none.
TEST(RangeImage, NearestAroundIsTheMinimumOverThe3x3Neighbourhood) {
  SensorModel sensor;
  sensor.horizontal_resolution = 2.0;  // a small image, densely filled, some pixels empty
  sensor.vertical_resolution = 1.0;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> azimuth(-kPi, kPi), elevation(-26.0, 3.0), range(0.3, 110.0);
  std::vector<float> scan;
  for (int i = 0; i < 3000; ++i) {
    const double a = azimuth(rng), e = elevation(rng) * kPi / 180, r = range(rng);
    scan.insert(scan.end(), {float(r * std::cos(e) * std::cos(a)), float(r * std::cos(e) * std::sin(a)), float(r * std::sin(e))});
    if (i % 500 == 0) {  // returns with a non-finite coordinate bin nowhere
      scan.insert(scan.end(), {std::numeric_limits<float>::quiet_NaN(), 1.0f, 1.0f});
      scan.insert(scan.end(), {1.0f, std::numeric_limits<float>::infinity(), 1.0f});
    }
  }
  std::vector<double> storage;
  const PixelLookup pixels(sensor);
  const RangeImage image(pixels, ScanView(scan.data(), scan.size() / 3), storage);
  const int rows = sensor.rows(), columns = sensor.columns();
  std::vector<double> nearest(std::size_t(rows * columns), RangeImage::kNoReturn);
  for (std::size_t i = 0; i < scan.size(); i += 3) {
    double r = 0.0;
    const std::uint32_t pixel = pixels.exact_pixel_of(Eigen::Vector3d(scan[i], scan[i + 1], scan[i + 2]), r);
    if (pixel != PixelLookup::kOutside) nearest[pixel] = std::min(nearest[pixel], r);
  }
  std::size_t empty = 0, gaps = 0;
  for (int row = 0; row < rows; ++row) {
    for (int column = 0; column < columns; ++column) {
      double expected = RangeImage::kNoReturn;
      bool row_without = false;
      for (int dr = -1; dr <= 1; ++dr) {
        if (row + dr < 0 || row + dr >= rows) continue;
        double in_row = RangeImage::kNoReturn;
        for (int dc = -1; dc <= 1; ++dc) {
          in_row = std::min(in_row, nearest[std::size_t((row + dr) * columns + (column + dc + columns) % columns)]);
        }
        expected = std::min(expected, in_row);
        row_without = row_without || in_row == RangeImage::kNoReturn;
      }
      if (row_without && expected != RangeImage::kNoReturn) {
        expected = RangeImage::kNoReturn;
        gaps += 1;
      }
      ASSERT_EQ(image.nearest_around(std::uint32_t(row * columns + column)), expected) << row << ", " << column;
      empty += expected == RangeImage::kNoReturn ? 1 : 0;
    }
  }
  EXPECT_GT(empty, 0u);  // the edge rows above and below the returns' elevations
  EXPECT_LT(empty, std::size_t(rows * columns) / 2);
  EXPECT_GT(gaps, 0u);  // some neighbourhood had a return but a row without one
}

}  // namespace
}  // namespace eco::detail
