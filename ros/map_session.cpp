#include "map_session.hpp"

#include "node_parameters.hpp"

#include <eco/ego_octree.hpp>
#include <eco/io/error.hpp>
#include <eco/io/point_cloud2.hpp>
#include <eco/odometry/local_map.hpp>
#include <eco/odometry/odometry.hpp>
#include <eco/workloads/sweep_placement.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace eco::ros_node {

struct DecodedPoints {
  io::DecodedCloud cloud;
};

namespace {

/// The region held after an update, as a marker draws it.
RegionOutline region_outline(const Region& region, const RegionExtents& extents, const Eigen::Isometry3d& world_T_sensor,
                         const Eigen::AlignedBox3d& ego_box) {
  RegionOutline out;
  const Eigen::Vector3d sensor = world_T_sensor.translation();
  switch (region.shape) {
    case eco::RegionShape::Cube:
      out.centre = ego_box.center();
      out.size = ego_box.sizes();
      break;
    case eco::RegionShape::Ball:
      out.ball = true;
      out.centre = sensor;
      out.size = Eigen::Vector3d::Constant(2.0 * extents.radius);
      break;
    case eco::RegionShape::OrientedBox: {
      // turned with the sensor's heading alone, or its whole rotation (core/geometry/ego_region.cpp)
      const Eigen::Matrix3d r = world_T_sensor.linear();
      out.turn = region.turn_with == TurnWith::Full
                     ? Eigen::Quaterniond(r)
                     : Eigen::Quaterniond(Eigen::AngleAxisd(std::atan2(r(1, 0), r(0, 0)), Eigen::Vector3d::UnitZ()));
      const Eigen::Vector3d lo(-extents.behind, -extents.right, -extents.down);
      const Eigen::Vector3d hi(extents.ahead, extents.left, extents.up);
      out.centre = sensor + out.turn * (0.5 * (lo + hi));
      out.size = hi - lo;
      break;
    }
  }
  return out;
}

class SnapshotMap final : public FrameMap {
 public:
  SnapshotMap(std::shared_ptr<const Snapshot> map, const RegionExtents& extents) : map_(std::move(map)), extents_(extents) {}

  [[nodiscard]] std::size_t size() const override { return map_->size(); }
  [[nodiscard]] bool has_intensity() const override { return map_->config().attributes.intensity; }

  [[nodiscard]] std::vector<std::uint8_t> point_bytes() const override {
    const std::size_t floats = has_intensity() ? 4 : 3;
    std::vector<std::uint8_t> bytes(map_->size() * floats * sizeof(float));
    std::uint8_t* at = bytes.data();
    const auto put = [&](std::initializer_list<float> values) {
      for (const float v : values) {
        std::memcpy(at, &v, sizeof v);
        at += sizeof v;
      }
    };
    if (!has_intensity()) {
      // a vector's data is aligned for any scalar: its bytes hold the floats in place
      map_->copy_points(std::span<float>(reinterpret_cast<float*>(bytes.data()), 3 * map_->size()));
    } else {
      for (const HeldPoint& h : map_->points_with_attributes()) {
        put({float(h.point.x()), float(h.point.y()), float(h.point.z()), h.attributes.intensity});
      }
    }
    return bytes;
  }

  [[nodiscard]] std::vector<Eigen::Vector3d> voxel_centres(double voxel) const override { return map_->voxelize(voxel); }

  [[nodiscard]] RegionOutline region() const override {
    return region_outline(map_->config().region, extents_, map_->pose(), map_->ego_box());
  }

 private:
  std::shared_ptr<const Snapshot> map_;
  RegionExtents extents_;
};

io::PointCloud2 eco_cloud(const CloudBytes& bytes) {
  io::PointCloud2 out;
  out.stamp_ns = bytes.stamp_ns;
  out.frame_id = bytes.frame_id;
  out.height = bytes.height;
  out.width = bytes.width;
  for (const CloudBytes::Field& f : bytes.fields) out.fields.push_back({f.name, f.offset, io::FieldType(f.datatype), f.count});
  out.is_bigendian = bytes.is_bigendian;
  out.point_step = bytes.point_step;
  out.row_step = bytes.row_step;
  out.data = std::span<const std::uint8_t>(bytes.data, bytes.size);
  out.is_dense = bytes.is_dense;
  return out;
}

}  // namespace

