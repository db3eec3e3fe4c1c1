// libFuzzer: any text given to the poses, calib and times parsers ends in values or an
// eco::io::Error, nothing else; every pose read is a rigid motion.

#include <eco/io/kitti.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto check_rigid = [](const Eigen::Isometry3d& pose) {
    const Eigen::Matrix3d r = pose.linear();
    if (!((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-9) ||
        !pose.translation().allFinite()) {
      std::abort();
    }
  };
  try {
    for (const auto& pose : eco::io::parse_kitti_poses(text, "poses.txt")) check_rigid(pose);
  } catch (const eco::io::Error&) {
  }
  try {
    check_rigid(eco::io::parse_kitti_calib(text, "calib.txt"));
  } catch (const eco::io::Error&) {
  }
  try {
    (void)eco::io::parse_kitti_times(text, "times.txt");
  } catch (const eco::io::Error&) {
  }
  return 0;
}
