#include "clearing/pixel_lookup.hpp"

#include <algorithm>
#include <limits>
#include <span>

#include "core/geometry/vector_clones.hpp"
#include "clearing/fast_atan2.hpp"

namespace eco::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The pseudo-angle of the direction at `degrees` of azimuth (a wall's).
double pseudo_angle_at(double degrees) {
  return PixelLookup::pseudo_angle(std::cos(degrees * kPi / 180.0), std::sin(degrees * kPi / 180.0));
}

/// The greatest s whose square root rounds to `max` or below (a square root correctly rounded
/// rises with its argument): sqrt(s) > max exactly when s > it.
double largest_square_within(double max) {
  if (!(max < std::numeric_limits<double>::infinity())) return max;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  double s = max * max;
  while (s > 0.0 && std::sqrt(s) > max) s = std::nextafter(s, 0.0);
  while (std::sqrt(std::nextafter(s, kInfinity)) <= max) s = std::nextafter(s, kInfinity);
  return s;
}

/// Fills `start`: for its bins, equal from walls.front() (`per_unit` to a unit), the last wall at
/// or below each bin's lower end (never the last two: the one closing the range and the sentinel).
void fill_starts(std::span<const double> walls, std::span<double> start, double per_unit) {
  std::size_t i = 0;
  for (std::size_t b = 0; b < start.size(); ++b) {
    const double lower = walls.front() + double(b) / per_unit;
    while (i + 3 < walls.size() && walls[i + 1] <= lower) ++i;
    start[b] = double(i);
  }
}

/// The row bins' density, for `bins` equal bins between the first row wall and the field of view's
/// top (row_walls[rows]): computed alike where the tables are built and where they are found.
double row_bins_per_unit(std::size_t bins, const double* row_walls, int rows) {
  return double(bins) / (row_walls[rows] - row_walls[0]);
}

/// The tables' layout: the sensor model they were built for, then the row walls (rows + 2: the
/// field of view's top and +infinity close them), the column walls (columns + 2: 4, the seam, and
/// +infinity), the column bins' starts (4 a column), the row bins' starts (to the end).
constexpr std::size_t kHeader = 5;
std::array<double, kHeader> header_of(const SensorModel& s) {
  return {s.vertical_fov_min, s.vertical_fov_max, s.vertical_resolution, s.horizontal_resolution, s.max_range};
}

/// Builds the tables for `sensor` (rows and columns of it) in `tables`.
void build_tables(const SensorModel& sensor, int rows, int columns, std::vector<double>& tables) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const std::array<double, kHeader> header = header_of(sensor);
  tables.assign(header.begin(), header.end());
  for (int r = 0; r < rows; ++r) {
    tables.push_back(std::sin((sensor.vertical_fov_min + r * sensor.vertical_resolution) * kPi / 180.0));
  }
  const double fov_top = std::sin(sensor.vertical_fov_max * kPi / 180.0);
  tables.insert(tables.end(), {fov_top, kInfinity});
  const std::size_t column_walls = tables.size();
  for (int c = 0; c < columns; ++c) tables.push_back(pseudo_angle_at(-180.0 + c * sensor.horizontal_resolution));
  tables[column_walls] = 0.0;  // -180 deg, whatever sin(-pi) rounds to
  tables.insert(tables.end(), {4.0, kInfinity});
  // Bins narrower than the narrowest pixel hold one wall at most. A column spans at least half its
  // width in radians of pseudo-angle (the slope is 1/2 to 1), so 4 bins a column suffice; a row's
  // sine span shrinks with cos(elevation): the bins follow its narrowest row, within bounds.
  double narrowest = kInfinity;  // of the whole rows (the top one may be a sliver)
  for (int r = 0; r + 1 < rows; ++r) narrowest = std::min(narrowest, tables[kHeader + r + 1] - tables[kHeader + r]);
  const double span = fov_top - tables[kHeader];
  const double wanted = std::ceil(2.0 * span / std::max(narrowest, 1e-300));
  const std::size_t column_start = tables.size(), column_bins = 4 * std::size_t(columns);
  const std::size_t row_start = column_start + column_bins;
  tables.resize(row_start + std::size_t(std::clamp(wanted, 4.0 * rows, 16.0 * rows + 16.0)));
  const std::span<const double> row_walls(tables.data() + kHeader, std::size_t(rows) + 2);
  const std::span<const double> columns_walls(tables.data() + column_walls, std::size_t(columns) + 2);
  fill_starts(columns_walls, std::span(tables.data() + column_start, column_bins), double(columns));
  const std::span<double> row_starts(tables.data() + row_start, tables.size() - row_start);
  fill_starts(row_walls, row_starts, row_bins_per_unit(row_starts.size(), row_walls.data(), rows));
}

}  // namespace

