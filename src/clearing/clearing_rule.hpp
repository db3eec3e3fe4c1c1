#pragma once
// The comparison at the heart of free-space clearing's rule (include/eco/config.hpp): a return
// clears a held point when it lies more than the margin beyond it; and the screen that rules out
// most points without it, in vector code.

#include <cmath>
#include <cstdint>

namespace eco::detail {

/// Whether `nearest` > |v| + `margin`, evaluated in double with |v| = sqrt(`squared`) as rounded —
/// decided on `squared` itself, without the square root, wherever the roundings cannot matter.
/// `margin` finite and >= 0; `nearest` >= 0 or +infinity.
///
/// Why the shortcut is exact: with room = nearest - margin and guard = 1e-9 (nearest + margin),
/// squared < (room - guard)^2 puts |v| + margin, with every rounding in it (a few units of 1e-16
/// of nearest + margin), below nearest; squared > (room + guard)^2 puts it above. Between the two,
/// the rule is evaluated as written.
[[nodiscard]] inline bool lies_beyond(double nearest, double squared, double margin) {
  if (nearest <= margin) return false;  // |v| + margin >= margin, rounded too
  const double room = nearest - margin, guard = 1e-9 * (nearest + margin);
  const double below = room - guard, above = room + guard;
  if (below > 0.0 && squared < below * below) return true;
  if (squared > above * above) return false;
  return nearest > std::sqrt(squared) + margin;
}

/// 0 where lies_beyond(`nearest`, `squared`, `margin`) surely does not hold, else 1; without
/// branches, for vector code (PixelStream's screens). Its test is lies_beyond's own sure "no" with
/// twice the guard: room + 2 guard >= room + guard however either is rounded (a fused multiply-add
/// in one and not the other moves a sum by far less than a guard), so where this says 0, so does
/// lies_beyond.
[[nodiscard]] inline std::uint32_t may_lie_beyond(double nearest, double squared, double margin) {
  const double room = nearest - margin, guard = 1e-9 * (nearest + margin);
  const double above = room + 2.0 * guard;
  return std::uint32_t(nearest > margin) & std::uint32_t(!(squared > above * above));
}

}  // namespace eco::detail
