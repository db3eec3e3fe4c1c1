// to_sensor_frame, whose lanes rotate held points in vector code (src/clearing/sensor_frame.cpp),
// against Eigen's product one point at a time: the same doubles to the bit, for random rotations,
// offsets near and far from the precision origin, and every group size; and load_returns, which
// loads a scan's returns (packed, in vector code, or strided), against the floats themselves.

#include "clearing/sensor_frame.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

TEST(SensorFrame, GroupsRotateAsEigenDoesToTheBit) {
  std::mt19937 rng(21);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<float> stored(-30.0f, 30.0f);
  std::size_t compared = 0;
  for (int pose_index = 0; pose_index < 400; ++pose_index) {
    const Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    const double reach = pose_index % 4 == 0 ? 1e5 : 20.0;  // sensors far from the precision origin too
    const SensorPose pose(q.normalized().toRotationMatrix(), Eigen::Vector3d(u(rng), u(rng), u(rng)) * reach);
    for (std::size_t size = 1; size <= PixelLookup::kGroup; ++size) {
      StoredGroup in;
      in.size = size;
      for (std::size_t i = 0; i < PixelLookup::kGroup; ++i) in.x[i] = stored(rng), in.y[i] = stored(rng), in.z[i] = stored(rng);
      PixelLookup::Group out;
      to_sensor_frame(pose, in, out);
      ASSERT_EQ(out.size, size);
      for (std::size_t i = 0; i < size; ++i) {
        const Eigen::Vector3d want = pose.apply({in.x[i], in.y[i], in.z[i]});
        ASSERT_EQ(out.x[i], want.x()) << "pose " << pose_index << " lane " << i;
        ASSERT_EQ(out.y[i], want.y()) << "pose " << pose_index << " lane " << i;
        ASSERT_EQ(out.z[i], want.z()) << "pose " << pose_index << " lane " << i;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 400u * PixelLookup::kGroup * (PixelLookup::kGroup + 1) / 2);  // every group size
}

TEST(SensorFrame, ReturnsLoadAsTheirFloatsForEveryStrideAndGroupSize) {
  std::mt19937 rng(22);
  std::uniform_real_distribution<float> coordinate(-120.0f, 120.0f);
  for (const std::size_t stride : {3u, 4u, 7u}) {
    std::vector<float> scan(stride * (PixelLookup::kGroup + 5));
    for (float& f : scan) f = coordinate(rng);
    scan[stride * 2] = std::numeric_limits<float>::quiet_NaN();  // non-finite coordinates pass as they are
    scan[stride * 3 + 1] = -std::numeric_limits<float>::infinity();
    for (const std::size_t begin : {0u, 1u, 5u}) {
      for (std::size_t n = 1; n <= PixelLookup::kGroup; ++n) {
        PixelLookup::Group out;
        out.x.fill(-1.0), out.y.fill(-1.0), out.z.fill(-1.0);
        load_returns(scan.data() + begin * stride, stride, n, out);
        ASSERT_EQ(out.size, n);
        for (std::size_t i = 0; i < n; ++i) {
          const float* p = scan.data() + (begin + i) * stride;
          const auto same = [](double loaded, float f) { return std::isnan(f) ? std::isnan(loaded) : loaded == double(f); };
          ASSERT_TRUE(same(out.x[i], p[0]) && same(out.y[i], p[1]) && same(out.z[i], p[2]))
              << "stride " << stride << " begin " << begin << " n " << n << " lane " << i;
        }
        for (std::size_t i = n; i < PixelLookup::kGroup; ++i) ASSERT_EQ(out.x[i], -1.0) << "lane " << i << " past n = " << n;
      }
    }
  }
}

}  // namespace
}  // namespace eco::detail
