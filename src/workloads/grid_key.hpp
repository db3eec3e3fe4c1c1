#pragma once
// One 64-bit key per cell of a world-aligned grid: 21 bits per axis, cells -2^20 .. 2^20 - 1.

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <optional>

namespace eco::workloads::detail {

inline constexpr std::int64_t kCellLimit = std::int64_t{1} << 20;

[[nodiscard]] inline std::optional<std::uint64_t> grid_key(const Eigen::Vector3d& p, double side) {
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const double cell = std::floor(p[a] / side);
    if (!(cell >= -static_cast<double>(kCellLimit) && cell < static_cast<double>(kCellLimit))) return std::nullopt;
    key = (key << 21) | static_cast<std::uint64_t>(static_cast<std::int64_t>(cell) + kCellLimit);
  }
  return key;
}

}  // namespace eco::workloads::detail
