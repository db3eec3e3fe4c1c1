#pragma once
// The pixel of a sensor-frame point in the sensor's range image (SensorModel's formulas), exactly
// as the formulas give it and much faster: free-space clearing looks one up for every return and
// every held point in range. Three tiers, each deciding only where its error cannot matter:
//
// 1. Groups of points in vector code (core/geometry/vector_clones.hpp: four lanes with SSE2, eight with
//    AVX2, sixteen with AVX-512, whose clone made the update with clearing 6-8 % faster), in
//    single precision: elevation and azimuth by a polynomial arctangent
//    (src/clearing/fast_atan2.hpp), row and column by truncation, wherever both angles lie farther
//    than kAngleGuard from every wall.
// 2. In double, without arctangents, for the points tier 1 leaves (PixelStream gathers them into
//    groups of their own) or one point: the elevation replaced by its sine, z / |v|, and
//    the azimuth by a pseudo-angle that rises with it, 0 at -180 deg through 1, 2, 3 at -90, 0,
//    90 deg to 4 at 180 deg (y / (|x| + |y|), shifted by quadrant). Each wall is mapped into these
//    once; a coarse table gives the wall just below a value and one comparison the next. Both maps
//    have slope at most 1 per radian, so a value farther than kGuard from every wall lies on the
//    formulas' side of each.
// 3. The formulas themselves, with libm's atan2 (exact_pixel_of).

#include <eco/config.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace eco::detail {

class PixelLookup {
 public:
  /// No pixel: the point lies outside the vertical field of view or beyond max_range.
  static constexpr std::uint32_t kOutside = std::numeric_limits<std::uint32_t>::max();

  explicit PixelLookup(const SensorModel& sensor);
  /// The same, its walls and bins built in `tables` — or found there, built for the same sensor by
  /// an earlier lookup: the caller keeps them between frames, so that no frame computes them again
  /// (a few thousand sines and cosines) — and read there while it lives.
  PixelLookup(const SensorModel& sensor, std::vector<double>& tables);
  PixelLookup(const PixelLookup&) = delete;  // its walls point into its tables
  PixelLookup& operator=(const PixelLookup&) = delete;

  /// The pixel (row * columns + column) of the sensor-frame point `v`, or kOutside; `range` gets
  /// |v|. Exactly exact_pixel_of(), faster (tier 2, then 3).
  [[nodiscard]] std::uint32_t pixel_of(const Eigen::Vector3d& v, double& range) const {
    range = v.norm();
    const std::uint32_t pixel = second_tier_lane(second_, v.x(), v.y(), v.z(), range);
    return pixel == kUndecided ? exact_pixel_of(v) : pixel;
  }

  /// Tier 2's stand-in for the azimuth of (x, y) != (0, 0): in [0, 4], rising with it.
  [[nodiscard]] static double pseudo_angle(double x, double y) {
    const double d = y / (std::abs(x) + std::abs(y));  // in [-1, 1], rising with the angle in each half-plane
    return x >= 0.0 ? 2.0 + d : (y >= 0.0 ? 4.0 - d : -d);
  }

  /// Points whose pixels are looked up together (PixelStream's): enough that the calls through the
  /// clones' dispatch are few, few enough to stay in registers and the first cache level.
  static constexpr std::size_t kGroup = 32;
  struct Group {
    std::size_t size = 0;  // at most kGroup
    alignas(16) std::array<double, kGroup> x{}, y{}, z{};
  };
  /// Tier 1's verdict on a point it leaves to tiers 2 and 3 (no pixel has this index: kMaxPixels).
  static constexpr std::uint32_t kUndecided = kOutside - 1;
  /// What tier 1 hands back with each pixel: the range |v|, or its square (as rounded before the
  /// square root), for a caller that can compare it without the root.
  enum class Reach { Range, SquaredRange };
  /// PixelStream's parts. Tier 1 for a group: each point's pixel, kOutside, or kUndecided, and its
  /// reach (all of them).
  void first_tier_of(const Group& points, std::array<std::uint32_t, kGroup>& pixels, std::array<double, kGroup>& reaches,
                     Reach reach) const {
    if (reach == Reach::Range) return first_tier(points, fast_, pixels, reaches);
    first_tier_squared(points, fast_, pixels, reaches);
  }
  /// Tiers 2 and 3 for a group whose points' ranges are `ranges`: each point's pixel or kOutside.
  void later_tiers_of(const Group& points, const std::array<double, kGroup>& ranges,
                      std::array<std::uint32_t, kGroup>& pixels) const;

  /// The pixel by the formulas themselves, with libm's atan2; `range` gets |v|.
  [[nodiscard]] std::uint32_t exact_pixel_of(const Eigen::Vector3d& v, double& range) const;
  [[nodiscard]] std::uint32_t exact_pixel_of(const Eigen::Vector3d& v) const {
    double range = 0.0;
    return exact_pixel_of(v, range);
  }

  [[nodiscard]] int rows() const { return rows_; }
  [[nodiscard]] int columns() const { return columns_; }
  [[nodiscard]] std::uint32_t index(int row, int column) const {
    return std::uint32_t(row) * std::uint32_t(columns_) + std::uint32_t(column);
  }

 private:
  /// [deg] How far tier 1's angles must lie from a wall: above their error (fast_atan2's, and the
  /// rounding of the rows' and columns' arithmetic in single precision, below 2e-5 deg more),
  /// far below a pixel (HDL-64E: 0.42 x 0.2 deg). The test passes at 5e-5 and fails at 2e-5.
  static constexpr double kAngleGuard = 2e-4;

