// eco.io: KITTI-layout sequences read frame by frame, and the single-file readers and writers.

#include "bindings.hpp"
#include "records.hpp"
#include "scans.hpp"

#include <eco/io/kitti.hpp>
#include <eco/io/kitti_sequence.hpp>
#include <eco/io/pcd.hpp>
#include <eco/io/ply.hpp>
#include <eco/workloads/scan_source.hpp>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <span>

namespace eco::python {
namespace {

namespace fs = std::filesystem;

ScanData read_frame(const io::KittiSequence& seq, std::size_t i, FrameParts parts) {
  ScanData data;
  io::KittiFrame frame = seq.read(i);
  data.index = i;
  data.pose = frame.world_T_lidar;
  data.cloud = std::move(frame.cloud);
  if (i < seq.times().size()) data.time = seq.times()[i];
  if (parts == FrameParts::Everything && seq.has_labels()) data.labels = seq.read_labels(i);
  return data;
}

ScanData read_source_frame(const workloads::OpenedSource& source, std::size_t i, FrameParts) {
  workloads::WorkloadFrame frame = source.frames->frame(i);
  ScanData data;
  data.index = i;
  data.pose = frame.world_T_sensor;
  data.time = frame.time;
  data.cloud.points = std::move(frame.points);
  data.cloud.intensity = std::move(frame.intensities);
  if (!frame.labels.empty()) data.labels = std::move(frame.labels);
  if (!frame.point_times.empty()) data.point_times = std::move(frame.point_times);
  return data;
}

/// An optional string argument: None or a str.
std::string text_arg(const py::object& value, const char* name) {
  if (value.is_none()) return {};
  if (!py::isinstance<py::str>(value) && !py::isinstance(value, py::module_::import("os").attr("PathLike"))) {
    throw py::type_error(std::string(name) + " must be a str or None, not " + std::string(py::str(value.get_type().attr("__name__"))));
  }
  return py::str(py::module_::import("os").attr("fspath")(value));
}

/// A cloud from caller arrays, for the writers.
io::PointCloud cloud_arg(const py::object& points, const py::object& intensity) {
  const Rows3 rows(points, "points", /*allow_single=*/false);
  io::PointCloud cloud;
  cloud.points.reserve(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) cloud.points.push_back(rows.row(i).cast<float>());
  if (!intensity.is_none()) {
    const py::array_t<float, py::array::forcecast> values(intensity);
    if (values.ndim() != 1 || std::size_t(values.shape(0)) != rows.size()) {
      throw py::value_error("intensity must have shape (" + std::to_string(rows.size()) +
                            ",), one value per point");
    }
    cloud.intensity.assign(values.data(), values.data() + rows.size());
  }
  return cloud;
}

/// A writer binding: checks the arrays with the GIL, writes without it.
template <class Write>
auto cloud_writer(Write write) {
  return [write](const fs::path& path, const py::object& points, const py::object& intensity) {
    const io::PointCloud cloud = cloud_arg(points, intensity);
    py::gil_scoped_release no_gil;
    write(path, cloud);
  };
}

template <class Read>
py::tuple read_cloud(const fs::path& path, Read read) {
  io::PointCloud cloud;
  {
    py::gil_scoped_release no_gil;
    cloud = read(path);
  }
  return cloud_arrays(std::move(cloud));
}

py::array_t<double> poses_array(std::span<const Eigen::Isometry3d> poses) {
  py::array_t<double> out({poses.size(), std::size_t(4), std::size_t(4)});
  auto a = out.mutable_unchecked<3>();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) a(py::ssize_t(i), r, c) = poses[i].matrix()(r, c);
    }
  }
  return out;
}

constexpr const char* kSequenceDoc = R"(A KITTI odometry folder, read one scan at a time.

    folder/velodyne/000000.bin ...   scans (float32 x, y, z, reflectance)
    folder/poses.txt                 one 3x4 pose per scan
    folder/calib.txt                 `Tr:` velodyne -> camera 0, when poses are camera-frame
    folder/times.txt, labels/        optional

