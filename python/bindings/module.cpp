// The native module eco._eco; the package eco (python/eco/) re-exports it.

#include "bindings.hpp"

#include <eco/version.hpp>

PYBIND11_MODULE(_eco, m) {
  using namespace eco::python;
  m.doc() = "ECO's C++ core, bound with pybind11. Import the package `eco`, not this module.";
  m.attr("__version__") = eco::kVersion;
  bind_config(m);
  bind_results(m);
  bind_tree(m);
  py::module_ io = m.def_submodule("io", "KITTI-layout sequences, scans, poses, PLY and PCD.");
  bind_io(io);
  py::module_ sim = m.def_submodule("sim", "The LiDAR simulator.");
  bind_sim(sim);
  py::module_ odometry = m.def_submodule("odometry", "A LiDAR odometry on ECO's map.");
  bind_odometry(odometry);
}
