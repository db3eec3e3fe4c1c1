#pragma once
// One maker per method, each defined in the method's own file.

#include "baselines/method.hpp"

namespace eco::baselines {

std::unique_ptr<Method> make_eco(const Config& config, Recentring recentring);
/// `eco` with free-space clearing on, whatever the config says: clearing's cost and effect side
/// by side with `eco` in one run.
std::unique_ptr<Method> make_eco_clearing(const Config& config);
/// `eco` holding a ball about the sensor: the config's region if it is one, else of radius
/// box_side / 2 (the largest the cube holds).
std::unique_ptr<Method> make_eco_ball(const Config& config);
/// `eco` holding a box turned with the sensor's heading: the config's region if it is one, else
/// 0.39 box_side ahead, 0.2 behind, 0.3 to each side, 0.25 up and down (turning about the vertical,
/// its corners stay within the cube's half side).
std::unique_ptr<Method> make_eco_box(const Config& config);
std::unique_ptr<Method> make_octree_base(const Config& config);
std::unique_ptr<Method> make_scan_only(const Config& config);
std::unique_ptr<Method> make_ioctree_global(const Config& config);
std::unique_ptr<Method> make_ioctree_target(const Config& config);
std::unique_ptr<Method> make_nanoflann(const Config& config);
std::unique_ptr<Method> make_pcl_octree(const Config& config);
std::unique_ptr<Method> make_scan_pass(const Config& config);

}  // namespace eco::baselines
