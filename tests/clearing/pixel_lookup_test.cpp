// PixelLookup's comparisons against the formulas themselves: pixel_of() answers exactly as
// exact_pixel_of() for points anywhere, on pixel walls and at every distance from them, on the field
// of view's edges, straight up and down, beyond the range, and in single precision as scans come.

#include "clearing/fast_atan2.hpp"
#include "clearing/pixel_lookup.hpp"
#include "clearing/pixel_stream.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace eco::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Equal, or both NaN (the range of a point with a NaN coordinate).
bool same(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

TEST(PixelLookup, FastAtan2StaysWithinItsStatedError) {
  double worst = 0.0;
  for (int i = 0; i <= 2000000; ++i) {  // every octant, densely
    const double angle = -kPi + 2.0 * kPi * i / 2000000.0;
    for (const double r : {1e-3, 1.0, 150.0}) {
      const float x = float(r * std::cos(angle)), y = float(r * std::sin(angle));
      worst = std::max(worst, std::abs(fast_atan2_degrees(y, x) - std::atan2(double(y), double(x)) * 180.0 / kPi));
    }
  }
  EXPECT_LT(worst, 2.5e-5);
  EXPECT_LT(worst, kFastAtan2Error);
  EXPECT_EQ(fast_atan2_degrees(0.0f, -1.0f), 180.0f);
  EXPECT_EQ(fast_atan2_degrees(-0.0f, -1.0f), -180.0f);
  EXPECT_EQ(fast_atan2_degrees(1.0f, -0.0f), 90.0f);
  EXPECT_EQ(fast_atan2_degrees(-1.0f, 0.0f), -90.0f);
}

/// Sensor-frame points on the walls of `sensor`'s pixels and field of view, and at every distance
/// from them (1e-14 to 1e-3 degrees either side), in double and rounded to float as scans come.
std::vector<Eigen::Vector3d> on_walls(const SensorModel& sensor, std::mt19937& rng) {
  std::uniform_real_distribution<double> range(0.5, 1.2 * sensor.max_range), exponent(-14.0, -3.0);
  std::uniform_int_distribution<int> column(0, sensor.columns());
  std::uniform_int_distribution<int> row(-1, sensor.rows() + 1);
  const auto nudge = [&] { return (rng() % 2 ? 1.0 : -1.0) * std::pow(10.0, exponent(rng)); };
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < 200000; ++i) {
    const double azimuth = (-180.0 + column(rng) * sensor.horizontal_resolution + (i % 3 ? nudge() : 0.0)) * kPi / 180;
    double elevation = sensor.vertical_fov_min + row(rng) * sensor.vertical_resolution + (i % 5 ? nudge() : 0.0);
    if (i % 7 == 0) elevation = (i % 2 ? sensor.vertical_fov_max : sensor.vertical_fov_min) + (i % 3 ? nudge() : 0.0);
    elevation = std::clamp(elevation, -90.0, 90.0) * kPi / 180;
    const double r = range(rng);
    const Eigen::Vector3d v(r * std::cos(elevation) * std::cos(azimuth), r * std::cos(elevation) * std::sin(azimuth),
                            r * std::sin(elevation));
    out.push_back(i % 2 ? v : v.cast<float>().cast<double>());
  }
  return out;
}

