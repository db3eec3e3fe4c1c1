#pragma once
// eco_node: ECO's map of a live sensor_msgs/PointCloud2 topic. Each cloud is decoded as a
// recording's clouds are, held back until its poses are known for its whole sweep (a pose topic
// or tf) or estimated (ECO's odometry), and taken into the map (map_session.hpp); the frame's
// snapshot then goes to the publishing thread (map_publisher.hpp).

#include "map_publisher.hpp"
#include "map_session.hpp"
#include "pose_sources.hpp"

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <deque>
#include <memory>
#include <optional>

namespace eco::ros_node {

class EcoNode {
 public:
  /// Subscribes and advertises under `private_node` (~map, ~voxels, ~region, ~stats, ~odom, ~save).
  EcoNode(ros::NodeHandle& node, ros::NodeHandle& private_node, std::unique_ptr<MapSession> session);

  /// After the spinning stopped: says what was left waiting and what was taken, and saves the map
  /// when ~save_on_exit asks. Throws what EgoOctree::save throws.
  void finish();

 private:
  /// A decoded cloud and when it arrived.
  struct Waiting {
    DecodedSweep sweep;
    Clock::time_point received;
  };

  void on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg);
  void on_pose(const nav_msgs::Odometry::ConstPtr& msg);
  bool on_save(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  /// Takes the waiting clouds whose poses are known, in order; one that waited past ~tf_timeout
  /// is taken with the poses known by then (its stamp's at least), or skipped with a warning.
  void take_ready();
  /// The poses of the oldest waiting cloud, once it has waited past ~tf_timeout.
  [[nodiscard]] SweepPoses poses_after_waiting(const DecodedSweep& sweep);
  /// Estimates the cloud's pose by ECO's odometry, publishes it (~odom and tf), and maps it.
  void take_by_odometry(Waiting cloud);
  /// Hands a taken cloud (of `stamp_ns`, arrived at `received`, its poses known `waited_ms` later)
  /// to the publisher.
  void hand_over(TakenFrame taken, std::int64_t stamp_ns, Clock::time_point received, double waited_ms);

  std::unique_ptr<MapSession> session_;
  const NodeSettings& settings_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  std::unique_ptr<PoseSource> poses_;  // none with ~odometry
  TopicPoses* topic_poses_ = nullptr;  // poses_, when they are a topic's
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros::Publisher odom_;
  ros::Subscriber clouds_, pose_messages_;
  ros::ServiceServer save_;
  ros::SteadyTimer retry_;
  std::deque<Waiting> waiting_;
  std::optional<std::uint32_t> last_seq_;
  std::size_t lost_ = 0, skipped_ = 0, refused_ = 0;
  MapPublisher publisher_;  // last: it stops (and sends what it holds) first
};

}  // namespace eco::ros_node
