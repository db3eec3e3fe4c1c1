#pragma once
// Which page of a point pool holds a block, without a division.

#include <cstdint>

namespace eco::detail {

/// How many blocks a pool's page holds, and which page block i lies on: i / count by a multiply
/// and a shift (a leaf's block is found on every read; a division would cost several times more).
/// Exact for every i < 2^32: the reciprocal, rounded up, is over 2^63 / count by at most
/// count / 2^63, which moves no quotient below 2^63 / count.
class BlocksPerPage {
 public:
  BlocksPerPage() = default;
  explicit BlocksPerPage(std::uint32_t blocks)
      : count(blocks), reciprocal_(std::uint64_t((static_cast<unsigned __int128>(1) << 63) / blocks) + 1) {}
  [[nodiscard]] std::uint32_t page_of(std::uint32_t i) const {
    return std::uint32_t((static_cast<unsigned __int128>(i) * reciprocal_) >> 63);
  }
  std::uint32_t count = 1;

 private:
  std::uint64_t reciprocal_ = std::uint64_t{1} << 63;
};

}  // namespace eco::detail
