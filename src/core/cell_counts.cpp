#include "core/cell_counts.hpp"

#include "core/vector_clones.hpp"

namespace eco::detail {

ECO_WIDE_VECTOR_CLONES
std::size_t CellCounts::refuse_full_near_home(const std::uint64_t* slots, std::size_t last, int shift,
                                              const std::uint64_t* keys, std::size_t n, std::uint32_t limit,
                                              std::uint8_t* passed, std::uint32_t* open) {
  // A key found in a slot is that slot's cell wherever its probe run began (keys are unique).
  std::array<std::uint8_t, kMaxKeys> full;
  for (std::size_t k = 0; k < n; ++k) {  // without branches: vector code
    const std::size_t at = home(keys[k], shift);
    const std::uint64_t here = slots[at], next = slots[(at + 1) & last];
    full[k] = std::uint8_t(((key_of(here) == keys[k]) & (count_of(here) >= limit)) |
                           ((key_of(next) == keys[k]) & (count_of(next) >= limit)));
  }
  std::size_t left = 0;
  for (std::size_t k = 0; k < n; ++k) {
    passed[k] = 0;
    open[left] = std::uint32_t(k);
    left += full[k] == 0;
  }
  return left;
}

}  // namespace eco::detail
