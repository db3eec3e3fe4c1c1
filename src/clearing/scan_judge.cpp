#include "clearing/scan_judge.hpp"

#include "core/geometry/set_flags.hpp"
#include "core/geometry/vector_clones.hpp"

namespace eco::detail {

ECO_WIDE_VECTOR_CLONES
std::uint32_t SeenThrough::screen_group(const double* image, std::uint32_t pixel_count, double margin,
                                        const std::array<std::uint32_t, PixelLookup::kGroup>& pixels,
                                        const std::array<double, PixelLookup::kGroup>& squared, std::size_t size) {
  std::uint8_t flags[PixelLookup::kGroup];
  for (std::size_t i = 0; i < PixelLookup::kGroup; ++i) {
    const std::uint32_t in_image = std::uint32_t(pixels[i] < pixel_count);
    const double nearest = image[in_image != 0 ? pixels[i] : 0];
    const std::uint32_t may = in_image & std::uint32_t(nearest != RangeImage::kNoReturn) &
                              may_lie_beyond(nearest, squared[i], margin);
    const std::uint32_t undecided = std::uint32_t(pixels[i] == PixelLookup::kUndecided);
    flags[i] = std::uint8_t((may | undecided) & std::uint32_t(i < size));
  }
  return std::uint32_t(flags_as_bits(flags, PixelLookup::kGroup));
}

std::uint32_t SeenThrough::screen(const std::array<std::uint32_t, PixelLookup::kGroup>& pixels,
                                  const std::array<double, PixelLookup::kGroup>& squared, std::size_t size) const {
  const std::span<const double> image = image_.image();
  return screen_group(image.data(), std::uint32_t(image.size()), margin_, pixels, squared, size);
}

}  // namespace eco::detail
