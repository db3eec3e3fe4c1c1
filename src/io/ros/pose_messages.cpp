#include "io/ros/pose_messages.hpp"

#include "io/ros/byte_reader.hpp"

#include <cmath>

namespace eco::io::detail {
namespace {

enum class PoseType { Odometry, PoseStamped, TransformStamped, None };

PoseType pose_type(const std::string& type) {
  if (type == "nav_msgs/Odometry" || type == "nav_msgs/msg/Odometry") return PoseType::Odometry;
  if (type == "geometry_msgs/PoseStamped" || type == "geometry_msgs/msg/PoseStamped") return PoseType::PoseStamped;
  if (type == "geometry_msgs/TransformStamped" || type == "geometry_msgs/msg/TransformStamped") return PoseType::TransformStamped;
  return PoseType::None;
}

/// A position then a quaternion (x, y, z, w), as Pose and Transform both lay them out.
Eigen::Isometry3d read_pose(ByteReader& in) {
  double v[7];
  for (double& value : v) value = in.read<double>("a pose's value");
  for (double value : v) {
    if (!std::isfinite(value)) in.fail("a pose value is not finite");
  }
  const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  if (std::abs(q.norm() - 1.0) > 1e-3) in.fail("the quaternion's length is " + std::to_string(q.norm()) + ", not 1");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return pose;
}

}  // namespace

bool is_pose_type(const std::string& type) { return pose_type(type) != PoseType::None; }

StampedPose parse_pose_message(std::span<const std::uint8_t> message, Encoding encoding, const std::string& type,
                               const std::string& source) {
  const PoseType kind = pose_type(type);
  if (kind == PoseType::None) throw Error(source, "", type + " holds no pose");
  const bool cdr = encoding == Encoding::Cdr;
  bool big_endian = false;
  if (cdr) {
    ByteReader head(message, source);
    (void)head.read<std::uint8_t>("the encapsulation");
    big_endian = head.read<std::uint8_t>("the encapsulation") == 0;
  }
  ByteReader in(message, source, 0, cdr ? 4 : ByteReader::kUnaligned, big_endian);
  if (cdr) in.seek(4);
  StampedPose out;
  if (!cdr) (void)in.read<std::uint32_t>("the header's seq");
  const std::int64_t sec = cdr ? in.read<std::int32_t>("the stamp") : std::int64_t(in.read<std::uint32_t>("the stamp"));
  out.stamp_ns = sec * 1000000000 + in.read<std::uint32_t>("the stamp");
  out.frame_id = in.string("frame_id");
  if (kind != PoseType::PoseStamped) out.child_frame_id = in.string("child_frame_id");
  out.pose = read_pose(in);
  return out;
}

}  // namespace eco::io::detail
