#pragma once
// The scan as free-space clearing sees it: its returns binned into the sensor's range image
// (SensorModel, include/eco/config.hpp), each pixel knowing the nearest return around it.

#include <eco/types.hpp>

#include "clearing/pixel_lookup.hpp"

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace eco::detail {

/// For every pixel, the nearest return of a scan among that pixel and its 8 neighbours (columns
/// wrap around the circle, rows stop at the image's edge); infinity where some row of those (one
/// in the image) got none. Pixels are named by PixelLookup's indices.
class RangeImage {
 public:
  static constexpr double kNoReturn = std::numeric_limits<double>::infinity();

  /// Bins every finite return of `scan` (sensor frame) that `pixels` places in the image, in
  /// `storage` (resized to an image and three rows; the caller keeps it between frames, so that
  /// no frame pays for fresh pages, and while this image is read).
  RangeImage(const PixelLookup& pixels, ScanView scan, std::vector<double>& storage);
  /// The image an earlier RangeImage binned into `storage`, for the same `pixels`.
  RangeImage(const PixelLookup& pixels, const std::vector<double>& storage)
      : around_(storage.data(), std::size_t(pixels.rows()) * std::size_t(pixels.columns())) {}

  /// The nearest return around `pixel` (not kOutside) [m]; kNoReturn when a row around it got none.
  [[nodiscard]] double nearest_around(std::uint32_t pixel) const { return around_[pixel]; }
  /// Every pixel's nearest_around, by index.
  [[nodiscard]] std::span<const double> image() const { return around_; }

 private:
  std::span<const double> around_;  // in the caller's storage
};

}  // namespace eco::detail
