// eco.sim: the LiDAR simulator's configuration, field for field with eco::sim::SimConfig, and
// the Simulator, whose frames come out as (pose, points) numpy pairs.

#include "bindings.hpp"
#include "records.hpp"
#include "scans.hpp"

#include <eco/sim/simulator.hpp>

#include <pybind11/stl/filesystem.h>

namespace eco::python {

using sim::CityModel;
using sim::LidarModel;
using sim::SimConfig;

template <>
struct Record<LidarModel> {
  static constexpr const char* name = "LidarModel";
  static std::vector<Field<LidarModel>> fields() {
    return {
        field("beams", &LidarModel::beams,
              "laser beams, spread evenly over the vertical field of view"),
        field("fov_up_deg", &LidarModel::fov_up_deg,
              "[deg] upper edge of the vertical field of view"),
        field("fov_down_deg", &LidarModel::fov_down_deg, "[deg] lower edge"),
        field("columns", &LidarModel::columns, "firings per revolution (360 degrees)"),
        field("min_range", &LidarModel::min_range, "[m] nearer returns are dropped (the vehicle)"),
        field("max_range", &LidarModel::max_range, "[m]"),
        field("range_noise", &LidarModel::range_noise, "[m] standard deviation of range noise"),
        field("dropout", &LidarModel::dropout, "probability that a return is lost"),
        field("mount_height", &LidarModel::mount_height, "[m] above the road"),
        field("rolling_sweep", &LidarModel::rolling_sweep,
              "columns fired over the frame's period from where the sensor then is: smear, and per-point times"),
    };
  }
};

template <>
struct Record<CityModel> {
  static constexpr const char* name = "CityModel";
  static std::vector<Field<CityModel>> fields() {
    return {
        field("block_pitch", &CityModel::block_pitch, "[m] between parallel street centre lines"),
        field("road_half_width", &CityModel::road_half_width, "[m] centre line to kerb"),
        field("lane_offset", &CityModel::lane_offset, "[m] centre line to the right-hand lane"),
        field("turn_radius", &CityModel::turn_radius, "[m] of the centre line through a corner"),
        field("cars_per_intersection", &CityModel::cars_per_intersection,
              "moving cars that set off from each intersection the route passes, on average"),
        field("parked_car_chance", &CityModel::parked_car_chance, "per kerb-side parking slot"),
    };
  }
};

template <>
struct Record<SimConfig> {
  static constexpr const char* name = "SimConfig";
  static std::vector<Field<SimConfig>> fields() {
    return {
        field("seed", &SimConfig::seed, "everything random is drawn from it"),
        field("frames", &SimConfig::frames, "length of the drive"),
        field("rate_hz", &SimConfig::rate_hz, "[Hz] scans per second"),
        field("speed", &SimConfig::speed, "[m/s] of the sensor vehicle"),
        field("manoeuvre", &SimConfig::manoeuvre, "Manoeuvre: how the vehicle moves (route by default)"),
        field("spin_rate_deg", &SimConfig::spin_rate_deg, "[deg/s] Manoeuvre.spin's"),
        field("roundabout_radius", &SimConfig::roundabout_radius, "[m] Manoeuvre.roundabout's"),
        field("sway_deg", &SimConfig::sway_deg, "[deg] amplitude of the vehicle's roll and pitch"),
        field("lidar", &SimConfig::lidar, "LidarModel (or a dict of its fields)"),
        field("city", &SimConfig::city, "CityModel (or a dict of its fields)"),
    };
  }
};

namespace {

/// The simulator makes the labels with the points, so a frame is always made whole.
ScanData simulated(const sim::Simulator& simulator, std::size_t i, FrameParts /*parts*/) {
  sim::SimFrame frame = simulator.frame(i);
  ScanData data;
  data.index = i;
  data.time = frame.time;
  data.pose = frame.world_T_lidar;
  data.cloud = std::move(frame.cloud);
  data.labels = std::move(frame.labels);
  if (!frame.point_times.empty()) data.point_times = std::move(frame.point_times);
  return data;
}

constexpr const char* kSimulatorDoc =
    R"(A LiDAR drive through a procedural city, for running ECO with no download.

Simulator(config=None, **fields) takes a SimConfig or its fields as keyword arguments, e.g.
Simulator(frames=50, seed=3, lidar={"columns": 1000}). Deterministic: the same configuration gives
the same frames on every machine. Frames are computed on demand, in any order; iterating yields
(pose (4, 4) float64 world_T_lidar, points (N, 3) float32 lidar frame) pairs. An HDL-64E-like
sensor on a car at 10 m/s, 10 Hz; returns from moving cars carry label 252.)";

}  // namespace

void bind_sim(py::module_& s) {
  py::enum_<sim::Manoeuvre>(s, "Manoeuvre", "How the simulated vehicle moves (SimConfig.manoeuvre).")
      .value("route", sim::Manoeuvre::Route, "The streets, going straight or turning at each intersection. Default.")
      .value("straight", sim::Manoeuvre::Straight, "One street east, never turning.")
      .value("uturn", sim::Manoeuvre::UTurn, "East 40 m, a U-turn across the street, back west, a U-turn, again.")
      .value("roundabout", sim::Manoeuvre::Roundabout, "Round the first intersection, anticlockwise.")
      .value("spin", sim::Manoeuvre::Spin, "Standing on the street, turning in place at spin_rate_deg.")
      .value("still", sim::Manoeuvre::Still, "Standing on the street.");
  bind_record<LidarModel>(s, "The simulated sensor.", Access::ReadWrite);
  bind_record<CityModel>(s, "The simulated city.", Access::ReadWrite);
  bind_record<SimConfig>(s, "Configuration of a Simulator (eco::sim::SimConfig).",
                         Access::ReadWrite);

  py::class_<sim::Simulator> simulator_class(s, "Simulator", kSimulatorDoc);
  def_frames(simulator_class, "Frames in the drive (config.frames).", "frame",
             "Frame `index` with its time, reflectance and labels (an eco.io.Scan).", &simulated);
  simulator_class
      .def(py::init([](const py::object& config, const py::kwargs& fields) {
             return sim::Simulator(config_or_fields<SimConfig>(config, fields, "Simulator"));
           }),
           py::arg("config") = py::none())
      .def(
          "pose",
          [](const sim::Simulator& simulator, std::ptrdiff_t index) {
            return matrix_array(simulator.pose(sequence_index(index, simulator.size())));
          },
          py::arg("index"), "The pose (4, 4) of frame `index`, without simulating its scan.")
      .def(
          "write_kitti",
          [](const sim::Simulator& simulator, const std::filesystem::path& folder) {
            py::gil_scoped_release no_gil;
            simulator.write_kitti(folder);
          },
          py::arg("folder"),
          "Writes every frame to `folder` in KITTI's layout (velodyne/, labels/, poses.txt in the "
          "camera frame with calib.txt, times.txt); eco.io.KittiSequence reads it back.")
      .def_property_readonly(
          "config", [](const sim::Simulator& simulator) { return simulator.config(); },
          "The SimConfig (a copy: a simulator's configuration is fixed).")
      .def("__repr__", [](const sim::Simulator& simulator) {
        return "Simulator(frames=" + std::to_string(simulator.size()) +
               ", seed=" + std::to_string(simulator.config().seed) + ")";
      });
}

}  // namespace eco::python
