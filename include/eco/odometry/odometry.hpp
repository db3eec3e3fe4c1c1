#pragma once
/// @file odometry.hpp
/// A scan-to-map LiDAR odometry on a LocalMap (local_map.hpp), compact enough to read in one
/// sitting: each scan is range-filtered, voxel-downsampled twice (a finer copy for the map, a
/// coarser one to register), predicted by constant velocity, registered point-to-plane against
/// the map's k nearest points (a Geman–McClure kernel, a correspondence threshold that adapts to
/// how far the motion model has been wrong), then handed to the map at the estimated pose.
///
///   Odometry odo(OdometryConfig{}, make_local_map("eco", settings));
///   for (each scan) odo.register_frame(scan);   // FrameReport: pose, timings, iterations
///   odo.poses();                                // world_T_sensor of every frame

#include <eco/odometry/local_map.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace eco::odometry {

struct OdometryConfig {
  double max_range = 100.0;       ///< [m] farther returns are dropped
  double min_range = 2.0;         ///< [m] nearer returns are dropped (the vehicle itself)
  /// [m] the map's cell (MapSettings::cell_size); the scan goes to the map downsampled to half
  /// of it, and is registered downsampled to 1.5 times it. KISS-ICP's choice: max_range / 100.
  double voxel_size = 1.0;
  std::uint32_t max_points_per_voxel = 20;  ///< MapSettings::max_points
  double box_side = 200.0;        ///< [m] MapSettings::box_side: the map reaches max_range around the sensor
  std::size_t neighbours = 5;     ///< k: the map points each plane is fitted to
  double plane_tolerance = 0.2;   ///< [m] a plane is used when all k points lie this close to it
  /// [voxels] ... and within this many voxel_size of the point registered, as a voxel-hash map's
  /// 27 voxels around it would hold them: k points from farther (a sparse part of the map, or a
  /// point not yet near its surface) make a plane of little worth.
  double plane_reach = 1.0;
  double initial_threshold = 2.0; ///< [m] the motion model's error assumed before it has samples
  double min_motion = 0.1;        ///< [m] model errors below this are not sampled
  int max_iterations = 50;
  double convergence = 1e-4;      ///< stop once a step moves the pose less than this [m, rad]
  unsigned threads = 1;           ///< MapSettings::threads
  /// Correct each scan for the sensor's motion during its sweep, from its points' times (when
  /// register_frame is given them): constant velocity, the last frame's motion spread over the
  /// sweep, each point moved to where the sensor was at the scan's stamp (time 0), as KISS-ICP does
  /// about the sweep's middle.
  bool deskew = true;

  /// Throws std::invalid_argument naming the first value out of range.
  void validate() const;
  /// The map's settings these imply.
  [[nodiscard]] MapSettings map_settings() const;
};

/// One frame's outcome.
struct FrameReport {
  std::size_t index = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< world_T_sensor estimated
  bool registered = false;         ///< false: the first frame, or a scan with no usable point (pose predicted)
  std::size_t scan_points = 0;     ///< as given
  std::size_t dropped_invalid = 0; ///< not finite
  std::size_t dropped_range = 0;   ///< nearer than min_range or farther than max_range
  bool deskewed = false;           ///< the scan was corrected for the motion during its sweep
  std::size_t map_input = 0;       ///< points handed to the map
  std::size_t source = 0;          ///< points registered
  int iterations = 0;
  std::size_t correspondences = 0; ///< in the last iteration
  std::size_t inliers = 0;         ///< of those, within a tenth of voxel_size of their plane
  double threshold = 0.0;          ///< [m] the correspondence distance used
  std::size_t map_points = 0;      ///< held after the update
  // [ms]
  double preprocess_ms = 0.0;      ///< range filter
  double downsample_ms = 0.0;      ///< both voxel downsamplings
  double query_ms = 0.0;           ///< the map's KNN, every iteration
  double solve_ms = 0.0;           ///< planes, normal equations, pose steps
  double update_ms = 0.0;          ///< the map's update
  double total_ms = 0.0;
  /// Minor page faults of the process: during the odometry's own preprocessing and downsampling
  /// (which allocate, as any client's do), and during the map's queries and update.
  std::size_t own_faults = 0;
  std::size_t map_faults = 0;
};

class Odometry {
 public:
  /// Throws std::invalid_argument for a bad configuration or a null map.
  Odometry(const OdometryConfig& config, std::unique_ptr<LocalMap> map);
  ~Odometry();
  Odometry(Odometry&&) noexcept;
  Odometry& operator=(Odometry&&) noexcept;

  /// Registers `scan` (sensor frame) and adds it to the map. The first frame is placed at
  /// `start` (set_start), with nothing to register against. `point_times`, when given, holds
  /// each point's time in seconds after the scan's stamp (the instant its pose is estimated
  /// for), one per point: the sweep they span is taken as one frame's motion, for deskewing.
  /// Throws std::invalid_argument when their count is not the scan's.
  FrameReport register_frame(ScanView scan, std::span<const double> point_times = {});
  /// Where the first frame lies (default the identity): a reference trajectory's first pose, so
  /// that the estimate shares its world frame. Only before the first frame.
  void set_start(const Eigen::Isometry3d& world_T_sensor);

  [[nodiscard]] const std::vector<Eigen::Isometry3d>& poses() const;
  [[nodiscard]] const LocalMap& map() const;
  [[nodiscard]] const OdometryConfig& config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace eco::odometry
