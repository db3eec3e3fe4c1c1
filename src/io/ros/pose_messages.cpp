#include "io/ros/pose_messages.hpp"

#include "io/ros/byte_reader.hpp"

#include <eco/io/pose_file.hpp>

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
  return pose_of({v[0], v[1], v[2]}, q);
}

/// A message body: the header, child_frame_id (all but PoseStamped), then the pose. ROS 1's header
/// begins with a sequence number and its stamp's seconds are unsigned.
StampedPose read_stamped(ByteReader& in, PoseType kind, bool cdr) {
  StampedPose out;
  if (!cdr) (void)in.read<std::uint32_t>("the header's seq");
  const std::int64_t sec = cdr ? in.read<std::int32_t>("the stamp") : std::int64_t(in.read<std::uint32_t>("the stamp"));
  out.stamp_ns = sec * 1000000000 + in.read<std::uint32_t>("the stamp");
  out.frame_id = in.string("frame_id");
  if (kind != PoseType::PoseStamped) out.child_frame_id = in.string("child_frame_id");
  out.pose = read_pose(in);
  return out;
}

/// A reader of `message` past its encapsulation (CDR: 4 bytes naming the byte order).
ByteReader body_of(std::span<const std::uint8_t> message, Encoding encoding, const std::string& source) {
  if (encoding != Encoding::Cdr) return ByteReader(message, source);
  ByteReader head(message, source);
  (void)head.read<std::uint8_t>("the encapsulation");
  const bool big_endian = head.read<std::uint8_t>("the encapsulation") == 0;
  ByteReader in(message, source, 0, 4, big_endian);
  in.seek(4);
  return in;
}

}  // namespace

bool is_pose_type(const std::string& type) { return pose_type(type) != PoseType::None; }

bool is_tf_type(const std::string& type) {
  return type == "tf2_msgs/msg/TFMessage" || type == "tf2_msgs/TFMessage" || type == "tf/tfMessage";
}

StampedPose parse_pose_message(std::span<const std::uint8_t> message, Encoding encoding, const std::string& type,
                               const std::string& source) {
  const PoseType kind = pose_type(type);
  if (kind == PoseType::None) throw Error(source, "", type + " holds no pose");
  ByteReader in = body_of(message, encoding, source);
  return read_stamped(in, kind, encoding == Encoding::Cdr);
}

std::vector<StampedPose> parse_tf_message(std::span<const std::uint8_t> message, Encoding encoding,
                                          const std::string& source) {
  ByteReader in = body_of(message, encoding, source);
  const std::uint32_t count = in.read<std::uint32_t>("the count of transforms");
  // each transform takes at least its stamp, two string lengths and seven doubles
  if (std::uint64_t(count) * 68 > in.remaining()) in.fail(std::to_string(count) + " transforms cannot fit in what remains");
  std::vector<StampedPose> transforms;
  transforms.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) transforms.push_back(read_stamped(in, PoseType::TransformStamped, encoding == Encoding::Cdr));
  return transforms;
}

}  // namespace eco::io::detail
