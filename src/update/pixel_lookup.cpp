#include "update/pixel_lookup.hpp"

#include <algorithm>

#include "update/fast_atan2.hpp"

namespace eco::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The pseudo-angle of the direction at `degrees` of azimuth, as pixel_of computes it.
double pseudo_angle(double degrees) {
  const double x = std::cos(degrees * kPi / 180.0), y = std::sin(degrees * kPi / 180.0);
  const double d = y / (std::abs(x) + std::abs(y));
  return x >= 0.0 ? 2.0 + d : (y >= 0.0 ? 4.0 - d : -d);
}

/// For `bins` equal bins from walls.front(), the last wall at or below each bin's lower end (never the
/// last two: the one closing the range and the sentinel).
std::vector<std::uint32_t> starts(const std::vector<double>& walls, std::size_t bins, double per_unit) {
  std::vector<std::uint32_t> start(bins);
  std::uint32_t i = 0;
  for (std::size_t b = 0; b < bins; ++b) {
    const double lower = walls.front() + double(b) / per_unit;
    while (i + 3 < walls.size() && walls[i + 1] <= lower) ++i;
    start[b] = i;
  }
  return start;
}

}  // namespace

PixelLookup::PixelLookup(const SensorModel& sensor)
    : sensor_(sensor), rows_(sensor.rows()), columns_(sensor.columns()) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  for (int r = 0; r < rows_; ++r) {
    row_walls_.push_back(std::sin((sensor.vertical_fov_min + r * sensor.vertical_resolution) * kPi / 180.0));
  }
  fov_top_ = std::sin(sensor.vertical_fov_max * kPi / 180.0);
  row_walls_.insert(row_walls_.end(), {fov_top_, kInfinity});
  for (int c = 0; c < columns_; ++c) column_walls_.push_back(pseudo_angle(-180.0 + c * sensor.horizontal_resolution));
  column_walls_.front() = 0.0;  // -180 deg, whatever sin(-pi) rounds to
  column_walls_.insert(column_walls_.end(), {4.0, kInfinity});
  // Bins narrower than the narrowest pixel hold one wall at most. A column spans at least half its
  // width in radians of pseudo-angle (the slope is 1/2 to 1), so 4 bins a column suffice; a row's
  // sine span shrinks with cos(elevation): the bins follow its narrowest row, within bounds.
  column_bins_per_unit_ = double(columns_);
  column_start_ = starts(column_walls_, 4 * std::size_t(columns_), column_bins_per_unit_);
  double narrowest = kInfinity;  // of the whole rows (the top one may be a sliver)
  for (int r = 0; r + 1 < rows_; ++r) narrowest = std::min(narrowest, row_walls_[r + 1] - row_walls_[r]);
  const double span = fov_top_ - row_walls_.front();
  const double wanted = std::ceil(2.0 * span / std::max(narrowest, 1e-300));
  const std::size_t row_bins = std::size_t(std::clamp(wanted, 4.0 * rows_, 16.0 * rows_ + 16.0));
  row_bins_per_unit_ = double(row_bins) / span;
  row_start_ = starts(row_walls_, row_bins, row_bins_per_unit_);
}

