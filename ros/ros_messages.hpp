#pragma once
// ROS 1 messages to and from the map session's plain types (map_session.hpp): clouds in, the map,
// its voxels and its region out, poses both ways.

#include "map_session.hpp"

#include <geometry_msgs/Transform.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/Marker.h>

namespace eco::ros_node {

/// `msg` with its data viewed, not copied (it lives as long as `msg`).
[[nodiscard]] CloudBytes cloud_bytes(const sensor_msgs::PointCloud2& msg);

/// A frame's held points (float32 x, y, z, and intensity when kept) in `header`'s frame.
[[nodiscard]] sensor_msgs::PointCloud2 map_cloud(const FrameMap& map, const std_msgs::Header& header);
/// Points (voxel centres) as float32 x, y, z.
[[nodiscard]] sensor_msgs::PointCloud2 xyz_cloud(const std::vector<Eigen::Vector3d>& points, const std_msgs::Header& header);

/// The region a frame's map holds, translucent.
[[nodiscard]] visualization_msgs::Marker region_marker(const RegionOutline& region, const std_msgs::Header& header);

[[nodiscard]] Eigen::Isometry3d pose_of(const geometry_msgs::Transform& transform);
[[nodiscard]] geometry_msgs::Transform transform_of(const Eigen::Isometry3d& pose);

}  // namespace eco::ros_node
