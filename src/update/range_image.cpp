#include "update/range_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace eco::detail {

RangeImage::RangeImage(const PixelLookup& pixels, ScanView scan, std::vector<double>& storage) {
  const int rows = pixels.rows(), columns = pixels.columns();
  const std::size_t size = std::size_t(rows) * std::size_t(columns);
  storage.resize(2 * size);
  const std::span<double> nearest(storage.data(), size);  // becomes the 3x3 minimum at the end
  const std::span<double> across(storage.data() + size, size);
  std::fill(nearest.begin(), nearest.end(), kNoReturn);
  PixelLookup::Group group;
  std::array<std::uint32_t, PixelLookup::kGroup> pixel;
  std::array<double, PixelLookup::kGroup> range;
  const auto bin = [&] {
    pixels.pixels_of(group, pixel, range);
    for (std::size_t i = 0; i < group.size; ++i) {
      if (pixel[i] != PixelLookup::kOutside) nearest[pixel[i]] = std::min(nearest[pixel[i]], range[i]);
    }
    group.size = 0;
  };
  for (std::size_t i = 0; i < scan.count; ++i) {
    const float* p = scan.data + i * scan.stride;
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) continue;
    group.x[group.size] = p[0], group.y[group.size] = p[1], group.z[group.size] = p[2];
    if (++group.size == PixelLookup::kGroup) bin();
  }
  bin();
  // The minimum over 3x3 neighbourhoods, separably: along each row (wrapping), then across rows.
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      const int left = c == 0 ? columns - 1 : c - 1;
      const int right = c + 1 == columns ? 0 : c + 1;
      across[pixels.index(r, c)] =
          std::min({nearest[pixels.index(r, left)], nearest[pixels.index(r, c)], nearest[pixels.index(r, right)]});
    }
  }
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      double m = across[pixels.index(r, c)];
      if (r > 0) m = std::min(m, across[pixels.index(r - 1, c)]);
      if (r + 1 < rows) m = std::min(m, across[pixels.index(r + 1, c)]);
      nearest[pixels.index(r, c)] = m;
    }
  }
  around_ = nearest;
}

}  // namespace eco::detail
