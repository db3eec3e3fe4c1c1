#include "scans.hpp"

#include <string>

namespace eco::python {

py::tuple cloud_arrays(io::PointCloud&& cloud) {
  py::object intensity = py::none();
  if (cloud.has_intensity()) intensity = values_array(std::move(cloud.intensity));
  return py::make_tuple(rows_array(std::move(cloud.points)), intensity);
}

Scan ScanData::to_python() && {
  Scan out;
  out.index = index;
  out.time = time ? py::object(py::float_(*time)) : py::none();
  out.pose = matrix_array(pose);
  const py::tuple arrays = cloud_arrays(std::move(cloud));
  out.points = arrays[0];
  out.intensity = arrays[1];
  out.labels = labels ? py::object(values_array(std::move(*labels))) : py::none();
  out.point_times = point_times ? py::object(values_array(std::move(*point_times))) : py::none();
  return out;
}

py::tuple ScanData::pose_and_points() && {
  return py::make_tuple(matrix_array(pose), rows_array(std::move(cloud.points)));
}

std::size_t sequence_index(std::ptrdiff_t index, std::size_t size) {
  const std::ptrdiff_t n = std::ptrdiff_t(size);
  const std::ptrdiff_t i = index < 0 ? index + n : index;
  if (i < 0 || i >= n) {
    throw py::index_error("index " + std::to_string(index) + " is out of range for " +
                          std::to_string(size) + " frames");
  }
  return std::size_t(i);
}

void bind_scan(py::module_& io) {
  py::class_<Scan>(io, "Scan",
                   "One frame of a sequence: what KittiSequence.read() and "
                   "Simulator.frame() return.")
      .def_readonly("index", &Scan::index, "frame number in its sequence")
      .def_readonly("time", &Scan::time, "[s] timestamp, or None when the sequence has none")
      .def_readonly("pose", &Scan::pose, "(4, 4) float64 world_T_lidar")
      .def_readonly("points", &Scan::points, "(N, 3) float32, lidar frame")
      .def_readonly("intensity", &Scan::intensity, "(N,) float32 reflectance, or None")
      .def_readonly("labels", &Scan::labels,
                    "(N,) uint32 SemanticKITTI labels, or None (ids >= 252 are moving objects)")
      .def_readonly("point_times", &Scan::point_times,
                    "(N,) float64 seconds of each point after `time` (a recording's per-point times), or None")
      .def("__repr__", [](const Scan& s) {
        return "Scan(index=" + std::to_string(s.index) +
               ", points=" + std::to_string(py::len(s.points)) + ")";
      });
}

}  // namespace eco::python
