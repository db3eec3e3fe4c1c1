#pragma once
// Pixels for many points, each tier of PixelLookup on full groups: tier 1 runs on each group of
// points handed in (each point tagged), and the points it leaves undecided (the simulator casts one
// ray in ten on a column's wall) wait for a group of their own for tiers 2 and 3, instead of
// taking them one by one beside it. A screen may rule out, a group at a time in vector code, the
// points whose pixel and reach the caller has no use for (free-space clearing's judges: most held
// points are not seen through), so that only the others are handed over one by one.

#include "clearing/pixel_lookup.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace eco::detail {

/// A PixelStream's screen that rules out no point.
struct EveryPoint {};

/// Calls take(tag, pixel, reach) once for every point pushed — its pixel as PixelLookup::pixel_of
/// gives it (or kOutside) and its range |v| (kReach Range) or the square of it (SquaredRange) —
/// not in the order pushed; flush() hands back the last ones. A point's tag is its number in the
/// order pushed, from 0: every caller numbers its points so (a leaf's run on from the last leaf's),
/// so no tag is copied per point. With a screen, only for the points it does not rule out:
/// screen.screen(pixels, reaches, size) gives, of a group's lanes [0, size) from tier 1, as bits
/// (lane i on bit i), those left kUndecided and those whose pixel and reach the caller may want.
template <class Take, PixelLookup::Reach kReach = PixelLookup::Reach::Range, class Screen = EveryPoint>
class PixelStream {
 public:
  static constexpr std::size_t kGroup = PixelLookup::kGroup;

  PixelStream(const PixelLookup& lookup, Take take, Screen screen = {})
      : lookup_(lookup), take_(std::move(take)), screen_(std::move(screen)) {}

  /// A group of sensor-frame points, the next points.size of them.
  void push_group(const PixelLookup::Group& points) {
    lookup_.first_tier_of(points, pixels_, reaches_, kReach);
    if constexpr (std::is_same_v<Screen, EveryPoint>) {
      for (std::size_t i = 0; i < points.size; ++i) pass_on(points, i);
    } else {
      for (std::uint32_t lanes = screen_.screen(pixels_, reaches_, points.size); lanes != 0; lanes &= lanes - 1) {
        pass_on(points, std::size_t(std::countr_zero(lanes)));
      }
    }
    pushed_ += std::uint32_t(points.size);
  }
  /// Answers the points still waiting.
  void flush() { run_left(); }

 private:
  /// Lane i of the group pushed: taken, or left for tiers 2 and 3.
  void pass_on(const PixelLookup::Group& points, std::size_t i) {
    const std::uint32_t tag = pushed_ + std::uint32_t(i);
    if (pixels_[i] != PixelLookup::kUndecided) {
      take_(tag, pixels_[i], reaches_[i]);
      return;
    }
    const std::size_t j = left_.size++;
    left_.x[j] = points.x[i], left_.y[j] = points.y[i], left_.z[j] = points.z[i];
    left_reaches_[j] = reaches_[i];
    left_tags_[j] = tag;
    if (left_.size == kGroup) run_left();
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
  [[no_unique_address]] Screen screen_;
  std::array<std::uint32_t, kGroup> pixels_{};  // tier 1's answers for the group pushed
  std::array<double, kGroup> reaches_{};
  std::uint32_t pushed_ = 0;  // points pushed before the group at hand
  PixelLookup::Group left_;  // the points tier 1 left, waiting for a group of their own
  std::array<std::uint32_t, kGroup> left_tags_{}, left_pixels_{};
  std::array<double, kGroup> left_reaches_{};
};

}  // namespace eco::detail
