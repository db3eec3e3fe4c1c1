#include "core/density/cell_counts.hpp"

#include "core/geometry/vector_clones.hpp"

#include <algorithm>

namespace eco::detail {

ECO_WIDE_VECTOR_CLONES
std::uint64_t CellCounts::refuse_full_near_home(const Table& table, const std::uint64_t* keys, std::size_t n,
                                                std::uint32_t limit, std::uint8_t* passed) {
  // A block found in a slot is that slot's wherever its probe run began (blocks are unique).
  // A key like its `limit` predecessors' (limit 1 or 2) is refused too: each of them was counted or
  // found its cell full, so the cell holds `limit` by its turn. A scan lists a cell's points side
  // by side, so under a cap this spares the probes of a cell new to the group.
  std::array<std::uint64_t, kMaxKeys + 2> padded;  // keys[k] at k + 2, after two that are no key
  padded[0] = ~std::uint64_t{0};
  padded[1] = ~std::uint64_t{1};
  std::copy(keys, keys + n, padded.begin() + 2);
  std::fill(padded.begin() + 2 + std::ptrdiff_t(n), padded.end(), std::uint64_t{0});
  const std::uint64_t after_one = limit == 1, after_two = limit == 2, at_least = limit;
  const std::uint64_t* const slots = table.slots;
  const std::size_t last = table.last, stride = table.stride;
  const int shift = table.shift;
  const std::uint64_t width = std::uint64_t(table.width), mask = (std::uint64_t{1} << width) - 1;
  std::array<std::uint8_t, kMaxKeys> full;
  // Every one of the kMaxKeys lanes, those past n on key 0 (their verdicts are overwritten below):
  // a trip count the compiler knows. Over n, the vector loop had a scalar tail and, at AVX-512,
  // ran only when n was 64.
  for (std::size_t k = 0; k < kMaxKeys; ++k) {  // without branches: vector code
    const std::uint64_t key = padded[k + 2];
    const std::uint64_t tag = block_of(key) | kOccupied;
    const std::size_t at = home(block_of(key), shift), next = (at + 1) & last;
    const std::uint64_t here_holds = slots[at * stride] == tag, next_holds = slots[next * stride] == tag;
    const std::size_t slot = next ^ ((at ^ next) & (0 - here_holds));  // at where it holds the block
    const std::uint64_t bit = std::uint64_t(cell_of(key)) * width;
    const std::uint64_t count = (slots[slot * stride + 1 + (bit >> 6)] >> (bit & 63)) & mask;
    const std::uint64_t repeats = padded[k + 1] == key, repeats_twice = repeats & (padded[k] == key);
    full[k] = std::uint8_t(((here_holds | next_holds) & (count >= at_least)) | (repeats & after_one) |
                           (repeats_twice & after_two));
  }
  std::fill(passed, passed + n, std::uint8_t{0});
  // the open keys as bits: those not full, and none past n (as a mask: filling the flags past n
  // instead left the loop above scalar)
  const std::uint64_t beyond = n == kMaxKeys ? 0 : ~std::uint64_t{0} << n;
  return ~(flags_as_bits(full.data(), kMaxKeys) | beyond);
}

}  // namespace eco::detail
