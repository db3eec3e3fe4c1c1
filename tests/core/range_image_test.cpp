// The range image's fast pixel lookup against the formulas themselves: the table's atan2 stays
// within its stated error, and pixel_of() answers exactly as exact_pixel_of() for points anywhere,
// on pixel walls, on the field of view's edges, straight up and down, and beyond the range.

#include "update/range_image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace eco::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(RangeImage, FastAtan2StaysWithinItsStatedError) {
  double worst = 0.0;
  for (int i = 0; i <= 2000000; ++i) {  // every octant, densely
    const double angle = -kPi + 2.0 * kPi * i / 2000000.0;
    for (const double r : {1e-3, 1.0, 150.0}) {
      const double x = r * std::cos(angle), y = r * std::sin(angle);
      worst = std::max(worst, std::abs(fast_atan2_degrees(y, x) - std::atan2(y, x) * 180.0 / kPi));
    }
  }
  EXPECT_LT(worst, 1.2e-6);
  EXPECT_LT(worst, kFastAtan2Error / 5);
  EXPECT_EQ(fast_atan2_degrees(0.0, -1.0), 180.0);
  EXPECT_EQ(fast_atan2_degrees(-0.0, -1.0), -180.0);
}

/// Sensor-frame points on the walls of `sensor`'s pixels and field of view, and near them.
std::vector<Eigen::Vector3d> on_walls(const SensorModel& sensor, std::mt19937& rng) {
  std::uniform_real_distribution<double> range(0.5, 1.2 * sensor.max_range);
  std::uniform_int_distribution<int> column(0, sensor.columns());
  std::uniform_int_distribution<int> row(-1, sensor.rows() + 1);
  std::uniform_real_distribution<double> nudge(-3e-5, 3e-5);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < 200000; ++i) {
    const double azimuth = (-180.0 + column(rng) * sensor.horizontal_resolution + (i % 3 ? nudge(rng) : 0.0)) * kPi / 180;
    double elevation = sensor.vertical_fov_min + row(rng) * sensor.vertical_resolution + (i % 5 ? nudge(rng) : 0.0);
    if (i % 7 == 0) elevation = i % 2 ? sensor.vertical_fov_max : sensor.vertical_fov_min;
    elevation *= kPi / 180;
    const double r = range(rng);
    out.emplace_back(r * std::cos(elevation) * std::cos(azimuth), r * std::cos(elevation) * std::sin(azimuth),
                     r * std::sin(elevation));
  }
  return out;
}

TEST(RangeImage, FastPixelsAreTheFormulasPixels) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-120.0, 120.0);
  SensorModel odd;  // columns that do not divide the circle, uneven rows
  odd.horizontal_resolution = 0.7;
  odd.vertical_resolution = 1.3;
  odd.vertical_fov_min = -15.0;
  odd.vertical_fov_max = 15.0;
  for (const SensorModel& sensor : {SensorModel{}, odd}) {
    std::vector<double> storage;
    const RangeImage image(sensor, ScanView(), storage);
    std::vector<Eigen::Vector3d> points = on_walls(sensor, rng);
    for (int i = 0; i < 200000; ++i) points.emplace_back(u(rng), u(rng), 0.2 * u(rng));
    for (const Eigen::Vector3d& v : {Eigen::Vector3d(0, 0, 5), Eigen::Vector3d(0, 0, -5), Eigen::Vector3d(0, 0, 0),
                                     Eigen::Vector3d(-3, 0, -0.5), Eigen::Vector3d(-3, -0.0, -0.5)}) {
      points.push_back(v);
    }
    std::size_t inside = 0;
    for (const Eigen::Vector3d& v : points) {
      double fast_range = -1.0, exact_range = -2.0;
      const std::uint32_t fast = image.pixel_of(v, fast_range);
      const std::uint32_t exact = image.exact_pixel_of(v, exact_range);
      ASSERT_EQ(fast, exact) << v.transpose();  // the same row and column, or both outside
      ASSERT_EQ(fast_range, exact_range);
      inside += fast != RangeImage::kOutside ? 1 : 0;
    }
    EXPECT_GT(inside, points.size() / 4);
  }
}

/// A very narrow field of view cut into very fine rows: a point below or above it lies billions of
/// rows away, more than an int holds; the lookup still answers as the formulas do.
TEST(RangeImage, PointsFarOutsideANarrowFieldOfViewAreOutside) {
  SensorModel narrow;
  narrow.vertical_fov_min = 1.0;
  narrow.vertical_fov_max = 1.001;
  narrow.vertical_resolution = 1e-9;  // 1e6 rows: -90 deg is 9.1e10 rows below
  narrow.horizontal_resolution = 360.0;
  std::vector<double> storage;
  const RangeImage image(narrow, ScanView(), storage);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  std::size_t inside = 0;
  for (int i = 0; i < 20000; ++i) {
    Eigen::Vector3d v(u(rng), u(rng), u(rng));
    if (i % 4 == 0) v.z() = std::tan(1.0005 * kPi / 180) * std::hypot(v.x(), v.y());  // inside
    double fast_range = -1.0, exact_range = -2.0;
    const std::uint32_t fast = image.pixel_of(v, fast_range);
    ASSERT_EQ(fast, image.exact_pixel_of(v, exact_range)) << v.transpose();
    ASSERT_EQ(fast_range, exact_range);
    inside += fast != RangeImage::kOutside ? 1 : 0;
  }
  EXPECT_GT(inside, 1000u);
}

/// nearest_around against the rule written out: the minimum range of the returns binned (by
/// exact_pixel_of) into the pixel and its 8 neighbours, columns wrapping around, rows not.
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
  }
  std::vector<double> storage;
  const RangeImage image(sensor, ScanView(scan.data(), scan.size() / 3), storage);
  const int rows = sensor.rows(), columns = sensor.columns();
  std::vector<double> nearest(std::size_t(rows * columns), RangeImage::kNoReturn);
  for (std::size_t i = 0; i < scan.size(); i += 3) {
    double r = 0.0;
    const std::uint32_t pixel = image.exact_pixel_of(Eigen::Vector3d(scan[i], scan[i + 1], scan[i + 2]), r);
    if (pixel != RangeImage::kOutside) nearest[pixel] = std::min(nearest[pixel], r);
  }
  std::size_t empty = 0;
  for (int row = 0; row < rows; ++row) {
    for (int column = 0; column < columns; ++column) {
      double expected = RangeImage::kNoReturn;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if (row + dr < 0 || row + dr >= rows) continue;
          expected = std::min(expected, nearest[std::size_t((row + dr) * columns + (column + dc + columns) % columns)]);
        }
      }
      ASSERT_EQ(image.nearest_around(std::uint32_t(row * columns + column)), expected) << row << ", " << column;
      empty += expected == RangeImage::kNoReturn ? 1 : 0;
    }
  }
  EXPECT_GT(empty, 0u);  // the edge rows above and below the returns' elevations
  EXPECT_LT(empty, std::size_t(rows * columns) / 2);
}

}  // namespace
}  // namespace eco::detail
