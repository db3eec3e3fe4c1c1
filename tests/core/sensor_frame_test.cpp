// to_sensor_frame, whose lanes rotate held points in vector code (src/update/sensor_frame.cpp),
// against Eigen's product one point at a time: the same doubles to the bit, for random rotations,
// offsets near and far from the precision origin, and every group size.

#include "update/sensor_frame.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <random>

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

}  // namespace
}  // namespace eco::detail
