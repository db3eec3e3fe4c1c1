#include "core/subcells.hpp"

#include "core/vector_clones.hpp"

#include <algorithm>

namespace eco::detail {

ECO_VECTOR_CLONES
std::uint64_t Subcells::bits(const float* x, const float* y, const float* z, std::uint32_t begin,
                             std::uint32_t end) const {
  // the subcells a chunk at a time in vector code (comparisons summed lane by lane), then set
  constexpr std::uint32_t kChunk = 64;
  std::array<std::uint32_t, kChunk> at;
  std::uint64_t out = 0;
  for (std::uint32_t from = begin; from < end; from += kChunk) {
    const std::uint32_t n = std::min(kChunk, end - from);
    for (std::uint32_t i = 0; i < n; ++i) {
      at[i] = std::uint32_t(of({x[from + i], y[from + i], z[from + i]}));
    }
    for (std::uint32_t i = 0; i < n; ++i) out |= std::uint64_t{1} << at[i];
  }
  return out;
}

}  // namespace eco::detail
