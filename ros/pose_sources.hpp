#pragma once
// Where a cloud was taken, asked for the whole sweep: each point may be placed at its own time.
// Two sources: a nav_msgs/Odometry topic (its poses interpolated as eco::io::pose_at does for a
// recording's pose topic, the extrinsic from its child frame to the cloud's taken from tf), or tf
// itself (fixed frame -> the cloud's frame_id).

#include "map_session.hpp"

#include <eco/io/pose_file.hpp>

#include <nav_msgs/Odometry.h>
#include <tf2_ros/buffer.h>

#include <limits>
#include <string>

namespace eco::ros_node {

/// The poses of one sweep.
struct SweepPoses {
  enum class State {
    Ready,    ///< known across the sweep: pose_at answers for all of it
    Waiting,  ///< not yet known (they may come)
    Never,    ///< will not be: the cloud lies before the first pose
  };
  State state = State::Waiting;
  PoseAtTime pose_at;  ///< Ready: the cloud frame's pose in the fixed frame, at a time [s]
  std::string why;                ///< Waiting, Never: what is missing
};

class PoseSource {
 public:
  virtual ~PoseSource() = default;
  /// The poses of a cloud of `frame_id` over [first, last] (seconds, ROS time).
  [[nodiscard]] virtual SweepPoses sweep(const std::string& frame_id, double first, double last) = 0;
  /// Forgets what no cloud from `time` on will ask for.
  virtual void forget_before(double /*time*/) {}
  /// The latest time [s] the poses reach, or -infinity where that is not known (tf).
  [[nodiscard]] virtual double latest() const { return -std::numeric_limits<double>::infinity(); }
  /// "tf: map -> velodyne", "/odom (base_link in map)": for the start's log line.
  [[nodiscard]] virtual std::string describe() const = 0;
};

/// tf's chain from `fixed_frame` to each cloud's frame.
class TfPoses final : public PoseSource {
 public:
  TfPoses(const tf2_ros::Buffer& buffer, std::string fixed_frame) : buffer_(buffer), fixed_frame_(std::move(fixed_frame)) {}
  [[nodiscard]] SweepPoses sweep(const std::string& frame_id, double first, double last) override;
  [[nodiscard]] std::string describe() const override { return "tf from " + fixed_frame_ + " to the clouds' frame"; }

 private:
  const tf2_ros::Buffer& buffer_;
  std::string fixed_frame_;
};

/// A topic's poses, kept in stamp order as they arrive; the cloud's frame reached from the poses'
/// child frame through tf when they differ.
class TopicPoses final : public PoseSource {
 public:
  TopicPoses(const tf2_ros::Buffer& buffer, std::string topic) : buffer_(buffer), topic_(std::move(topic)) {}
  void add(const nav_msgs::Odometry& pose);
  [[nodiscard]] SweepPoses sweep(const std::string& frame_id, double first, double last) override;
  void forget_before(double time) override;
  [[nodiscard]] double latest() const override {
    return track_.times.empty() ? -std::numeric_limits<double>::infinity() : track_.times.back();
  }
  [[nodiscard]] std::string describe() const override;

 private:
  const tf2_ros::Buffer& buffer_;
  std::string topic_;
  std::string frame_id_, child_frame_id_;  // of the first pose
  io::PoseTrack track_;
};

}  // namespace eco::ros_node
