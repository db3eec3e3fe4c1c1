#include "map_publisher.hpp"

#include "ros_messages.hpp"

#include <nlohmann/json.hpp>
#include <std_msgs/String.h>

#include <algorithm>

namespace eco::ros_node {

MapPublisher::MapPublisher(ros::NodeHandle& private_node, const NodeSettings& settings)
    : settings_(settings),
      // latched: a viewer or node that starts later gets the last map at once
      map_(private_node.advertise<sensor_msgs::PointCloud2>("map", 2, true)),
      voxels_(private_node.advertise<sensor_msgs::PointCloud2>("voxels", 2, true)),
      region_(private_node.advertise<visualization_msgs::Marker>("region", 2, true)),
      stats_(private_node.advertise<std_msgs::String>("stats", 100)),
      thread_([this] { run(); }) {}

MapPublisher::~MapPublisher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void MapPublisher::offer(UpdatedFrame frame) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(frame));
  }
  wake_.notify_one();
}

void MapPublisher::run() {
  for (;;) {
    UpdatedFrame frame;
    bool newer_map = false;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, all sent
      frame = std::move(queue_.front());
      queue_.pop_front();
      newer_map = std::any_of(queue_.begin(), queue_.end(), [](const UpdatedFrame& f) { return f.publish_map; });
    }
    try {
      publish(frame, frame.publish_map && !newer_map);
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(1.0, "eco_node: frame %u not published: %s", frame.taken.stats.frame, e.what());
    }
  }
}

void MapPublisher::publish(const UpdatedFrame& frame, bool send_map) {
  std_msgs::Header header;
  header.stamp = frame.stamp;
  header.frame_id = settings_.fixed_frame;
  const FrameMap& map = *frame.taken.map;
  const auto since_received = [&] { return std::chrono::duration<double, std::milli>(Clock::now() - frame.received).count(); };
  double latency_ms = 0.0;
  if (send_map) {
    map_.publish(map_cloud(map, header));
    latency_ms = since_received();
    if (settings_.voxel > 0.0) voxels_.publish(xyz_cloud(map.voxel_centres(settings_.voxel), header));
  }
  region_.publish(region_marker(map.region(), header));
  const FrameStats& s = frame.taken.stats;
  const nlohmann::json stats{
      {"frame", s.frame},           {"stamp", frame.stamp.toSec()}, {"scan_points", s.scan_points},
      {"inserted", s.inserted},     {"pruned", s.pruned},           {"cleared", s.cleared},
      {"held", s.held},             {"update_ms", s.update_ms},     {"waited_ms", frame.waited_ms},
      {"taken_ms", frame.taken_ms},
      {"map_published", send_map},  {"lost", frame.lost},           {"skipped", frame.skipped},
      {"refused", frame.refused},
      // the cloud's arrival to its map sent (to the statistics, for a frame whose map is not)
      {"latency_ms", send_map ? latency_ms : since_received()}};
  std_msgs::String text;
  text.data = stats.dump();
  stats_.publish(text);
}

}  // namespace eco::ros_node