/// Streamed (tier 1 in groups, the points it leaves in groups of their own; handing back ranges and
/// squared ranges), each point's pixel and reach as pixel_of's one at a time, every point once;
/// with a screen, only the points it does not rule out.
void expect_streamed_as_one_at_a_time(const PixelLookup& lookup, const std::vector<Eigen::Vector3d>& points) {
  const auto stream_all = [&](auto& stream) {
    PixelLookup::Group group;
    for (std::size_t begin = 0; begin < points.size(); begin += group.size) {
      group.size = std::min(points.size() - begin, 1 + begin % PixelLookup::kGroup);  // groups of every size
      for (std::size_t i = 0; i < group.size; ++i) {
        group.x[i] = points[begin + i].x(), group.y[i] = points[begin + i].y(), group.z[i] = points[begin + i].z();
      }
      stream.push_group(group);  // tags its points begin, begin + 1, ...
      if (begin % 1000 < PixelLookup::kGroup) stream.flush();  // waiting groups of every size too
    }
    stream.flush();
  };
  std::vector<std::uint32_t> pixels(points.size(), PixelLookup::kUndecided), squared_pixels = pixels;
  std::vector<double> ranges(points.size(), -1.0), squared = ranges;
  std::size_t taken = 0, squared_taken = 0;
  PixelStream stream(lookup, [&](std::uint32_t tag, std::uint32_t pixel, double range) {
    pixels.at(tag) = pixel;
    ranges.at(tag) = range;
    ++taken;
  });
  const auto take_squared = [&](std::uint32_t tag, std::uint32_t pixel, double reach) {
    squared_pixels.at(tag) = pixel;
    squared.at(tag) = reach;
    ++squared_taken;
  };
  PixelStream<decltype(take_squared), PixelLookup::Reach::SquaredRange> squared_stream(lookup, take_squared);
  // screened: only the points tier 1 leaves undecided or gives an even pixel
  struct EvenPixels {
    [[nodiscard]] std::uint32_t screen(const std::array<std::uint32_t, PixelLookup::kGroup>& pixels,
                                       const std::array<double, PixelLookup::kGroup>&, std::size_t size) const {
      std::uint32_t lanes = 0;
      for (std::size_t i = 0; i < size; ++i) {
        if (pixels[i] == PixelLookup::kUndecided || pixels[i] % 2 == 0) lanes |= 1u << i;
      }
      return lanes;
    }
  };
  std::vector<std::uint32_t> screened_pixels(points.size(), PixelLookup::kUndecided);
  std::vector<int> screened_takes(points.size(), 0);
  const auto take_screened = [&](std::uint32_t tag, std::uint32_t pixel, double) {
    screened_pixels.at(tag) = pixel;
    ++screened_takes.at(tag);
  };
  PixelStream<decltype(take_screened), PixelLookup::Reach::SquaredRange, EvenPixels> screened_stream(lookup, take_screened);
  stream_all(stream);
  stream_all(squared_stream);
  stream_all(screened_stream);
  EXPECT_EQ(taken, points.size());
  EXPECT_EQ(squared_taken, points.size());
  std::size_t screened_out = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // tier 1's own verdict, a point at a time
    PixelLookup::Group one;
    one.size = 1;
    one.x[0] = points[i].x(), one.y[0] = points[i].y(), one.z[0] = points[i].z();
    std::array<std::uint32_t, PixelLookup::kGroup> first{};
    std::array<double, PixelLookup::kGroup> reaches{};
    lookup.first_tier_of(one, first, reaches, PixelLookup::Reach::SquaredRange);
    const bool wanted = first[0] == PixelLookup::kUndecided || first[0] % 2 == 0;
    ASSERT_EQ(screened_takes[i], wanted ? 1 : 0) << points[i].transpose();
    if (wanted) {
      ASSERT_EQ(screened_pixels[i], lookup.exact_pixel_of(points[i])) << points[i].transpose();
    }
    screened_out += wanted ? 0 : 1;
  }
  EXPECT_GT(screened_out, 0u);
  for (std::size_t i = 0; i < points.size(); ++i) {
    double range = 0.0;
    const std::uint32_t exact = lookup.exact_pixel_of(points[i], range);
    ASSERT_EQ(pixels[i], exact) << points[i].transpose();
    ASSERT_EQ(squared_pixels[i], exact) << points[i].transpose();
    ASSERT_TRUE(same(ranges[i], range)) << ranges[i] << " " << range;
    ASSERT_TRUE(same(squared[i], points[i].squaredNorm())) << squared[i] << " " << points[i].squaredNorm();
  }
}

TEST(PixelLookup, FastPixelsAreTheFormulasPixels) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-120.0, 120.0), tiny(-1e-9, 1e-9);
  SensorModel odd;  // columns that do not divide the circle, uneven rows
  odd.horizontal_resolution = 0.7;
  odd.vertical_resolution = 1.3;
  odd.vertical_fov_min = -15.0;
  odd.vertical_fov_max = 15.0;
  SensorModel poles;  // rows narrowing towards both poles; one column
  poles.vertical_fov_min = -90.0;
  poles.vertical_fov_max = 89.95;
  poles.vertical_resolution = 0.1;
  poles.horizontal_resolution = 360.0;
  SensorModel fine;  // a fine image with a sliver of a top row
  fine.vertical_fov_min = -30.0;
  fine.vertical_fov_max = 10.001;
  fine.vertical_resolution = 0.05;
  fine.horizontal_resolution = 0.01;
  for (const SensorModel& sensor : {SensorModel{}, odd, poles, fine}) {
    const PixelLookup lookup(sensor);
    std::vector<Eigen::Vector3d> points = on_walls(sensor, rng);
    for (int i = 0; i < 200000; ++i) points.emplace_back(u(rng), u(rng), (i % 2 ? 0.2 : 1.0) * u(rng));
    for (int i = 0; i < 2000; ++i) points.emplace_back(tiny(rng), tiny(rng), u(rng));  // nearly straight up or down
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN(), kInf = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& v : {Eigen::Vector3d(0, 0, 5), Eigen::Vector3d(0, 0, -5), Eigen::Vector3d(0, 0, 0),
                                     Eigen::Vector3d(-3, 0, -0.5), Eigen::Vector3d(-3, -0.0, -0.5),
                                     Eigen::Vector3d(-0.0, 3, -0.5), Eigen::Vector3d(-0.0, -3, -0.5),
                                     Eigen::Vector3d(kNaN, 1, 1), Eigen::Vector3d(1, 1, kNaN), Eigen::Vector3d(kInf, 1, 1),
                                     Eigen::Vector3d(1, -kInf, 1), Eigen::Vector3d(1, 1, kInf)}) {
      points.push_back(v);  // the last five: no pixel, as the formulas say (their range is not <= max_range)
    }
    std::size_t inside = 0;
    for (const Eigen::Vector3d& v : points) {
      double fast_range = -1.0, exact_range = -2.0;
      const std::uint32_t fast = lookup.pixel_of(v, fast_range);
      const std::uint32_t exact = lookup.exact_pixel_of(v, exact_range);
      ASSERT_EQ(fast, exact) << v.transpose();  // the same row and column, or both outside
      ASSERT_TRUE(same(fast_range, exact_range)) << fast_range << " " << exact_range;
      inside += fast != PixelLookup::kOutside ? 1 : 0;
    }
    EXPECT_GT(inside, points.size() / 4);
    expect_streamed_as_one_at_a_time(lookup, points);
  }
}

