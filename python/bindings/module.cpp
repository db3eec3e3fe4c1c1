// The native module eco._eco; the package eco (python/eco/) re-exports it.

#include "bindings.hpp"

#include <eco/process_heap.hpp>
#include <eco/version.hpp>

PYBIND11_MODULE(_eco, m) {
  using namespace eco::python;
  m.doc() = "ECO's C++ core, bound with pybind11. Import the package `eco`, not this module.";
  m.attr("__version__") = eco::kVersion;
  bind_config(m);
  bind_results(m);
  bind_tree(m);
  m.def("keep_freed_heap", &eco::keep_freed_heap, py::arg("keep_bytes") = std::size_t{128} << 20,
        "Lets the C library keep what each frame frees for the next frames instead of handing it back to the "
        "kernel and faulting it in again (blocks under 32 MiB from the heap, up to keep_bytes kept free at its "
        "end; glibc's M_MMAP_THRESHOLD and M_TRIM_THRESHOLD). Importing eco calls it. Returns False where the C "
        "library has no such settings.");
  py::module_ io = m.def_submodule("io", "KITTI-layout sequences, scans, poses, PLY and PCD.");
  bind_io(io);
  py::module_ sim = m.def_submodule("sim", "The LiDAR simulator.");
  bind_sim(sim);
  py::module_ odometry = m.def_submodule("odometry", "A LiDAR odometry on ECO's map.");
  bind_odometry(odometry);
}
