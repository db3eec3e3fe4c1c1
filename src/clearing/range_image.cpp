#include "clearing/range_image.hpp"

#include "core/geometry/vector_clones.hpp"
#include "clearing/pixel_stream.hpp"
#include "clearing/sensor_frame.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace eco::detail {
namespace {

/// The minimum of each pixel of `row` and its two neighbours along it, the row wrapping around.
[[gnu::always_inline]] inline void minimum_along(const double* row, std::size_t n, double* out) {
  const auto at = [&](std::size_t c, int step) { return row[(c + n + std::size_t(step)) % n]; };
  out[0] = std::min({at(0, -1), row[0], at(0, 1)});
  for (std::size_t c = 1; c + 1 < n; ++c) out[c] = std::min(row[c - 1], std::min(row[c], row[c + 1]));
  if (n > 1) out[n - 1] = std::min({row[n - 2], row[n - 1], at(n - 1, 1)});
}

/// Each of a row's pixels (`n`, into `out`) from its column's minima along three rows: the nearest
/// of them, or kNoReturn where one of them got none. At the image's edge the missing row is the
/// middle one again (`above` or `below` == `here`), which changes neither.
[[gnu::always_inline]] inline void minimum_across(const double* above, const double* here, const double* below,
                                                  std::size_t n, double* out) {
  for (std::size_t c = 0; c < n; ++c) {
    const double m = std::min(above[c], std::min(here[c], below[c]));
    const double farthest = std::max(above[c], std::max(here[c], below[c]));
    out[c] = farthest == RangeImage::kNoReturn ? RangeImage::kNoReturn : m;
  }
}

/// The minimum over 3x3 neighbourhoods of the `rows` x `columns` image `nearest`, separably and in
/// place, in `three_rows` (3 x columns) of room: the minima along three rows are kept (the row's,
/// the one above's, the one below's), each computed before its row is overwritten by the minimum
/// across them. A neighbourhood with a row that got no return is no evidence (kNoReturn): a gap
/// between beams is not a ray that passed. In vector code: the image is read and written whole.
ECO_WIDE_VECTOR_CLONES
void minimum_around(double* nearest, std::size_t rows, std::size_t columns, double* three_rows) {
  double *above = three_rows, *here = above + columns, *below = here + columns;
  minimum_along(nearest, columns, here);
  for (std::size_t r = 0; r < rows; ++r) {
    if (r + 1 < rows) minimum_along(nearest + (r + 1) * columns, columns, below);
    minimum_across(r > 0 ? above : here, here, r + 1 < rows ? below : here, columns, nearest + r * columns);
    std::swap(above, here);  // the rows move up: here becomes above, below becomes here
    std::swap(here, below);
  }
}

/// Every pixel of `image` set to kNoReturn (vector stores: the image is ~1 MB).
ECO_WIDE_VECTOR_CLONES
void clear_image(double* image, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i) image[i] = RangeImage::kNoReturn;
}

}  // namespace

RangeImage::RangeImage(const PixelLookup& pixels, ScanView scan, std::vector<double>& storage) {
  const std::size_t rows = std::size_t(pixels.rows()), columns = std::size_t(pixels.columns());
  const std::size_t size = rows * columns;
  storage.resize(size + 3 * columns);
  const std::span<double> nearest(storage.data(), size);  // becomes the 3x3 minimum at the end
  clear_image(nearest.data(), size);
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
  minimum_around(nearest.data(), rows, columns, storage.data() + size);
  around_ = nearest;
}

}  // namespace eco::detail