/// Points at the sensor's maximum range, to the last double, and either side of it.
TEST(PixelLookup, PointsAtTheMaximumRangeAreInsideOrOutsideAsTheFormulasSay) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> azimuth(-kPi, kPi), elevation(-24.0, 1.0);
  std::uniform_int_distribution<int> steps(-8, 8);
  for (const double max_range : {120.0, 80.3, 1.0 / 3.0}) {
    SensorModel sensor;
    sensor.max_range = max_range;
    const PixelLookup lookup(sensor);
    std::vector<Eigen::Vector3d> points;
    std::size_t inside = 0, outside = 0;
    for (int i = 0; i < 20000; ++i) {
      const double a = azimuth(rng), e = elevation(rng) * kPi / 180;
      Eigen::Vector3d v(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
      v *= max_range / v.norm();
      for (int k = steps(rng); k != 0; k += k > 0 ? -1 : 1) v.x() = std::nextafter(v.x(), k > 0 ? 1e9 : -1e9);
      points.push_back(v);
      (v.norm() > max_range ? outside : inside) += 1;
    }
    EXPECT_GT(inside, 2000u);
    EXPECT_GT(outside, 2000u);
    expect_streamed_as_one_at_a_time(lookup, points);
  }
}

/// Tables kept by the caller between lookups are found again for the same sensor, untouched, and
/// built anew for another; every lookup answers as the formulas do.
TEST(PixelLookup, TablesKeptBetweenLookupsServeTheSensorTheyWereBuiltFor) {
  SensorModel wide, fine;
  wide.horizontal_resolution = 0.7;
  wide.vertical_fov_min = -40.0;
  fine.vertical_resolution = 0.1;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-60.0, 60.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 20000; ++i) points.emplace_back(u(rng), u(rng), 0.3 * u(rng));
  std::vector<double> tables;
  for (const SensorModel* sensor : {&wide, &wide, &fine, &wide}) {
    const PixelLookup lookup(*sensor, tables);
    const PixelLookup fresh(*sensor);
    for (const Eigen::Vector3d& v : points) {
      double range = 0.0, fresh_range = 0.0;
      const std::uint32_t pixel = lookup.pixel_of(v, range);
      ASSERT_EQ(pixel, lookup.exact_pixel_of(v)) << v.transpose();
      ASSERT_EQ(pixel, fresh.pixel_of(v, fresh_range)) << v.transpose();
    }
  }
}

/// A very narrow field of view cut into very fine rows: a point below or above it lies billions of
/// rows away, more than an int holds; the lookup still answers as the formulas do.
TEST(PixelLookup, PointsFarOutsideANarrowFieldOfViewAreOutside) {
  SensorModel narrow;
  narrow.vertical_fov_min = 1.0;
  narrow.vertical_fov_max = 1.001;
  narrow.vertical_resolution = 1e-9;  // 1e6 rows: -90 deg is 9.1e10 rows below
  narrow.horizontal_resolution = 360.0;
  const PixelLookup lookup(narrow);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  std::size_t inside = 0;
  for (int i = 0; i < 20000; ++i) {
    Eigen::Vector3d v(u(rng), u(rng), u(rng));
    if (i % 4 == 0) v.z() = std::tan(1.0005 * kPi / 180) * std::hypot(v.x(), v.y());  // inside
    double fast_range = -1.0, exact_range = -2.0;
    const std::uint32_t fast = lookup.pixel_of(v, fast_range);
    ASSERT_EQ(fast, lookup.exact_pixel_of(v, exact_range)) << v.transpose();
    ASSERT_EQ(fast_range, exact_range);
    inside += fast != PixelLookup::kOutside ? 1 : 0;
  }
  EXPECT_GT(inside, 1000u);
}

}  // namespace
}  // namespace eco::detail
