#include <eco/odometry/local_map.hpp>

#include "odometry/maps.hpp"

#include <cmath>
#include <stdexcept>

namespace eco::odometry {

void MapSettings::validate() const {
  if (!(std::isfinite(box_side) && box_side > 0.0)) {
    throw std::invalid_argument("map box_side must be finite and > 0 m, got " + std::to_string(box_side));
  }
  if (!(std::isfinite(cell_size) && cell_size > 0.0 && cell_size <= box_side)) {
    throw std::invalid_argument("map cell_size must be > 0 m and at most box_side, got " + std::to_string(cell_size));
  }
  if (max_points == 0) throw std::invalid_argument("map max_points must be >= 1, got 0");
  if (threads == 0) throw std::invalid_argument("map threads must be >= 1, got 0");
  if (!(std::isfinite(ball_radius) && ball_radius > 0.0)) {
    throw std::invalid_argument("map ball_radius must be finite and > 0 m, got " + std::to_string(ball_radius));
  }
}

Config ego_config(const MapSettings& settings, bool ball) {
  Config config;
  config.box_side = settings.box_side;
  config.insert_policy = InsertPolicy::AllInBox;
  config.density_cap = {settings.cell_size, settings.max_points};
  if (ball) config.region = {RegionShape::Ball, std::min(settings.ball_radius, settings.box_side / 2)};
  return config;
}

const std::vector<std::string>& local_map_names() {
  static const std::vector<std::string> names{"eco", "eco_ball", "voxel_hash"};
  return names;
}

std::unique_ptr<LocalMap> make_local_map(std::string_view name, const MapSettings& settings) {
  settings.validate();
  if (name == "eco") return make_eco_map(settings, false);
  if (name == "eco_ball") return make_eco_map(settings, true);
  if (name == "voxel_hash") return make_voxel_hash_map(settings);
  throw unknown_map(name, local_map_names());
}

std::invalid_argument unknown_map(std::string_view name, const std::vector<std::string>& known) {
  std::string list;
  for (const std::string& n : known) list += (list.empty() ? "" : ", ") + n;
  return std::invalid_argument("unknown map '" + std::string(name) + "' (known: " + list + ")");
}

}  // namespace eco::odometry
