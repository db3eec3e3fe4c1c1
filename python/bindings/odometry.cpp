// eco.odometry: the LiDAR odometry on ECO's map (eco/odometry/odometry.hpp), its settings field
// for field with OdometryConfig, its frame reports, and the trajectory errors.

#include "bindings.hpp"
#include "records.hpp"

#include <eco/odometry/odometry.hpp>
#include <eco/odometry/trajectory_errors.hpp>

#include <pybind11/stl.h>

namespace eco::python {

using odometry::FrameReport;
using odometry::OdometryConfig;

template <>
struct Record<OdometryConfig> {
  static constexpr const char* name = "OdometryConfig";
  static std::vector<Field<OdometryConfig>> fields() {
    return {
        field("max_range", &OdometryConfig::max_range, "[m] farther returns are dropped"),
        field("min_range", &OdometryConfig::min_range, "[m] nearer returns are dropped (the vehicle)"),
        field("voxel_size", &OdometryConfig::voxel_size,
              "[m] the map's voxel; the scan goes in at half, is registered at 1.5 times it"),
        field("max_points_per_voxel", &OdometryConfig::max_points_per_voxel, "the map's density cap"),
        field("box_side", &OdometryConfig::box_side, "[m] side of the cube the map holds around the sensor"),
        field("neighbours", &OdometryConfig::neighbours, "k: map points each plane is fitted to"),
        field("plane_tolerance", &OdometryConfig::plane_tolerance, "[m] all k points this close to their plane"),
        field("plane_reach", &OdometryConfig::plane_reach, "[voxels] all k points this close to the point registered"),
        field("initial_threshold", &OdometryConfig::initial_threshold,
              "[m] the motion model's error assumed before it has samples"),
        field("min_motion", &OdometryConfig::min_motion, "[m] model errors below this are not sampled"),
        field("max_iterations", &OdometryConfig::max_iterations, "ICP iterations at most"),
        field("convergence", &OdometryConfig::convergence, "a step under this ends the iterations [m, rad]"),
        field("threads", &OdometryConfig::threads, "threads ECO's batch KNN spreads the queries over"),
        field("deskew", &OdometryConfig::deskew, "correct scans given point times for the motion during their sweep"),
    };
  }
};

template <>
struct Record<FrameReport> {
  static constexpr const char* name = "FrameReport";
  static std::vector<Field<FrameReport>> fields() {
    return {
        field("index", &FrameReport::index, "the frame's number"),
        field("registered", &FrameReport::registered, "False: the first frame, or nothing usable (pose predicted)"),
        field("scan_points", &FrameReport::scan_points, "points given"),
        field("dropped_invalid", &FrameReport::dropped_invalid, "points not finite"),
        field("dropped_range", &FrameReport::dropped_range, "points out of [min_range, max_range]"),
        field("deskewed", &FrameReport::deskewed, "the scan was corrected for the motion during its sweep"),
        field("map_input", &FrameReport::map_input, "points handed to the map"),
        field("source", &FrameReport::source, "points registered"),
        field("iterations", &FrameReport::iterations, "ICP iterations"),
        field("correspondences", &FrameReport::correspondences, "planes used in the last iteration"),
        field("inliers", &FrameReport::inliers, "of those, within a tenth of voxel_size of their plane"),
        field("threshold", &FrameReport::threshold, "[m] the correspondence distance used"),
        field("map_points", &FrameReport::map_points, "held after the update"),
        field("preprocess_ms", &FrameReport::preprocess_ms, "[ms] range filter"),
        field("downsample_ms", &FrameReport::downsample_ms, "[ms] both voxel downsamplings"),
        field("query_ms", &FrameReport::query_ms, "[ms] the map's KNN"),
        field("solve_ms", &FrameReport::solve_ms, "[ms] planes and pose steps"),
        field("update_ms", &FrameReport::update_ms, "[ms] the map's update"),
        field("total_ms", &FrameReport::total_ms, "[ms] the frame"),
        field("own_faults", &FrameReport::own_faults, "page faults in preprocessing and downsampling"),
        field("map_faults", &FrameReport::map_faults, "page faults in the map's queries and update"),
    };
  }
};

namespace {

constexpr const char* kOdometryDoc =
    R"(A scan-to-map LiDAR odometry on a local map: each scan range-filtered, voxel-downsampled, predicted
by constant velocity, registered point-to-plane against the map's k nearest points, then added to the
map at the estimated pose.

Odometry(map="eco", config=None, **fields) takes an OdometryConfig or its fields as keyword
arguments, e.g. Odometry(max_range=40, voxel_size=0.4). map is "eco" (an EgoOctree, its density cap
the map's downsampling) or "voxel_hash" (KISS-ICP's map, approximate); the command `eco odometry`
also runs nanoflann's k-d tree and PCL's octree.

