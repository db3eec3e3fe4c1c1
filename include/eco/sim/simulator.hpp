#pragma once
/// @file simulator.hpp
/// A LiDAR simulator for running ECO with no download: a procedural city (road, kerbs and
/// sidewalks, building façades, poles, trees, parked cars) with cars driving their own routes,
/// scanned by an HDL-64E-like sensor on a vehicle that drives the streets at 10 Hz.
/// Deterministic: the same configuration and seed give the same bytes on every machine.
/// Frames are computed on demand (random access), and can be written in KITTI's layout with
/// SemanticKITTI labels marking the returns that hit moving cars.

#include <eco/io/point_cloud.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace eco::sim {

/// The sensor: beams spread evenly over the vertical field of view, columns over 360 degrees.
struct LidarModel {
  int beams = 64;
  double fov_up_deg = 2.0;
  double fov_down_deg = -24.9;
  int columns = 2000;
  double min_range = 2.5;          ///< [m] nearer returns are dropped (the vehicle itself)
  double max_range = 120.0;        ///< [m]
  double range_noise = 0.02;       ///< [m] standard deviation of Gaussian range noise
  double dropout = 0.02;           ///< probability that a return is lost
  double mount_height = 1.73;      ///< [m] above the road, as on KITTI's car
  /// The columns fired one after another over the frame's period, each from where the sensor is
  /// then, as a spinning LiDAR does: a moving sensor's scan is smeared, and each point carries its
  /// time (SimFrame::point_times). False: every ray from the frame's pose at once.
  bool rolling_sweep = false;
};

/// The city: a grid of streets `block_pitch` apart; everything else is drawn from the seed.
struct CityModel {
  double block_pitch = 80.0;       ///< [m] between parallel street centre lines
  double road_half_width = 7.0;    ///< [m] centre line to kerb
  double lane_offset = 2.5;        ///< [m] centre line to the middle of the right-hand lane
  double turn_radius = 7.0;        ///< [m] of the centre line through a corner
  /// Moving cars that set off from each intersection the sensor's route passes, on average
  /// (Poisson), each on a route of its own, as the sensor nears it; one more leads the sensor.
  double cars_per_intersection = 1.0;
  double parked_car_chance = 0.5;  ///< per kerb-side parking slot
};

/// How the sensor vehicle moves through the city (SimConfig::manoeuvre), on the right-hand lane.
enum class Manoeuvre {
  Route,       ///< the streets, going straight or turning at each intersection (the default)
  Straight,    ///< one street east, never turning: a motorway's straight
  UTurn,       ///< east 40 m, a U-turn across the street, back west, a U-turn, and again
  Roundabout,  ///< round the first intersection, anticlockwise, on a circle of roundabout_radius
  Spin,        ///< standing on the street, turning in place at spin_rate_deg
  Still,       ///< standing on the street
};

/// Each manoeuvre by the name the eco command gives it: route, straight, uturn, roundabout, spin, still.
[[nodiscard]] const std::map<std::string, Manoeuvre>& manoeuvre_names();

struct SimConfig {
  std::uint64_t seed = 1;
  std::size_t frames = 100;
  double rate_hz = 10.0;
  double speed = 10.0;             ///< [m/s] of the sensor vehicle: 1 m per frame at 10 Hz
  Manoeuvre manoeuvre = Manoeuvre::Route;
  double spin_rate_deg = 1000.0;   ///< [deg/s] Spin's
  double roundabout_radius = 6.0;  ///< [m] Roundabout's: at 9.42 m/s it turns 90 deg/s
  double sway_deg = 0.3;           ///< amplitude of the vehicle's roll and pitch
  LidarModel lidar;
  CityModel city;

  /// Throws std::invalid_argument naming the first field out of range.
  void validate() const;
};

struct SimFrame {
  std::size_t index = 0;
  double time = 0.0;                                ///< [s] index / rate_hz
  Eigen::Isometry3d world_T_lidar = Eigen::Isometry3d::Identity();
  io::PointCloud cloud;                             ///< lidar frame, with reflectance in [0, 1]
  std::vector<std::uint32_t> labels;                ///< SemanticKITTI id per point (io::label)
  /// [s] after `time` each point was measured, in the frame of the sensor then (rolling_sweep);
  /// empty without a rolling sweep.
  std::vector<double> point_times;
};

class Simulator {
 public:
  explicit Simulator(const SimConfig& config = {});
  ~Simulator();
  Simulator(Simulator&&) noexcept;
  Simulator& operator=(Simulator&&) noexcept;

  [[nodiscard]] std::size_t size() const;           ///< config().frames
  /// Frame `index` (any order; throws std::out_of_range past size()).
  [[nodiscard]] SimFrame frame(std::size_t index) const;
  [[nodiscard]] Eigen::Isometry3d pose(std::size_t index) const;
  /// The sensor's pose at `time` seconds into the drive (pose(i) is pose_at(i / rate_hz)).
  [[nodiscard]] Eigen::Isometry3d pose_at(double time) const;
  [[nodiscard]] const SimConfig& config() const;
  [[nodiscard]] std::size_t static_shape_count() const;

  /// Writes every frame to `folder` in KITTI's layout: velodyne/, labels/, poses.txt
  /// (camera-frame, with calib.txt holding KITTI's Tr) and times.txt.
  void write_kitti(const std::filesystem::path& folder) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace eco::sim
