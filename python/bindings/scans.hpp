#pragma once
// One scan of a sequence (read from disk or simulated) as Python sees it.

#include "arrays.hpp"

#include <eco/io/point_cloud.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace eco::python {

/// eco.io.Scan: a frame's index, time, pose, points and, when known, intensity and labels.
struct Scan {
  std::size_t index = 0;
  py::object time;       // float seconds, or None
  py::object pose;       // (4, 4) float64 world_T_lidar
  py::object points;     // (N, 3) float32, lidar frame
  py::object intensity;  // (N,) float32, or None
  py::object labels;     // (N,) uint32 SemanticKITTI labels, or None
  py::object point_times;  // (N,) float64 seconds after `time`, or None
};

/// Everything a reader or the simulator produced for one frame. Built without the GIL, turned
/// into a Scan (which needs it) by to_python().
struct ScanData {
  std::size_t index = 0;
  std::optional<double> time;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  io::PointCloud cloud;
  std::optional<std::vector<std::uint32_t>> labels;
  std::optional<std::vector<double>> point_times;

  [[nodiscard]] Scan to_python() &&;
  /// (pose, points): what iterating a sequence yields.
  [[nodiscard]] py::tuple pose_and_points() &&;
};

/// (points (N, 3) float32, intensity (N,) float32 or None).
[[nodiscard]] py::tuple cloud_arrays(io::PointCloud&& cloud);

void bind_scan(py::module_& io);

/// Python's index rules for a sequence of `size` items: negatives count from the end;
/// IndexError (naming the index and the size) past either end.
[[nodiscard]] std::size_t sequence_index(std::ptrdiff_t index, std::size_t size);

/// How much of a frame a caller wants: iterating needs the pose and points only, so a reader can
/// skip the rest (a KITTI folder's label files).
enum class FrameParts { PoseAndPoints, Everything };

/// Gives a class of frames (a KITTI folder, the simulator) Python's sequence protocol:
/// __len__, and __getitem__ (negative indices too) returning (pose, points), so iterating yields
/// the pairs EgoOctree.update() takes; and `scan_method(index)` returning the whole Scan.
/// `load(object, i, parts)` makes frame i; it runs without the GIL.
template <class Frames, class Load>
void def_frames(py::class_<Frames>& cls, const char* len_doc, const char* scan_method,
                const char* scan_doc, Load load) {
  const auto loaded = [load](const Frames& frames, std::ptrdiff_t index, FrameParts parts) {
    const std::size_t i = sequence_index(index, frames.size());
    py::gil_scoped_release no_gil;
    return load(frames, i, parts);
  };
  cls.def("__len__", &Frames::size, len_doc);
  cls.def(
      "__getitem__",
      [loaded](const Frames& frames, std::ptrdiff_t index) {
        return loaded(frames, index, FrameParts::PoseAndPoints).pose_and_points();
      },
      py::arg("index"),
      "(pose (4, 4) float64 world_T_lidar, points (N, 3) float32) of frame `index`.");
  cls.def(
      scan_method,
      [loaded](const Frames& frames, std::ptrdiff_t index) {
        return loaded(frames, index, FrameParts::Everything).to_python();
      },
      py::arg("index"), scan_doc);
}

}  // namespace eco::python
