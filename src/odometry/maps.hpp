#pragma once
// The four LocalMap backends (local_map.hpp), made by make_local_map.

#include <eco/config.hpp>
#include <eco/odometry/local_map.hpp>

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace eco::odometry {

/// The EgoOctree configuration every map that keeps ECO's held set shares: the cube (with `ball`,
/// a ball of MapSettings::ball_radius in it), AllInBox, and the cap as the map's downsampling.
[[nodiscard]] Config ego_config(const MapSettings& settings, bool ball = false);

/// `eco`, or with `ball` `eco_ball`: the same holding a ball of MapSettings::ball_radius.
[[nodiscard]] std::unique_ptr<LocalMap> make_eco_map(const MapSettings& settings, bool ball);
[[nodiscard]] std::unique_ptr<LocalMap> make_voxel_hash_map(const MapSettings& settings);

/// The error for a map name not among `known`, listing them.
[[nodiscard]] std::invalid_argument unknown_map(std::string_view name, const std::vector<std::string>& known);

}  // namespace eco::odometry