struct MapSession::Impl {
  explicit Impl(NodeParameters p)
      : parameters(std::move(p)), tree(parameters.config), decoder(parameters.time) {
    if (parameters.node.odometry) {
      odometry.emplace(parameters.odometry_config, odometry::make_local_map("eco", parameters.odometry_config.map_settings()));
    }
  }

  /// Takes `frame` into the map; the frame's snapshot and what the update did.
  TakenFrame update(const workloads::WorkloadFrame& frame) {
    std::optional<workloads::AttributedScan> attributed;
    const ScanView scan = workloads::scan_for(frame, parameters.config.attributes, attributed);
    const auto start = std::chrono::steady_clock::now();
    const UpdateStats u = tree.update(frame.world_T_sensor, scan);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    TakenFrame out{std::make_shared<SnapshotMap>(tree.snapshot(), u.region),
                   {frames, u.scan_points, u.inserted, u.pruned + u.over_budget, u.cleared, tree.size(), ms},
                   frame.world_T_sensor};
    ++frames;
    return out;
  }

  /// A sweep as a frame of `eco run --data`'s: its points, intensities and times, numbered in turn.
  workloads::WorkloadFrame frame_of(DecodedSweep& sweep) const {
    workloads::WorkloadFrame frame;
    frame.index = frames;
    frame.time = seconds_of(sweep.stamp_ns);
    frame.points = std::move(sweep.points->cloud.points);
    frame.intensities = std::move(sweep.points->cloud.intensities);
    frame.point_times = std::move(sweep.points->cloud.times);
    return frame;
  }

  NodeParameters parameters;
  EgoOctree tree;
  io::CloudDecoder decoder;
  std::optional<odometry::Odometry> odometry;
  std::uint32_t frames = 0;
};

MapSession::MapSession(const ParameterLookup& lookup, const std::vector<std::string>& given)
    : impl_(std::make_unique<Impl>(read_parameters(lookup, given))) {}

MapSession::~MapSession() = default;

const NodeSettings& MapSession::settings() const { return impl_->parameters.node; }

std::string MapSession::help() { return describe_parameters(); }

DecodedSweep MapSession::decode(const CloudBytes& cloud, const std::string& source) {
  DecodedSweep out{std::make_shared<DecodedPoints>(), cloud.stamp_ns, cloud.frame_id};
  out.points->cloud = impl_->decoder.decode(eco_cloud(cloud), source);
  const std::vector<double>& times = out.points->cloud.times;
  const double stamp = seconds_of(cloud.stamp_ns);
  out.first = stamp + (times.empty() ? 0.0 : std::min(0.0, *std::ranges::min_element(times)));
  out.last = stamp + (times.empty() ? 0.0 : std::max(0.0, *std::ranges::max_element(times)));
  return out;
}

std::string MapSession::layout() const { return impl_->decoder.layout() ? impl_->decoder.layout()->describe() : ""; }

TakenFrame MapSession::take(DecodedSweep sweep, const PoseAtTime& pose_at) {
  workloads::WorkloadFrame frame = impl_->frame_of(sweep);
  const std::optional<Eigen::Isometry3d> at_stamp = pose_at(frame.time);
  if (!at_stamp) throw std::logic_error("eco_node: a cloud taken without its pose at its stamp");
  frame.world_T_sensor = *at_stamp;
  (void)workloads::place_frame_at_stamp(frame, pose_at);
  return impl_->update(frame);
}

TakenFrame MapSession::take_by_odometry(DecodedSweep sweep) {
  workloads::WorkloadFrame frame = impl_->frame_of(sweep);
  frame.world_T_sensor = impl_->odometry->register_frame(frame.points, frame.point_times).pose;
  frame.point_times.clear();  // the map takes the scan as registered, at its stamp
  return impl_->update(frame);
}

void MapSession::save(const std::string& path) const { impl_->tree.save(path); }
std::size_t MapSession::size() const { return impl_->tree.size(); }
std::uint32_t MapSession::frames() const { return impl_->frames; }

}  // namespace eco::ros_node