/// Tier 1 for a whole group (every lane; those past its size are ignored): each point's pixel,
/// kOutside, or kUndecided, in vector code (core/geometry/vector_clones.hpp; |v| rounded as Eigen's norm()
/// rounds it: (x^2 + y^2) + z^2). Every comparison is false for NaN (a point straight up or down,
/// or the origin), which leaves it undecided.
template <PixelLookup::Reach kReach>
[[gnu::always_inline]] inline void PixelLookup::first_tier_lanes(const Group& points, const FirstTierWalls& w,
                                                                 std::array<std::uint32_t, kGroup>& pixels,
                                                                 std::array<double, kGroup>& reaches) {
  for (std::size_t i = 0; i < kGroup; ++i) {
    const double dx = points.x[i], dy = points.y[i], dz = points.z[i];
    const double squared = (dx * dx + dy * dy) + dz * dz;
    reaches[i] = kReach == Reach::Range ? std::sqrt(squared) : squared;
    const float x = float(dx), y = float(dy), z = float(dz);
    const float elevation = fast_atan2_degrees(z, std::sqrt(x * x + y * y)), azimuth = fast_atan2_degrees(y, x);
    // rows and columns counted from the field of view's bottom and from -180 deg, held where an
    // int32 holds them (outside, or NaN, they become 0 or 2^30, which no test below lets through)
    const auto count = [](float value) { return std::min(0x1p30f, std::max(0.0f, value)); };  // NaN: 0
    const float r = count((elevation - w.fov_min) * w.per_row), c = count((azimuth + 180.0f) * w.per_column);
    const std::int32_t row = std::int32_t(r), column = std::int32_t(c);
    const float r_part = r - float(row), c_part = c - float(column);
    const std::uint32_t decided = (elevation >= w.low) & (elevation <= w.high) & (r_part >= w.row_guard) &
                         (r_part <= w.row_room) & (c >= w.column_guard) & (c <= w.seam) & (c_part >= w.column_guard) &
                         (c_part <= w.column_room);
    const std::uint32_t outside = (squared > w.max_squared_range) | (elevation < w.below) | (elevation > w.above);
    const std::uint32_t pixel = std::uint32_t(row) * w.columns + std::uint32_t(column);
    // kOutside where outside (all ones), else the pixel where decided, else kUndecided
    pixels[i] = (0u - outside) | ((0u - decided) & pixel) | ((decided - 1u) & kUndecided);
  }
}

ECO_WIDE_VECTOR_CLONES
void PixelLookup::first_tier(const Group& points, const FirstTierWalls& w, std::array<std::uint32_t, kGroup>& pixels,
                             std::array<double, kGroup>& ranges) {
  first_tier_lanes<Reach::Range>(points, w, pixels, ranges);
}

ECO_WIDE_VECTOR_CLONES
void PixelLookup::first_tier_squared(const Group& points, const FirstTierWalls& w,
                                     std::array<std::uint32_t, kGroup>& pixels, std::array<double, kGroup>& squared) {
  first_tier_lanes<Reach::SquaredRange>(points, w, pixels, squared);
}

