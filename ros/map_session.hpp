#pragma once
// The node's map, as the ROS side (C++17, see node_settings.hpp) sees it: clouds in as bytes with
// their fields, taken in at the poses given or estimated; each frame out as a snapshot to publish
// from any thread. Behind it (map_session.cpp, C++20): the parameters' table, the decoder of a
// recording's clouds, the sweep's placement, the EgoOctree and the odometry, as `eco run --data`
// and `eco odometry` use them.

#include "node_settings.hpp"

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace eco::ros_node {

/// A ROS time in seconds, as eco::io reads a recording's stamps (the same double for the same stamp).
inline double seconds_of(std::int64_t nanoseconds) { return double(nanoseconds) * 1e-9; }

/// The cloud frame's pose in the fixed frame at a time [s]; nullopt where it is not known.
using PoseAtTime = std::function<std::optional<Eigen::Isometry3d>(double)>;

/// sensor_msgs/PointCloud2, its data viewed (not copied).
struct CloudBytes {
  struct Field {
    std::string name;
    std::uint32_t offset = 0;
    std::uint8_t datatype = 0;
    std::uint32_t count = 1;
  };
  std::int64_t stamp_ns = 0;
  std::string frame_id;
  std::uint32_t height = 0, width = 0;
  std::vector<Field> fields;
  bool is_bigendian = false;
  std::uint32_t point_step = 0, row_step = 0;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  bool is_dense = false;
};

struct DecodedPoints;  // the points, intensities and times of one cloud (map_session.cpp)

/// A decoded cloud, waiting for its poses.
struct DecodedSweep {
  std::shared_ptr<DecodedPoints> points;
  std::int64_t stamp_ns = 0;
  std::string frame_id;
  double first = 0.0, last = 0.0;  ///< [s] the times of its points, its stamp included
};

/// The region a frame's map holds, as a marker draws it: a box (the cube, or an oriented box) or
/// a ball, in the fixed frame.
struct RegionOutline {
  bool ball = false;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Quaterniond turn = Eigen::Quaterniond::Identity();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< the box's sides, or the ball's diameter on each axis
};

/// One frame's map (a snapshot: unchanged by later updates, read from any thread).
class FrameMap {
 public:
  virtual ~FrameMap() = default;
  [[nodiscard]] virtual std::size_t size() const = 0;
  [[nodiscard]] virtual bool has_intensity() const = 0;
  /// Every held point as float32 x, y, z (then intensity, when kept), packed, in the fixed frame.
  [[nodiscard]] virtual std::vector<std::uint8_t> point_bytes() const = 0;
  /// The centres of the occupied voxels of side `voxel` [m].
  [[nodiscard]] virtual std::vector<Eigen::Vector3d> voxel_centres(double voxel) const = 0;
  [[nodiscard]] virtual RegionOutline region() const = 0;
};

/// What one update did.
struct FrameStats {
  std::uint32_t frame = 0;  ///< frames taken before this one
  std::size_t scan_points = 0, inserted = 0, pruned = 0, cleared = 0, held = 0;
  double update_ms = 0.0;   ///< EgoOctree::update alone
};

struct TakenFrame {
  std::shared_ptr<const FrameMap> map;
  FrameStats stats;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< where the cloud was taken
};

/// A parameter's value as text (a number, true/false, or a string), or nullopt when it is not set.
using ParameterLookup = std::function<std::optional<std::string>(const std::string& name)>;

class MapSession {
 public:
  /// The map and node the parameters describe (names without ~; `given`: every private
  /// parameter set). Throws std::invalid_argument naming the parameter and its value.
  MapSession(const ParameterLookup& lookup, const std::vector<std::string>& given);
  ~MapSession();
  MapSession(const MapSession&) = delete;
  MapSession& operator=(const MapSession&) = delete;

  [[nodiscard]] const NodeSettings& settings() const;
  /// The parameters, a line each, for `eco_node --help`.
  [[nodiscard]] static std::string help();

  /// Decodes a cloud (the first fixes the layout, as a recording's). Throws std::runtime_error
  /// naming `source` for a cloud that cannot be read.
  [[nodiscard]] DecodedSweep decode(const CloudBytes& cloud, const std::string& source);
  /// "time: field t (uint32) in ns after the header stamp; ..." once a cloud was decoded, else "".
  [[nodiscard]] std::string layout() const;

  /// Takes `sweep` into the map at the poses `pose_at` gives (known at its stamp): each point
  /// placed at its own time where the poses reach, as `eco run --data` places a recording's.
  [[nodiscard]] TakenFrame take(DecodedSweep sweep, const PoseAtTime& pose_at);
  /// Estimates `sweep`'s pose by ECO's odometry, then takes it into the map there.
  [[nodiscard]] TakenFrame take_by_odometry(DecodedSweep sweep);

  /// EgoOctree::save. Throws what it throws.
  void save(const std::string& path) const;
  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] std::uint32_t frames() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace eco::ros_node
