#pragma once
// One maker per method, each defined in the method's own file.

#include <eco/baselines/method.hpp>

namespace eco::baselines {

std::unique_ptr<Method> make_eco(const Config& config, Recentring recentring);
/// `eco` with free-space clearing on, whatever the config says: clearing's cost and effect side
/// by side with `eco` in one run.
std::unique_ptr<Method> make_eco_clearing(const Config& config);
std::unique_ptr<Method> make_octree_base(const Config& config);
std::unique_ptr<Method> make_scan_only(const Config& config);
std::unique_ptr<Method> make_ioctree_global(const Config& config);
std::unique_ptr<Method> make_ioctree_target(const Config& config);
std::unique_ptr<Method> make_nanoflann(const Config& config);
std::unique_ptr<Method> make_pcl_octree(const Config& config);
std::unique_ptr<Method> make_scan_pass(const Config& config);

}  // namespace eco::baselines