void PixelLookup::pixels_of(const Group& points, std::array<std::uint32_t, kGroup>& pixels,
                            std::array<double, kGroup>& ranges) const {
  std::uint32_t decided = 0, outside = 0;  // bit i: tier 1 found point i's row and column / saw it outside the field of view
  alignas(16) std::array<std::int32_t, kGroup> row{}, column{};
#if defined(__SSE2__)
  const auto set = [](double value) { return _mm_set1_ps(float(value)); };
  const auto floats = [](const double* p) {
    return _mm_movelh_ps(_mm_cvtpd_ps(_mm_load_pd(p)), _mm_cvtpd_ps(_mm_load_pd(p + 2)));
  };
  const SensorModel& s = sensor_;
  const __m128 fov_min = set(s.vertical_fov_min), low = set(s.vertical_fov_min + kAngleGuard),
               high = set(s.vertical_fov_max - kAngleGuard), below = set(s.vertical_fov_min - kAngleGuard),
               above = set(s.vertical_fov_max + kAngleGuard);
  const __m128 per_row = set(1.0 / s.vertical_resolution), per_column = set(1.0 / s.horizontal_resolution);
  const __m128 row_guard = set(kAngleGuard / s.vertical_resolution), column_guard = set(kAngleGuard / s.horizontal_resolution);
  const __m128 row_room = set(1.0 - kAngleGuard / s.vertical_resolution),
               column_room = set(1.0 - kAngleGuard / s.horizontal_resolution);
  const __m128 seam = set(360.0 / s.horizontal_resolution - kAngleGuard / s.horizontal_resolution);
  for (std::size_t i = 0; i < points.size; i += 4) {  // lanes past the size are ignored
    for (std::size_t pair = i; pair < i + 4; pair += 2) {  // |v| in double, as Eigen's norm(): (x^2 + y^2) + z^2
      const __m128d x = _mm_load_pd(&points.x[pair]), y = _mm_load_pd(&points.y[pair]), z = _mm_load_pd(&points.z[pair]);
      _mm_storeu_pd(&ranges[pair], _mm_sqrt_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(x, x), _mm_mul_pd(y, y)), _mm_mul_pd(z, z))));
    }
    const __m128 x = floats(&points.x[i]), y = floats(&points.y[i]), z = floats(&points.z[i]);
    const __m128 elevation = fast_atan2_degrees(z, _mm_sqrt_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y))));
    const __m128 azimuth = fast_atan2_degrees(y, x);
    const __m128 r = _mm_mul_ps(_mm_sub_ps(elevation, fov_min), per_row);
    const __m128 c = _mm_mul_ps(_mm_add_ps(azimuth, _mm_set1_ps(180.0f)), per_column);
    const __m128i r_whole = _mm_cvttps_epi32(r), c_whole = _mm_cvttps_epi32(c);
    const __m128 r_part = _mm_sub_ps(r, _mm_cvtepi32_ps(r_whole)), c_part = _mm_sub_ps(c, _mm_cvtepi32_ps(c_whole));
    // every comparison false for NaN (straight up or down): those lanes are left undecided
    const __m128 in_rows = _mm_and_ps(_mm_and_ps(_mm_cmpge_ps(elevation, low), _mm_cmple_ps(elevation, high)),
                                      _mm_and_ps(_mm_cmpge_ps(r_part, row_guard), _mm_cmple_ps(r_part, row_room)));
    const __m128 in_columns = _mm_and_ps(_mm_and_ps(_mm_cmpge_ps(c, column_guard), _mm_cmple_ps(c, seam)),
                                         _mm_and_ps(_mm_cmpge_ps(c_part, column_guard), _mm_cmple_ps(c_part, column_room)));
    decided |= std::uint32_t(_mm_movemask_ps(_mm_and_ps(in_rows, in_columns))) << i;
    outside |= std::uint32_t(_mm_movemask_ps(_mm_or_ps(_mm_cmplt_ps(elevation, below), _mm_cmpgt_ps(elevation, above)))) << i;
    _mm_store_si128(reinterpret_cast<__m128i*>(&row[i]), r_whole);
    _mm_store_si128(reinterpret_cast<__m128i*>(&column[i]), c_whole);
  }
#else
  for (std::size_t i = 0; i < points.size; ++i) ranges[i] = Eigen::Vector3d(points.x[i], points.y[i], points.z[i]).norm();
#endif
  for (std::size_t i = 0; i < points.size; ++i) {
    if (!(ranges[i] <= sensor_.max_range) || (outside >> i & 1u) != 0) {
      pixels[i] = kOutside;
    } else if ((decided >> i & 1u) != 0) {
      pixels[i] = index(row[i], column[i]);
    } else {
      double range = 0.0;
      pixels[i] = pixel_of({points.x[i], points.y[i], points.z[i]}, range);
    }
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
