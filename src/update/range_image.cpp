#include "update/range_image.hpp"

#include "update/pixel_stream.hpp"
#include "update/sensor_frame.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace eco::detail {
namespace {

/// The minimum of each pixel of `row` and its two neighbours along it, the row wrapping around.
void minimum_along(std::span<const double> row, std::span<double> out) {
  const std::size_t n = row.size();
  const auto at = [&](std::size_t c, int step) { return row[(c + n + std::size_t(step)) % n]; };
  out[0] = std::min({at(0, -1), row[0], at(0, 1)});
  for (std::size_t c = 1; c + 1 < n; ++c) out[c] = std::min(row[c - 1], std::min(row[c], row[c + 1]));
  if (n > 1) out[n - 1] = std::min({row[n - 2], row[n - 1], at(n - 1, 1)});
}

}  // namespace

RangeImage::RangeImage(const PixelLookup& pixels, ScanView scan, std::vector<double>& storage) {
  const std::size_t rows = std::size_t(pixels.rows()), columns = std::size_t(pixels.columns());
  const std::size_t size = rows * columns;
  storage.resize(size + 3 * columns);
  const std::span<double> nearest(storage.data(), size);  // becomes the 3x3 minimum at the end
  std::fill(nearest.begin(), nearest.end(), kNoReturn);
  PixelStream stream(pixels, [&](std::uint32_t, std::uint32_t pixel, double range) {
    if (pixel != PixelLookup::kOutside) nearest[pixel] = std::min(nearest[pixel], range);
  });
  PixelLookup::Group group;
  for (std::size_t begin = 0; begin < scan.count; begin += PixelLookup::kGroup) {
    // a return with a non-finite coordinate has no pixel
    load_returns(scan.data + begin * scan.stride, scan.stride, std::min(PixelLookup::kGroup, scan.count - begin), group);
    stream.push_group(group);
  }
  stream.flush();
  // The minimum over 3x3 neighbourhoods, separably and in place: three rows' minima along them
  // are kept (the row's, the one above's, the one below's), each computed before its row is
  // overwritten by the minimum across them. A neighbourhood with a row that got no return is no
  // evidence (kNoReturn): a gap between beams is not a ray that passed.
  const auto row = [&](std::size_t r) { return nearest.subspan(r * columns, columns); };
  std::span<double> above(storage.data() + size, columns), here(above.data() + columns, columns),
      below(here.data() + columns, columns);
  minimum_along(row(0), here);
  for (std::size_t r = 0; r < rows; ++r) {
    if (r + 1 < rows) minimum_along(row(r + 1), below);
    const std::span<double> out = row(r);
    for (std::size_t c = 0; c < columns; ++c) {
      double m = here[c], farthest = here[c];  // the rows' nearest returns, and the largest of them
      if (r > 0) m = std::min(m, above[c]), farthest = std::max(farthest, above[c]);
      if (r + 1 < rows) m = std::min(m, below[c]), farthest = std::max(farthest, below[c]);
      out[c] = farthest == kNoReturn ? kNoReturn : m;
    }
    std::swap(above, here);  // the rows move up: here becomes above, below becomes here
    std::swap(here, below);
  }
  around_ = nearest;
}

}  // namespace eco::detail
