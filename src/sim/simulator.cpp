#include <eco/sim/simulator.hpp>

#include <eco/io/kitti_sequence.hpp>

#include "sim/city.hpp"
#include "sim/manoeuvre.hpp"
#include "sim/ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace eco::sim {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

void require(bool ok, const char* field, double value, const char* rule) {
  if (!ok) {
    throw std::invalid_argument(std::string("eco::sim::SimConfig: ") + field + " = " +
                                std::to_string(value) + " " + rule);
  }
}

}  // namespace

const std::map<std::string, Manoeuvre>& manoeuvre_names() {
  static const std::map<std::string, Manoeuvre> names{
      {"route", Manoeuvre::Route}, {"straight", Manoeuvre::Straight}, {"uturn", Manoeuvre::UTurn},
      {"roundabout", Manoeuvre::Roundabout}, {"spin", Manoeuvre::Spin}, {"still", Manoeuvre::Still}};
  return names;
}

void SimConfig::validate() const {
  require(frames >= 1, "frames", static_cast<double>(frames), "must be at least 1");
  require(rate_hz > 0.0 && std::isfinite(rate_hz), "rate_hz", rate_hz, "must be positive");
  require(speed >= 0.0 && speed <= 100.0, "speed", speed, "must be in [0, 100] m/s");
  require(sway_deg >= 0.0 && sway_deg <= 10.0, "sway_deg", sway_deg, "must be in [0, 10]");
  require(spin_rate_deg >= -1e4 && spin_rate_deg <= 1e4, "spin_rate_deg", spin_rate_deg, "must be in [-10000, 10000]");
  require(roundabout_radius >= 3.0 && roundabout_radius <= city.road_half_width, "roundabout_radius", roundabout_radius,
          "must be in [3, city.road_half_width]: inside the intersection");
  const LidarModel& l = lidar;
  require(l.beams >= 1 && l.beams <= 1024, "lidar.beams", l.beams, "must be in [1, 1024]");
  require(l.columns >= 1 && l.columns <= 100000, "lidar.columns", l.columns, "must be in [1, 100000]");
  require(l.fov_up_deg <= 90.0, "lidar.fov_up_deg", l.fov_up_deg, "must be at most 90");
  require(l.fov_down_deg >= -90.0 && l.fov_down_deg < l.fov_up_deg, "lidar.fov_down_deg",
          l.fov_down_deg, "must be in [-90, fov_up_deg)");
  require(l.min_range >= 0.0, "lidar.min_range", l.min_range, "must not be negative");
  require(l.max_range > l.min_range && l.max_range <= 1000.0, "lidar.max_range", l.max_range,
          "must be in (min_range, 1000]");
  require(l.range_noise >= 0.0 && l.range_noise <= 1.0, "lidar.range_noise", l.range_noise, "must be in [0, 1]");
  require(l.dropout >= 0.0 && l.dropout < 1.0, "lidar.dropout", l.dropout, "must be in [0, 1)");
  require(l.mount_height > 0.0 && l.mount_height <= 10.0, "lidar.mount_height", l.mount_height, "must be in (0, 10]");
  const CityModel& c = city;
  require(c.road_half_width > 0.0, "city.road_half_width", c.road_half_width, "must be positive");
  require(c.lane_offset > 0.0 && c.lane_offset < c.road_half_width, "city.lane_offset", c.lane_offset,
          "must be in (0, road_half_width)");
  require(c.turn_radius > c.lane_offset && c.turn_radius <= c.road_half_width, "city.turn_radius",
          c.turn_radius, "must be in (lane_offset, road_half_width]");
  require(c.block_pitch >= 2.0 * c.road_half_width + 40.0 && c.block_pitch <= 1000.0, "city.block_pitch",
          c.block_pitch, "must be in [2 road_half_width + 40, 1000]");
  require(c.cars_per_intersection >= 0.0 && c.cars_per_intersection <= 50.0, "city.cars_per_intersection",
          c.cars_per_intersection, "must be in [0, 50]");
  require(c.parked_car_chance >= 0.0 && c.parked_car_chance <= 1.0, "city.parked_car_chance",
          c.parked_car_chance, "must be in [0, 1]");
}

struct Simulator::Impl {
  explicit Impl(const SimConfig& c) : config((c.validate(), c)), city(build_city(config)), caster(city) {}

  SimConfig config;
  City city;
  RayCaster caster;
};

Simulator::Simulator(const SimConfig& config) : impl_(std::make_unique<Impl>(config)) {}
Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

std::size_t Simulator::size() const { return impl_->config.frames; }
const SimConfig& Simulator::config() const { return impl_->config; }
std::size_t Simulator::static_shape_count() const {
  const City& c = impl_->city;
  return c.boxes.size() + c.cylinders.size() + c.spheres.size();
}

