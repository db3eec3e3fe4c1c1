#pragma once
// An odometry's trajectories seen from above (x, y), one colour and marker per map, the reference
// dashed in black, at one scale on both axes: written as SVG directly.

#include "bench/odometry_run.hpp"

#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace eco::bench {

/// Throws eco::io::Error if the file cannot be written.
void write_trajectory_plot(const std::filesystem::path& path, const std::string& title,
                           const std::vector<OdometryRun>& runs, std::span<const Eigen::Isometry3d> reference);

}  // namespace eco::bench
