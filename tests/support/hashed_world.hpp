#pragma once
// An endless static world for long drives: a 6 m slab of 1 m cells, each holding 0, 1 or 2
// points at hashed positions. Deterministic, so a scan is the world inside the box, seen from
// the sensor.

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <vector>

namespace eco::test {

class HashedWorld {
 public:
  static constexpr int kSlabLow = -3, kSlabHigh = 3;  // z cells [-3, 3)
  static constexpr int kMaxPerCell = 2;

  /// World points in every cell that meets the cube of side `side` around `centre`, expressed in
  /// the sensor frame of `pose`.
  [[nodiscard]] std::vector<Eigen::Vector3f> scan(const Eigen::Isometry3d& pose, double side) const {
    std::vector<Eigen::Vector3f> out;
    const Eigen::Vector3d c = pose.translation();
    const Eigen::Isometry3d sensor_T_world = pose.inverse();
    const auto x0 = std::int64_t(std::floor(c.x() - side / 2)), x1 = std::int64_t(std::floor(c.x() + side / 2));
    const auto y0 = std::int64_t(std::floor(c.y() - side / 2)), y1 = std::int64_t(std::floor(c.y() + side / 2));
    for (std::int64_t i = x0; i <= x1; ++i) {
      for (std::int64_t j = y0; j <= y1; ++j) {
        for (std::int64_t l = kSlabLow; l < kSlabHigh; ++l) {
          std::uint64_t h = mix(std::uint64_t(i) * 0x9E3779B97F4A7C15ull ^ std::uint64_t(j) * 0xC2B2AE3D27D4EB4Full ^
                                std::uint64_t(l) * 0x165667B19E3779F9ull);
          const int n = int(h % (kMaxPerCell + 1));
          for (int k = 0; k < n; ++k) {
            h = mix(h);
            const Eigen::Vector3d w(double(i) + unit(h), double(j) + unit(h >> 20), double(l) + unit(h >> 40));
            out.push_back((sensor_T_world * w).cast<float>());
          }
        }
      }
    }
    return out;
  }

 private:
  static std::uint64_t mix(std::uint64_t x) {
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    return x ^ (x >> 33);
  }
  static double unit(std::uint64_t h) { return double(h & 0xFFFFF) / double(0x100000); }
};

}  // namespace eco::test