    odo = eco.odometry.Odometry()
    for reference, points in eco.sim.Simulator(frames=100):
        report = odo.register_frame(points)      # a FrameReport: pose, timings, iterations
    eco.odometry.trajectory_errors(odo.poses, reference_poses))";

py::array_t<double> poses_array(const std::vector<Eigen::Isometry3d>& poses) {
  py::array_t<double> out({poses.size(), std::size_t(4), std::size_t(4)});
  auto view = out.mutable_unchecked<3>();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) view(i, r, c) = poses[i].matrix()(r, c);
    }
  }
  return out;
}

std::vector<Eigen::Isometry3d> poses_arg(const py::handle& object, const char* name) {
  std::vector<Eigen::Isometry3d> poses;
  for (const py::handle pose : py::iter(object)) poses.push_back(pose_arg(pose, name));
  return poses;
}

}  // namespace

void bind_odometry(py::module_& o) {
  bind_record<OdometryConfig>(o, "Settings of an Odometry (eco::odometry::OdometryConfig).", Access::ReadWrite);
  bind_record<FrameReport>(o, "What one frame of an Odometry did.", Access::ReadOnly)
      .def_property_readonly(
          "pose", [](const FrameReport& r) { return matrix_array(r.pose); }, "(4, 4) world_T_sensor estimated");

  py::class_<odometry::Odometry>(o, "Odometry", kOdometryDoc)
      .def(py::init([](const std::string& map, const py::object& config, const py::kwargs& fields) {
             const OdometryConfig c = config_or_fields<OdometryConfig>(config, fields, "Odometry");
             return odometry::Odometry(c, odometry::make_local_map(map, c.map_settings()));
           }),
           py::arg("map") = "eco", py::arg("config") = py::none())
      .def(
          "register_frame",
          [](odometry::Odometry& odo, const py::handle& points, const py::object& times) {
            const Rows3 rows(points, "points", false);
            std::vector<float> storage;
            const ScanView scan = rows.scan(storage);
            std::vector<double> point_times;
            if (!times.is_none()) {
              const py::array_t<double, py::array::forcecast> values(times);
              if (values.ndim() != 1 || std::size_t(values.shape(0)) != rows.size()) {
                throw py::value_error("times must have shape (" + std::to_string(rows.size()) + ",), one per point");
              }
              point_times.assign(values.data(), values.data() + rows.size());
            }
            py::gil_scoped_release no_gil;
            return odo.register_frame(scan, point_times);
          },
          py::arg("points"), py::arg("times") = py::none(),
          "Registers an (N, 3) scan (sensor frame; points not finite or out of range are skipped and "
          "counted) and adds it to the map. `times`: (N,) seconds of each point after the scan's stamp "
          "(eco.io.Scan.point_times), for deskewing. Returns its FrameReport.")
      .def(
          "set_start", [](odometry::Odometry& odo, const py::handle& pose) { odo.set_start(pose_arg(pose, "pose")); },
          py::arg("pose"), "Where the first frame lies, (4, 4) (default the identity); before the first frame only.")
      .def_property_readonly(
          "poses", [](const odometry::Odometry& odo) { return poses_array(odo.poses()); },
          "(frames, 4, 4) world_T_sensor of every frame so far")
      .def_property_readonly(
          "config", [](const odometry::Odometry& odo) { return odo.config(); }, "The OdometryConfig (a copy)")
      .def_property_readonly(
          "map_size", [](const odometry::Odometry& odo) { return odo.map().size(); }, "Points the map holds");

  o.def("map_names", &odometry::local_map_names, "The maps an Odometry can run on.");
  o.def(
      "trajectory_errors",
      [](const py::handle& estimate, const py::handle& reference) {
        const odometry::TrajectoryErrors e =
            odometry::trajectory_errors(poses_arg(estimate, "estimate"), poses_arg(reference, "reference"));
        py::list segments;
        for (const odometry::SegmentError& s : e.by_length) {
          segments.append(py::dict(py::arg("length") = s.length, py::arg("segments") = s.segments,
                                   py::arg("translation_pct") = s.translation_pct,
                                   py::arg("rotation_deg_per_100m") = s.rotation_deg_per_100m));
        }
        return py::dict(py::arg("frames") = e.frames, py::arg("path_length") = e.path_length,
                        py::arg("by_length") = segments, py::arg("translation_pct") = e.translation_pct,
                        py::arg("rotation_deg_per_100m") = e.rotation_deg_per_100m, py::arg("ate_rmse") = e.ate_rmse,
                        py::arg("rpe_translation_rmse") = e.rpe_translation_rmse,
                        py::arg("rpe_rotation_rmse_deg") = e.rpe_rotation_rmse_deg);
      },
      py::arg("estimate"), py::arg("reference"),
      "KITTI's relative errors over 100-800 m segments (translation %, rotation deg/100 m; none "
      "for a drive under 100 m), the ATE after a rigid alignment and the frame-to-frame RPE of "
      "`estimate` against `reference`: sequences of (4, 4) poses, the same frames. A dict.");
}

}  // namespace eco::python
