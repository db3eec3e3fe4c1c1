#pragma once
// What an update refuses before it changes anything, shared by the update itself, the baselines
// that compose its stages, and loading a map file (whose saved pose must be one an update takes).

#include <eco/config.hpp>
#include <eco/types.hpp>

#include <Eigen/Geometry>

namespace eco::detail {

/// Throws std::invalid_argument naming the value unless `pose` is finite and rigid, `scan` is
/// readable and the density cap's grid can index the points around `pose` (Config's). `name`
/// names the pose argument in the message.
void check_update_arguments(const Eigen::Isometry3d& pose, const char* name, const ScanView& scan,
                            const Config& config);

}  // namespace eco::detail
