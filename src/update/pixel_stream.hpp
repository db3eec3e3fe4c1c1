#pragma once
// Pixels for many points, each tier of PixelLookup on full groups: tier 1 runs on each group of
// points handed in (each point tagged), and the points it leaves undecided (the simulator casts one
// ray in ten on a column's wall) wait for a group of their own for tiers 2 and 3, instead of
// taking them one by one beside it.

#include "update/pixel_lookup.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace eco::detail {

/// Calls take(tag, pixel, reach) once for every point pushed — its pixel as PixelLookup::pixel_of
/// gives it (or kOutside) and its range |v| (kReach Range) or the square of it (SquaredRange) —
/// not in the order pushed; flush() hands back the last ones.
template <class Take, PixelLookup::Reach kReach = PixelLookup::Reach::Range>
class PixelStream {
 public:
  static constexpr std::size_t kGroup = PixelLookup::kGroup;

  PixelStream(const PixelLookup& lookup, Take take) : lookup_(lookup), take_(std::move(take)) {}

  /// A group of sensor-frame points, lane i tagged tags[i].
  void push_group(const PixelLookup::Group& points, const std::array<std::uint32_t, kGroup>& tags) {
    lookup_.first_tier_of(points, pixels_, reaches_, kReach);
    for (std::size_t i = 0; i < points.size; ++i) {
      if (pixels_[i] != PixelLookup::kUndecided) {
        take_(tags[i], pixels_[i], reaches_[i]);
        continue;
      }
      const std::size_t j = left_.size++;
      left_.x[j] = points.x[i], left_.y[j] = points.y[i], left_.z[j] = points.z[i];
      left_reaches_[j] = reaches_[i];
      left_tags_[j] = tags[i];
      if (left_.size == kGroup) run_left();
    }
  }
  /// Answers the points still waiting.
  void flush() { run_left(); }

 private:
  void run_left() {
    std::array<double, kGroup> ranges = left_reaches_;
    if constexpr (kReach == PixelLookup::Reach::SquaredRange) {
      for (double& r : ranges) r = std::sqrt(r);
    }
    lookup_.later_tiers_of(left_, ranges, left_pixels_);
    for (std::size_t j = 0; j < left_.size; ++j) take_(left_tags_[j], left_pixels_[j], left_reaches_[j]);
    left_.size = 0;
  }

  const PixelLookup& lookup_;
  Take take_;
  std::array<std::uint32_t, kGroup> pixels_{};  // tier 1's answers for the group pushed
  std::array<double, kGroup> reaches_{};
  PixelLookup::Group left_;  // the points tier 1 left, waiting for a group of their own
  std::array<std::uint32_t, kGroup> left_tags_{}, left_pixels_{};
  std::array<double, kGroup> left_reaches_{};
};

}  // namespace eco::detail