KittiSequence(folder, pose_frame="Auto", poses_file="poses.txt"). pose_frame: "Auto" (camera-frame
poses when calib.txt exists, as KITTI's; else lidar poses, as BALM's), "Camera" or "Lidar".
Iterating yields (pose (4, 4) float64 world_T_lidar, points (N, 3) float32 lidar frame) pairs,
ready for EgoOctree.update(pose, points). Raises eco.io.Error naming the file and line at fault.)";

constexpr const char* kSourceDoc = R"(What --data reads, opened: a KITTI-layout folder, a folder of .pcd/.ply/.bin
files (name order), an .mcap or .db3 file, or a rosbag2 folder (metadata.yaml). Made by eco.io.open().

Iterating yields (pose (4, 4) float64 world_T_lidar, points (N, 3) float32 sensor frame); a source
without poses gives the identity (has_poses False: eco.odometry estimates them). read(i) gives the
whole eco.io.Scan, with a recording's per-point times in point_times (seconds after scan.time).)";

}  // namespace

void bind_io(py::module_& io) {
  py::register_exception<io::Error>(io, "Error", PyExc_OSError);
  bind_scan(io);

  py::enum_<io::PoseFrame>(io, "PoseFrame", "Which frame poses.txt is written in.")
      .value("Auto", io::PoseFrame::Auto, "camera-0 frame if calib.txt exists, else the lidar's")
      .value("Camera", io::PoseFrame::Camera, "camera-0 frame: lidar pose = Tr^-1 * P * Tr")
      .value("Lidar", io::PoseFrame::Lidar, "already world_T_lidar");

  py::class_<io::KittiSequence> sequence(io, "KittiSequence", kSequenceDoc);
  def_frames(sequence, "Scans in the folder.", "read",
             "Scan `index` with its time, reflectance and labels (an eco.io.Scan).", &read_frame);
  sequence
      .def(py::init(
               [](const fs::path& folder, const py::object& pose_frame, std::string poses_file) {
                 io::KittiOptions options;
                 options.pose_frame = enum_arg<io::PoseFrame>(pose_frame, "pose_frame");
                 options.poses_file = std::move(poses_file);
                 py::gil_scoped_release no_gil;
                 return io::KittiSequence(folder, options);
               }),
           py::arg("folder"), py::arg("pose_frame") = io::PoseFrame::Auto,
           py::arg("poses_file") = "poses.txt")
      .def_property_readonly(
          "poses",
          [](const io::KittiSequence& seq) {
            return poses_array(seq.poses());
          },
          "(n, 4, 4) float64 world_T_lidar of every scan.")
      .def_property_readonly(
          "times",
          [](const io::KittiSequence& seq) -> py::object {
            if (seq.times().empty()) return py::none();
            return values_array(std::vector<double>(seq.times().begin(), seq.times().end()));
          },
          "(n,) float64 seconds from times.txt, or None.")
      .def_property_readonly("folder", &io::KittiSequence::folder, "The sequence's folder.")
      .def_property_readonly("has_labels", &io::KittiSequence::has_labels,
                             "True when labels/ holds SemanticKITTI labels.")
      .def_property_readonly("poses_were_camera_frame", &io::KittiSequence::poses_were_camera_frame,
                             "True when poses.txt held camera-0 poses, converted with calib.txt.")
      .def("__repr__", [](const io::KittiSequence& seq) {
        return "KittiSequence('" + seq.folder().string() + "', " + std::to_string(seq.size()) +
               " scans)";
      });

  py::class_<workloads::OpenedSource> source(io, "Source", kSourceDoc);
  def_frames(source, "Frames in the source.", "read", "Frame `index` with its time, intensities and point times (an eco.io.Scan).",
             &read_source_frame);
  source.def_readonly("has_poses", &workloads::OpenedSource::has_poses, "False when every pose is the identity")
      .def_readonly("description", &workloads::OpenedSource::description, "what was opened and how it is read")
      .def_readonly("warnings", &workloads::OpenedSource::warnings, "what a user should know (a cut file, a guess)")
      .def_readonly("pose_topics", &workloads::OpenedSource::pose_topics, "a recording's topics of poses")
      .def("__repr__", [](const workloads::OpenedSource& s) { return "Source(" + s.description + ")"; });
  io.def(
      "open",
      [](const py::object& path, const py::object& poses, const py::object& topic, const py::object& time_field,
         const std::string& time_unit, const py::object& pose_topic, const py::object& fixed_frame, bool place_points) {
        workloads::SourceOptions options;
        options.poses = text_arg(poses, "poses");
        options.pose_topic = text_arg(pose_topic, "pose_topic");
        options.fixed_frame = text_arg(fixed_frame, "fixed_frame");
        options.place_points = place_points;
        options.recording.topic = text_arg(topic, "topic");
        options.recording.time.field = text_arg(time_field, "time_field");
        const std::optional<io::TimeUnit> unit = io::time_unit_named(time_unit);
        if (!unit) throw py::value_error("time_unit = '" + time_unit + "' must be one of auto, s, ms, us, ns");
        options.recording.time.unit = *unit;
        const std::string where = text_arg(path, "path");
        py::gil_scoped_release no_gil;
        return workloads::open_source(where, options);
      },
      py::arg("path"), py::arg("poses") = py::none(), py::arg("topic") = py::none(), py::arg("time_field") = py::none(),
      py::arg("time_unit") = "auto", py::arg("pose_topic") = py::none(), py::arg("fixed_frame") = py::none(),
      py::arg("place_points") = true,
      R"(Opens what `path` holds as an eco.io.Source (a KITTI folder, point-cloud files, an MCAP,
rosbag2 or ROS 1 recording). poses: a KITTI or TUM trajectory file; topic: the recording's
PointCloud2 topic (default: the only one); time_field / time_unit: where each point's time is and
in what unit ("auto", "s", "ms", "us", "ns"); pose_topic: the recording's nav_msgs/Odometry,
PoseStamped or TransformStamped topic, interpolated at each cloud's stamp (tf applied between its
frame and the clouds'), or "tf": the clouds' frame in fixed_frame (default: its tree's root)
through /tf and /tf_static; place_points: with timed poses and per-point times, each point placed
by the pose at its own time (False: as measured, with its time). Raises eco.io.Error naming the
file, byte or topic at fault.)");

  io.def(
      "read_kitti_scan", [](const fs::path& path) { return read_cloud(path, io::read_kitti_scan); },
      py::arg("path"), "A velodyne .bin scan: (points (N, 3) float32, reflectance (N,) float32).");
  io.def(
      "read_kitti_poses",
      [](const fs::path& path) {
        std::vector<Eigen::Isometry3d> poses;
        {
          py::gil_scoped_release no_gil;
          poses = io::read_kitti_poses(path);
        }
        return poses_array(poses);
      },
      py::arg("path"), "A poses.txt as an (n, 4, 4) float64 array (rows re-orthonormalised).");
  io.def(
      "read_ply", [](const fs::path& path) { return read_cloud(path, io::read_ply); },
      py::arg("path"),
      "A PLY file (ascii or binary): (points (N, 3) float32, intensity (N,) float32 or None).");
  io.def(
      "read_pcd", [](const fs::path& path) { return read_cloud(path, io::read_pcd); },
      py::arg("path"),
      "A PCD file (ascii, binary or binary_compressed): (points (N, 3) float32, intensity or "
      "None).");
  io.def("write_ply", cloud_writer([](const fs::path& path, const io::PointCloud& cloud) {
           io::write_ply(path, cloud);
         }),
         py::arg("path"), py::arg("points"), py::arg("intensity") = py::none(),
         "Writes points (N, 3) [and intensity (N,)] as binary little-endian PLY, float32.");
  io.def("write_pcd", cloud_writer([](const fs::path& path, const io::PointCloud& cloud) {
           io::write_pcd(path, cloud);
         }),
         py::arg("path"), py::arg("points"), py::arg("intensity") = py::none(),
         "Writes points (N, 3) [and intensity (N,)] as binary PCD, float32.");
}

}  // namespace eco::python
