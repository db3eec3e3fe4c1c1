#include "ros_messages.hpp"

#include <eco/io/pose_file.hpp>

namespace eco::ros_node {
namespace {

/// An unorganised cloud of float32 fields named `names`, holding `bytes`.
sensor_msgs::PointCloud2 float_cloud(std::vector<std::uint8_t> bytes, std::initializer_list<const char*> names,
                                     const std_msgs::Header& header) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header = header;
  for (const char* name : names) {
    sensor_msgs::PointField f;
    f.name = name;
    f.offset = std::uint32_t(cloud.fields.size() * sizeof(float));
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    cloud.fields.push_back(f);
  }
  cloud.point_step = std::uint32_t(cloud.fields.size() * sizeof(float));
  cloud.height = 1;
  cloud.width = std::uint32_t(bytes.size() / cloud.point_step);
  cloud.row_step = std::uint32_t(bytes.size());
  cloud.is_bigendian = false;
  cloud.is_dense = true;
  cloud.data = std::move(bytes);
  return cloud;
}

}  // namespace

CloudBytes cloud_bytes(const sensor_msgs::PointCloud2& msg) {
  CloudBytes out;
  out.stamp_ns = std::int64_t(msg.header.stamp.toNSec());
  out.frame_id = msg.header.frame_id;
  out.height = msg.height;
  out.width = msg.width;
  for (const sensor_msgs::PointField& f : msg.fields) out.fields.push_back({f.name, f.offset, f.datatype, f.count});
  out.is_bigendian = msg.is_bigendian != 0;
  out.point_step = msg.point_step;
  out.row_step = msg.row_step;
  out.data = msg.data.data();
  out.size = msg.data.size();
  out.is_dense = msg.is_dense != 0;
  return out;
}

sensor_msgs::PointCloud2 map_cloud(const FrameMap& map, const std_msgs::Header& header) {
  if (map.has_intensity()) return float_cloud(map.point_bytes(), {"x", "y", "z", "intensity"}, header);
  return float_cloud(map.point_bytes(), {"x", "y", "z"}, header);
}

sensor_msgs::PointCloud2 xyz_cloud(const std::vector<Eigen::Vector3d>& points, const std_msgs::Header& header) {
  std::vector<std::uint8_t> bytes(points.size() * 3 * sizeof(float));
  float* at = reinterpret_cast<float*>(bytes.data());  // a vector's bytes are aligned for any scalar
  for (const Eigen::Vector3d& p : points) {
    *at++ = float(p.x());
    *at++ = float(p.y());
    *at++ = float(p.z());
  }
  return float_cloud(std::move(bytes), {"x", "y", "z"}, header);
}

visualization_msgs::Marker region_marker(const RegionOutline& region, const std_msgs::Header& header) {
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = "eco_region";
  m.id = 0;
  m.action = visualization_msgs::Marker::ADD;
  m.type = region.ball ? visualization_msgs::Marker::SPHERE : visualization_msgs::Marker::CUBE;
  m.pose.position.x = region.centre.x();
  m.pose.position.y = region.centre.y();
  m.pose.position.z = region.centre.z();
  m.pose.orientation.w = region.turn.w();
  m.pose.orientation.x = region.turn.x();
  m.pose.orientation.y = region.turn.y();
  m.pose.orientation.z = region.turn.z();
  m.scale.x = region.size.x();
  m.scale.y = region.size.y();
  m.scale.z = region.size.z();
  m.color.r = 0.2f;
  m.color.g = 0.6f;
  m.color.b = 1.0f;
  m.color.a = 0.15f;
  return m;
}

Eigen::Isometry3d pose_of(const geometry_msgs::Transform& t) {
  return io::pose_of({t.translation.x, t.translation.y, t.translation.z},
                     Eigen::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z));
}

geometry_msgs::Transform transform_of(const Eigen::Isometry3d& pose) {
  geometry_msgs::Transform t;
  t.translation.x = pose.translation().x();
  t.translation.y = pose.translation().y();
  t.translation.z = pose.translation().z();
  const Eigen::Quaterniond q(pose.linear());
  t.rotation.w = q.w();
  t.rotation.x = q.x();
  t.rotation.y = q.y();
  t.rotation.z = q.z();
  return t;
}

}  // namespace eco::ros_node
