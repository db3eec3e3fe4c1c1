#pragma once
// eco_node's own settings (beside the map's Config), in plain types: the ROS side of the node is
// compiled as C++17 (ROS 1's message headers use std::allocator<void>::rebind, gone in C++20) and
// includes this; the parameters are read on the library's side (node_parameters.hpp).

#include <cstdint>
#include <string>

namespace eco::ros_node {

struct NodeSettings {
  std::string cloud_topic = "points";
  int queue_size = 10;           ///< clouds the subscriber holds while an update runs
  /// nav_msgs/Odometry placing the clouds; empty: tf from fixed_frame to the cloud's frame_id
  std::string pose_topic;
  std::string fixed_frame = "map";
  double tf_timeout = 0.5;       ///< [s] how long a cloud waits for its poses
  bool odometry = false;         ///< ECO's odometry estimates the poses (and publishes them)
  std::uint32_t publish_every = 1;  ///< frames between published maps
  double voxel = 0.2;            ///< [m] the voxel map's voxel; 0: none published
  std::string save_path = "eco_map.eco";
  bool save_on_exit = false;
};

}  // namespace eco::ros_node
