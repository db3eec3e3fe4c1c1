#pragma once
// The parts of the native module eco._eco, bound in this order by module.cpp.

#include <pybind11/pybind11.h>

namespace eco::python {

namespace py = pybind11;

void bind_config(py::module_& m);   // Recentring, InsertPolicy, Frame, DensityCap, Config
void bind_results(py::module_& m);  // Stats, UpdateStats
void bind_tree(py::module_& m);     // EgoOctree
void bind_io(py::module_& io);      // eco.io: KITTI sequences, scans, poses, PLY, PCD
void bind_sim(py::module_& sim);    // eco.sim: SimConfig and its models, Simulator
void bind_odometry(py::module_& o); // eco.odometry: Odometry, OdometryConfig, FrameReport, errors

}  // namespace eco::python
