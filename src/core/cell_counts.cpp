#include "core/cell_counts.hpp"

#include "core/vector_clones.hpp"

#include <algorithm>

namespace eco::detail {

ECO_WIDE_VECTOR_CLONES
std::uint64_t CellCounts::refuse_full_near_home(const std::uint64_t* slots, std::size_t last, int shift,
                                                const std::uint64_t* keys, std::size_t n, std::uint32_t limit,
                                                std::uint8_t* passed) {
  // A key found in a slot is that slot's cell wherever its probe run began (keys are unique).
  // A key like its `limit` predecessors' (limit 1 or 2) is refused too: each of them was counted or
  // found its cell full, so the cell holds `limit` by its turn. A scan lists a cell's points side
  // by side, so under a cap this spares the probes of a cell new to the group.
  std::array<std::uint64_t, kMaxKeys + 2> padded;  // keys[k] at k + 2, after two that are no key
  padded[0] = ~std::uint64_t{0};
  padded[1] = ~std::uint64_t{1};
  std::copy(keys, keys + n, padded.begin() + 2);
  std::fill(padded.begin() + 2 + std::ptrdiff_t(n), padded.end(), std::uint64_t{0});
  const std::uint32_t after_one = limit == 1, after_two = limit == 2;
  std::array<std::uint8_t, kMaxKeys> full;
  // Every one of the kMaxKeys lanes, those past n on key 0 (their verdicts are overwritten below):
  // a trip count the compiler knows. Over n, the vector loop had a scalar tail and, at AVX-512,
  // ran only when n was 64.
  for (std::size_t k = 0; k < kMaxKeys; ++k) {  // without branches: vector code
    const std::uint64_t key = padded[k + 2];
    const std::size_t at = home(key, shift);
    const std::uint64_t here = slots[at], next = slots[(at + 1) & last];
    const std::uint32_t repeats = padded[k + 1] == key, repeats_twice = repeats & (padded[k] == key);
    full[k] = std::uint8_t(((key_of(here) == key) & (count_of(here) >= limit)) |
                           ((key_of(next) == key) & (count_of(next) >= limit)) | (repeats & after_one) |
                           (repeats_twice & after_two));
  }
  std::fill(passed, passed + n, std::uint8_t{0});
  // the open keys as bits: those not full, and none past n
  std::fill(full.begin() + std::ptrdiff_t(n), full.end(), std::uint8_t{1});
  return ~flags_as_bits(full.data(), kMaxKeys);
}

}  // namespace eco::detail
