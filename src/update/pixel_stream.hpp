#pragma once
// Pixels for many points, each tier of PixelLookup on full groups: points are handed in one at a
// time with a tag; tier 1 runs on each group of kGroup as it fills, and the points it leaves
// (the simulator casts one ray in ten on a column's wall) wait for a group of their own for tiers
// 2 and 3, instead of taking them one by one beside it.

#include "update/pixel_lookup.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

namespace eco::detail {

/// Calls take(tag, pixel, reach) for every point pushed — its pixel as PixelLookup::pixel_of gives
/// it (or kOutside) and its range |v| (kReach Range) or the square of it (SquaredRange) — not in
/// the order pushed; flush() hands back the last ones.
template <class Take, PixelLookup::Reach kReach = PixelLookup::Reach::Range>
class PixelStream {
 public:
  static constexpr std::size_t kGroup = PixelLookup::kGroup;

  PixelStream(const PixelLookup& lookup, Take take) : lookup_(lookup), take_(std::move(take)) {}

  /// The sensor-frame point (x, y, z), named `tag` to take().
  void push(double x, double y, double z, std::uint32_t tag) {
    const std::size_t i = fresh_.size++;
    fresh_.x[i] = x, fresh_.y[i] = y, fresh_.z[i] = z;
    fresh_tags_[i] = tag;
    if (fresh_.size == kGroup) run_fresh();
  }
  /// A group of sensor-frame points at once, lane i named tags[i].
  void push_group(const PixelLookup::Group& points, const std::array<std::uint32_t, kGroup>& tags) {
    run_first_tier(points, tags);
  }
  void flush() {
    run_fresh();
    run_left();
  }

 private:
  void run_fresh() {
    run_first_tier(fresh_, fresh_tags_);
    fresh_.size = 0;
  }
  void run_first_tier(const PixelLookup::Group& points, const std::array<std::uint32_t, kGroup>& tags) {
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
  PixelLookup::Group fresh_, left_;  // points waiting for tier 1, and those it left
  std::array<std::uint32_t, kGroup> fresh_tags_{}, left_tags_{}, pixels_{}, left_pixels_{};
  std::array<double, kGroup> reaches_{}, left_reaches_{};
};

}  // namespace eco::detail
