#pragma once
// What the node publishes after each update, on a thread of its own and from the frame's snapshot,
// so that the next update never waits for a cloud being built or sent: the held map and its
// voxels (every ~publish_every frames), the region, and the frame's statistics.

#include "map_session.hpp"

#include <ros/ros.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

namespace eco::ros_node {

using Clock = std::chrono::steady_clock;

/// One frame's outcome, as the node hands it over.
struct UpdatedFrame {
  TakenFrame taken;
  ros::Time stamp;
  Clock::time_point received;  ///< when its cloud arrived
  double waited_ms = 0.0;      ///< from then until its poses were known (decoding included)
  double taken_ms = 0.0;       ///< ... until it was in the map, its snapshot made
  bool publish_map = false;
  std::size_t lost = 0, skipped = 0, refused = 0;  ///< clouds so far: missed upstream, without poses, undecodable
};

class MapPublisher {
 public:
  MapPublisher(ros::NodeHandle& private_node, const NodeSettings& settings);
  ~MapPublisher();  // sends what it was given, then stops
  MapPublisher(const MapPublisher&) = delete;
  MapPublisher& operator=(const MapPublisher&) = delete;

  /// Hands a frame to the publishing thread. A map not yet sent when a newer one comes is left
  /// out; every frame's region and statistics are sent.
  void offer(UpdatedFrame frame);

 private:
  void run();
  void publish(const UpdatedFrame& frame, bool send_map);

  NodeSettings settings_;
  ros::Publisher map_, voxels_, region_, stats_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<UpdatedFrame> queue_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace eco::ros_node