  /// How far tier 2's values must lie from a wall: above their error and the walls' (each a few
  /// units of 1e-16) and the formulas' (atan2 within an ulp, the degrees' arithmetic within
  /// 3e-14 deg: below 1e-15 rad), far below a pixel (HDL-64E: 7e-3 of sine, 2e-3 of
  /// pseudo-angle). The test passes at 1e-14 and fails at 0.
  static constexpr double kGuard = 1e-12;

  /// Tier 2's walls: of the rows, sin(elevation) of each row's lower wall, then of the field of
  /// view's top, then +infinity; of the columns, the pseudo-angle of each column's left wall, then 4
  /// (the seam at 180 deg), then +infinity. A coarse table of equal bins from the first wall gives,
  /// per bin, the wall at or below its lower end.
  struct Walls {
    const double* at = nullptr;
    const double* start = nullptr;  // whole numbers: GCC 12 vectorises a gather of doubles here, not of integers
    std::size_t bins = 0;
    double bins_per_unit = 0.0;
  };
  struct SecondTierWalls {
    Walls rows, columns;
    double fov_bottom = 0.0, fov_top = 0.0;  // sin(vertical_fov_min), sin(vertical_fov_max)
    double max_range = 0.0;
    std::uint32_t column_count = 0;
  };

  /// The i with walls[i] <= value < walls[i + 1] by the table's guess and one comparison; `clear`
  /// becomes 1 when the value lies kGuard or more inside them, 0 when not (near a wall, NaN, or the
  /// guess off by more than one wall: a bin holding two). `bin` is the value's position in the
  /// table's bins (clamped to them).
  [[gnu::always_inline]] static std::int32_t between(const Walls& walls, double bin, double value, std::uint32_t& clear) {
    const std::int32_t b = std::int32_t(std::min(double(walls.bins - 1), std::max(0.0, bin)));  // NaN: 0
    const std::int32_t i = std::int32_t(walls.start[b]);  // exact; at most the third wall from the end
    const double below = walls.at[i], next = walls.at[i + 1], after = walls.at[i + 2];  // loaded together
    const bool up = value >= next;
    const double lower = up ? next : below, upper = up ? after : next;
    clear = std::uint32_t(value - lower >= kGuard) & std::uint32_t(upper - value > kGuard);
    return i + std::int32_t(up);
  }
  /// Tier 2 for the point (x, y, z) with |v| = range: its pixel, kOutside, or kUndecided (left to
  /// the formulas: straight up or down, the origin, NaN, or within kGuard of a wall). Without
  /// branches, for the compiler to vectorise later_tiers_of's loop (GCC 12 does so with flags as
  /// integers, not when a flag is read back from a selected value).
  [[gnu::always_inline]] static std::uint32_t second_tier_lane(const SecondTierWalls& w, double x, double y, double z,
                                                               double range) {
    const double sine = z / range;
    const double pseudo = pseudo_angle(x, y);
    std::uint32_t row_clear = 0, column_clear = 0;
    const std::int32_t row = between(w.rows, (sine - w.fov_bottom) * w.rows.bins_per_unit, sine, row_clear);
    const std::int32_t column = between(w.columns, pseudo * w.columns.bins_per_unit, pseudo, column_clear);
    const std::uint32_t within_range = std::uint32_t(range <= w.max_range);
    const std::uint32_t off_axis = std::uint32_t(x != 0.0) | std::uint32_t(y != 0.0);
    const std::uint32_t inside = std::uint32_t(sine >= w.fov_bottom + kGuard) & std::uint32_t(sine <= w.fov_top - kGuard);
    const std::uint32_t outside = std::uint32_t(sine < w.fov_bottom - kGuard) | std::uint32_t(sine > w.fov_top + kGuard);
    const std::uint32_t pixel = std::uint32_t(row) * w.column_count + std::uint32_t(column);
    const std::uint32_t decided = inside & row_clear & column_clear;
    // the formulas' order: beyond the range; on the axis; outside or at the field of view's edges; a wall
    const std::uint32_t answer = decided != 0 ? pixel : outside != 0 ? kOutside : kUndecided;
    return within_range == 0 ? kOutside : off_axis == 0 ? kUndecided : answer;
  }
  static void second_tier(const Group& points, const std::array<double, kGroup>& ranges, const SecondTierWalls& walls,
                          std::array<std::uint32_t, kGroup>& pixels);

  /// Tier 1's walls and guards in single precision [deg, and rows or columns].
  struct FirstTierWalls {
    float fov_min, low, high, below, above;  // the field of view's bottom, and it and its top with the guard inside and outside
    float per_row, per_column;
    float row_guard, row_room, column_guard, column_room;  // the guard in rows and columns, and 1 - it
    float seam;                                            // 360 deg in columns, less the guard
    std::uint32_t columns;
    double max_squared_range;  // the greatest |v|^2 whose root rounds to max_range or below
  };
  /// Static, its walls handed in: a member's fields could alias the outputs for all the compiler
  /// knows, and it would not vectorise the loop. The same lanes (first_tier_lanes), handing back
  /// ranges or their squares.
  static void first_tier(const Group& points, const FirstTierWalls& walls, std::array<std::uint32_t, kGroup>& pixels,
                         std::array<double, kGroup>& ranges);
  static void first_tier_squared(const Group& points, const FirstTierWalls& walls,
                                 std::array<std::uint32_t, kGroup>& pixels, std::array<double, kGroup>& squared);
  template <Reach kReach>
  static void first_tier_lanes(const Group& points, const FirstTierWalls& walls,
                               std::array<std::uint32_t, kGroup>& pixels, std::array<double, kGroup>& reaches);

  SensorModel sensor_;
  FirstTierWalls fast_{};
  int rows_ = 0, columns_ = 0;
  std::vector<double> own_tables_;  // the tables, unless the caller keeps them
  SecondTierWalls second_;          // in the tables
};

}  // namespace eco::detail