Eigen::Isometry3d Simulator::pose(std::size_t index) const {
  const SimConfig& c = impl_->config;
  if (index >= c.frames) {
    throw std::out_of_range("eco::sim::Simulator: frame " + std::to_string(index) + " of " +
                            std::to_string(c.frames));
  }
  return pose_at(static_cast<double>(index) / c.rate_hz);
}

Eigen::Isometry3d Simulator::pose_at(double t) const {
  const SimConfig& c = impl_->config;
  const RoutePoint p = manoeuvre_at(c, impl_->city.routes[0], t);
  const double sway = c.sway_deg * kDegree;
  const double pitch = sway * std::sin(2.0 * std::numbers::pi * t / 2.3);
  const double roll = sway * std::sin(2.0 * std::numbers::pi * t / 3.1 + 1.0);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(p.position.x(), p.position.y(), c.lidar.mount_height);
  pose.linear() = (Eigen::AngleAxisd(p.heading, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX())).toRotationMatrix();
  return pose;
}

SimFrame Simulator::frame(std::size_t index) const {
  const SimConfig& c = impl_->config;
  const LidarModel& lidar = c.lidar;
  SimFrame frame;
  frame.index = index;
  frame.world_T_lidar = pose(index);
  frame.time = static_cast<double>(index) / c.rate_hz;

  const Eigen::Vector3d origin = frame.world_T_lidar.translation();
  std::vector<TurnedBox> cars;  // the moving cars within reach at this instant
  for (const MovingCar& car : impl_->city.cars) {
    const std::size_t before = cars.size();
    car_bodies(impl_->city, car, c.city.lane_offset, frame.time, cars);
    const bool out_of_reach = cars.size() > before && (cars[before].centre - origin).head<2>().norm() > lidar.max_range + 5.0;
    if (out_of_reach) cars.resize(before);
  }

  // where each column fires from: the frame's pose, or with a rolling sweep the pose at its time
  std::vector<Eigen::Isometry3d> column_poses(lidar.rolling_sweep ? static_cast<std::size_t>(lidar.columns) : 1,
                                              frame.world_T_lidar);
  std::vector<double> column_times(column_poses.size(), 0.0);
  for (std::size_t col = 1; col < column_poses.size(); ++col) {
    column_times[col] = static_cast<double>(col) / static_cast<double>(lidar.columns) / c.rate_hz;
    column_poses[col] = pose_at(frame.time + column_times[col]);
  }

  Rng rng(c.seed, 0x5CA7000000000000ull + index);
  const std::size_t rays = static_cast<std::size_t>(lidar.beams) * static_cast<std::size_t>(lidar.columns);
  frame.cloud.points.reserve(rays);
  frame.cloud.intensity.reserve(rays);
  frame.labels.reserve(rays);
  for (int b = 0; b < lidar.beams; ++b) {
    const double fraction = lidar.beams > 1 ? static_cast<double>(b) / (lidar.beams - 1) : 0.0;
    const double elevation = (lidar.fov_up_deg + fraction * (lidar.fov_down_deg - lidar.fov_up_deg)) * kDegree;
    for (int col = 0; col < lidar.columns; ++col) {
      if (rng.chance(lidar.dropout)) continue;
      const double azimuth = 2.0 * std::numbers::pi * col / lidar.columns;
      const Eigen::Vector3d in_sensor(std::cos(elevation) * std::cos(azimuth),
                                      std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
      const std::size_t fired = lidar.rolling_sweep ? static_cast<std::size_t>(col) : 0;
      const Ray ray{column_poses[fired].translation(), column_poses[fired].linear() * in_sensor};
      const auto hit = impl_->caster.cast(ray, lidar.max_range, cars);
      if (!hit || hit->t < lidar.min_range) continue;
      const double range = hit->t + lidar.range_noise * rng.normal();
      const double incidence = std::abs(hit->normal.dot(ray.direction));
      const double reflectance = hit->albedo * (0.3 + 0.7 * incidence) + 0.02 * rng.normal();
      frame.cloud.points.push_back((range * in_sensor).cast<float>());
      frame.cloud.intensity.push_back(static_cast<float>(std::clamp(reflectance, 0.0, 1.0)));
      frame.labels.push_back(hit->label);
      if (lidar.rolling_sweep) frame.point_times.push_back(column_times[fired]);
    }
  }
  return frame;
}

void Simulator::write_kitti(const std::filesystem::path& folder) const {
  io::KittiWriter writer(folder, io::kitti_velo_to_cam());
  for (std::size_t i = 0; i < size(); ++i) {
    const SimFrame f = frame(i);
    writer.write(f.world_T_lidar, f.cloud, f.labels, f.time);
  }
}

}  // namespace eco::sim