/// Tier 2 for a whole group (every lane), in vector code where the compiler manages it.
ECO_VECTOR_CLONES
void PixelLookup::second_tier(const Group& points, const std::array<double, kGroup>& ranges, const SecondTierWalls& walls,
                              std::array<std::uint32_t, kGroup>& pixels) {
  for (std::size_t i = 0; i < kGroup; ++i) pixels[i] = second_tier_lane(walls, points.x[i], points.y[i], points.z[i], ranges[i]);
}

PixelLookup::PixelLookup(const SensorModel& sensor) : PixelLookup(sensor, own_tables_) {}

PixelLookup::PixelLookup(const SensorModel& sensor, std::vector<double>& tables)
    : sensor_(sensor), rows_(sensor.rows()), columns_(sensor.columns()) {
  static_assert(kAngleGuard > 2 * kFastAtan2Error, "tier 1's guard must cover its arctangent's error");
  const std::size_t row_walls = std::size_t(rows_) + 2, column_walls = std::size_t(columns_) + 2;
  const std::size_t column_bins = 4 * std::size_t(columns_);
  const std::size_t row_start = kHeader + row_walls + column_walls + column_bins;
  const std::array<double, kHeader> header = header_of(sensor);
  if (!(tables.size() > row_start && std::equal(header.begin(), header.end(), tables.begin()))) {
    build_tables(sensor, rows_, columns_, tables);
  }
  const double* row_wall = tables.data() + kHeader;
  const double fov_top = row_wall[rows_];
  const std::size_t row_bins = tables.size() - row_start;
  second_ = {{row_wall, tables.data() + row_start, row_bins, row_bins_per_unit(row_bins, row_wall, rows_)},
             {row_wall + row_walls, row_wall + row_walls + column_walls, column_bins, double(columns_)},
             row_wall[0],
             fov_top,
             sensor.max_range,
             std::uint32_t(columns_)};
  const auto f = [](double value) { return float(value); };
  const double min = sensor.vertical_fov_min, max = sensor.vertical_fov_max;
  const double rows_guard = kAngleGuard / sensor.vertical_resolution, columns_guard = kAngleGuard / sensor.horizontal_resolution;
  fast_ = {f(min), f(min + kAngleGuard), f(max - kAngleGuard), f(min - kAngleGuard), f(max + kAngleGuard),
           f(1.0 / sensor.vertical_resolution), f(1.0 / sensor.horizontal_resolution), f(rows_guard), f(1.0 - rows_guard),
           f(columns_guard), f(1.0 - columns_guard), f(360.0 / sensor.horizontal_resolution - columns_guard),
           std::uint32_t(columns_), largest_square_within(sensor.max_range)};
}

void PixelLookup::later_tiers_of(const Group& points, const std::array<double, kGroup>& ranges,
                                 std::array<std::uint32_t, kGroup>& pixels) const {
  second_tier(points, ranges, second_, pixels);
  for (std::size_t i = 0; i < points.size; ++i) {
    if (pixels[i] == kUndecided) pixels[i] = exact_pixel_of({points.x[i], points.y[i], points.z[i]});
  }
}

std::uint32_t PixelLookup::exact_pixel_of(const Eigen::Vector3d& v, double& range) const {
  range = v.norm();
  if (!(range <= sensor_.max_range)) return kOutside;
  const double elevation = std::atan2(v.z(), std::hypot(v.x(), v.y())) * 180.0 / kPi;
  if (elevation < sensor_.vertical_fov_min || elevation >= sensor_.vertical_fov_max) return kOutside;
  const double azimuth = std::atan2(v.y(), v.x()) * 180.0 / kPi;
  const int row = std::min(rows_ - 1, int((elevation - sensor_.vertical_fov_min) / sensor_.vertical_resolution));
  const int column = int((azimuth + 180.0) / sensor_.horizontal_resolution) % columns_;
  return index(row, column);
}

}  // namespace eco::detail
