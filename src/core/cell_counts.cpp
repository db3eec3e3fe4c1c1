#include "core/cell_counts.hpp"

#include "core/vector_clones.hpp"

#include <cstring>

namespace eco::detail {

ECO_WIDE_VECTOR_CLONES
std::uint64_t CellCounts::refuse_full_near_home(const std::uint64_t* slots, std::size_t last, int shift,
                                                const std::uint64_t* keys, std::size_t n, std::uint32_t limit,
                                                std::uint8_t* passed) {
  // A key found in a slot is that slot's cell wherever its probe run began (keys are unique).
  std::array<std::uint8_t, kMaxKeys> full;
  for (std::size_t k = 0; k < n; ++k) {  // without branches: vector code
    const std::size_t at = home(keys[k], shift);
    const std::uint64_t here = slots[at], next = slots[(at + 1) & last];
    full[k] = std::uint8_t(((key_of(here) == keys[k]) & (count_of(here) >= limit)) |
                           ((key_of(next) == keys[k]) & (count_of(next) >= limit)));
  }
  std::fill(passed, passed + n, std::uint8_t{0});
  // the open keys as bits, eight verdicts a multiply
  std::fill(full.begin() + std::ptrdiff_t(n), full.end(), std::uint8_t{1});
  std::uint64_t open = 0;
  for (std::size_t w = 0; w < kMaxKeys / 8; ++w) {
    std::uint64_t eight;
    std::memcpy(&eight, full.data() + 8 * w, sizeof eight);
    eight ^= 0x0101010101010101ull;
    open |= std::uint64_t(verdict_bits(eight)) << (8 * w);
  }
  return open;
}

}  // namespace eco::detail
