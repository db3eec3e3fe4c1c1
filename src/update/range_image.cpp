#include "update/range_image.hpp"

#include <algorithm>

namespace eco::detail {

RangeImage::RangeImage(const SensorModel& sensor, ScanView scan, std::vector<double>& storage)
    : sensor_(sensor),
      rows_(sensor.rows()),
      columns_(sensor.columns()),
      row_guard_(2.0 * kFastAtan2Error / sensor.vertical_resolution + 1e-9),
      column_guard_(2.0 * kFastAtan2Error / sensor.horizontal_resolution + 1e-9),
      top_row_((sensor.vertical_fov_max - sensor.vertical_fov_min) / sensor.vertical_resolution),
      per_row_(1.0 / sensor.vertical_resolution),
      per_column_(1.0 / sensor.horizontal_resolution) {
  const std::size_t pixels = std::size_t(rows_) * std::size_t(columns_);
  storage.resize(2 * pixels);
  const std::span<double> nearest(storage.data(), pixels);  // becomes the 3x3 minimum at the end
  const std::span<double> across(storage.data() + pixels, pixels);
  std::fill(nearest.begin(), nearest.end(), kNoReturn);
  for (std::size_t i = 0; i < scan.count; ++i) {
    const float* p = scan.data + i * scan.stride;
    const Eigen::Vector3d v(p[0], p[1], p[2]);
    if (!v.allFinite()) continue;
    double range = 0.0;
    if (const std::uint32_t pixel = pixel_of(v, range); pixel != kOutside) {
      nearest[pixel] = std::min(nearest[pixel], range);
    }
  }
  // The minimum over 3x3 neighbourhoods, separably: along each row (wrapping), then across rows.
  for (int r = 0; r < rows_; ++r) {
    for (int c = 0; c < columns_; ++c) {
      const int left = c == 0 ? columns_ - 1 : c - 1;
      const int right = c + 1 == columns_ ? 0 : c + 1;
      across[index(r, c)] = std::min({nearest[index(r, left)], nearest[index(r, c)], nearest[index(r, right)]});
    }
  }
  for (int r = 0; r < rows_; ++r) {
    for (int c = 0; c < columns_; ++c) {
      double m = across[index(r, c)];
      if (r > 0) m = std::min(m, across[index(r - 1, c)]);
      if (r + 1 < rows_) m = std::min(m, across[index(r + 1, c)]);
      nearest[index(r, c)] = m;
    }
  }
  around_ = nearest;
}

}  // namespace eco::detail
