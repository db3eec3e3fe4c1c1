#pragma once
// A group's 0/1 flags (the density cap's verdicts) as bits: eight flags a word, a clear word
// skipped at once and a set one's bits visited alone, since under a cap most flags are clear.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace eco::detail {

/// Eight flags (bytes 0 or 1, the first lowest) as eight bits, byte b on bit b: one multiply moves
/// each byte's bit to a distinct place in the top byte.
inline unsigned verdict_bits(std::uint64_t eight) { return unsigned((eight * 0x0102040810204080ull) >> 56); }

/// Flags [0, n) (n <= 64; bytes 0 or 1, and 0 from n up to the next multiple of 8) as bits, flag
/// i on bit i, eight a multiply.
inline std::uint64_t flags_as_bits(const std::uint8_t* flag, std::size_t n) {
  std::uint64_t bits = 0;
  for (std::size_t w = 0; w < (n + 7) / 8; ++w) {
    std::uint64_t eight;
    std::memcpy(&eight, flag + 8 * w, sizeof eight);
    bits |= std::uint64_t(verdict_bits(eight)) << (8 * w);
  }
  return bits;
}

/// Calls take(i) for each i < n whose flag[i] (0 or 1) is 1, in order.
template <class Take>
void for_each_set(const std::uint8_t* flag, std::size_t n, Take&& take) {
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    std::uint64_t eight;
    std::memcpy(&eight, flag + i, sizeof eight);
    if (eight == 0) continue;
    for (unsigned bits = verdict_bits(eight); bits != 0; bits &= bits - 1) {
      take(i + std::size_t(std::countr_zero(bits)));
    }
  }
  for (; i < n; ++i) {
    if (flag[i] != 0) take(i);
  }
}

}  // namespace eco::detail
