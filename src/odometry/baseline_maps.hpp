#pragma once
/// @file baseline_maps.hpp
/// The odometry's maps borrowed from the benchmark's baselines — `nanoflann` (a k-d tree rebuilt
/// every frame) and `pcl_octree` (PCL's octree) — which hold exactly ECO's points. Built in the
/// tree beside the benchmark (eco::odometry_baselines), not installed.

#include <eco/odometry/local_map.hpp>

#include <memory>
#include <string_view>

namespace eco::odometry {

/// Every map name make_any_local_map accepts: local_map_names(), then nanoflann and pcl_octree.
[[nodiscard]] const std::vector<std::string>& all_local_map_names();

/// make_local_map, or one of the baselines' maps. Throws std::invalid_argument for an unknown
/// name (listing the known ones) or settings out of range.
[[nodiscard]] std::unique_ptr<LocalMap> make_any_local_map(std::string_view name, const MapSettings& settings);

}  // namespace eco::odometry
