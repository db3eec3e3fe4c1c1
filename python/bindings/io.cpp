// eco.io: KITTI-layout sequences read frame by frame, and the single-file readers and writers.

#include "bindings.hpp"
#include "records.hpp"
#include "scans.hpp"

#include <eco/io/kitti.hpp>
#include <eco/io/kitti_sequence.hpp>
#include <eco/io/pcd.hpp>
#include <eco/io/ply.hpp>

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
