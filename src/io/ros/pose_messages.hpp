#pragma once
// The poses a recording carries: nav_msgs/Odometry, geometry_msgs/PoseStamped or
// geometry_msgs/TransformStamped on a topic of their own, or tf2_msgs/TFMessage (/tf, /tf_static),
// in ROS 1's encoding or CDR, each read as its header stamp and the pose it gives (of
// child_frame_id in frame_id).

#include "io/ros/message_store.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace eco::io::detail {

struct StampedPose {
  std::int64_t stamp_ns = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::string frame_id, child_frame_id;
};

/// Whether messages of `type` ("nav_msgs/msg/Odometry", "geometry_msgs/PoseStamped", ...) hold a pose.
[[nodiscard]] bool is_pose_type(const std::string& type);
/// Whether `type` is tf's message, a list of transforms (tf2_msgs/TFMessage, tf/tfMessage).
[[nodiscard]] bool is_tf_type(const std::string& type);

/// One message of a pose type. Throws eco::io::Error naming `source` and the byte for a message
/// cut short, a quaternion far from unit length or a value not finite.
[[nodiscard]] StampedPose parse_pose_message(std::span<const std::uint8_t> message, Encoding encoding,
                                             const std::string& type, const std::string& source);
/// One tf message: its transforms, each with its own stamp and frames. Throws as above.
[[nodiscard]] std::vector<StampedPose> parse_tf_message(std::span<const std::uint8_t> message, Encoding encoding,
                                                        const std::string& source);

}  // namespace eco::io::detail
