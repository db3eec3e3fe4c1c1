#pragma once
// The age limit (Config::max_age_frames or max_age_seconds) as the current frame applies it:
// every point and node carries an age key, and keys below the frame's cutoff are past the limit.

#include "core/geometry/motion.hpp"
#include "core/storage/point_store.hpp"

#include <eco/config.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace eco::detail {

struct AgeLimit {
  bool by_time = false;      ///< keys are stored times (max_age_seconds), else insertion frames
  std::uint32_t cutoff = 0;  ///< keys below it are past the limit; 0 while none applies

  /// The limit `config` sets in the frame of `motion`.
  static AgeLimit of(const Config& config, const Motion& motion) {
    AgeLimit limit{config.max_age_seconds > 0.0, 0};
    if (limit.by_time) {
      if (motion.clock.latest == -std::numeric_limits<double>::infinity()) return limit;
      // stored time f is aged when origin + f < latest - max age, i.e. when f is below the least
      // float at or above c (no float lies between c and that one)
      const double c = motion.clock.latest - config.max_age_seconds - motion.clock.origin;
      float least = float(c);
      if (double(least) < c) least = std::nextafter(least, std::numeric_limits<float>::infinity());
      limit.cutoff = time_key(least);
    } else if (config.max_age_frames > 0 && motion.frame > config.max_age_frames) {
      limit.cutoff = motion.frame - config.max_age_frames;
    }
    return limit;
  }

  /// What the limit compares: the insertion frame, or the stored time as an order-keeping
  /// integer. Nodes keep the smallest below them.
  [[nodiscard]] std::uint32_t key(const StoredPoint& s) const { return by_time ? time_key(s.time) : s.stamp; }
  [[nodiscard]] bool admits(const StoredPoint& s) const { return key(s) >= cutoff; }

  /// The order-keeping integer of float `f`: a < b exactly when time_key(a) < time_key(b).
  static std::uint32_t time_key(float f) {
    const auto u = std::bit_cast<std::uint32_t>(f + 0.0f);  // + 0: -0 becomes +0
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
  }
};

}  // namespace eco::detail
