#pragma once
// Where the sensor vehicle is at a time, for each SimConfig::manoeuvre: the route's streets, or a
// fixed pattern on the first street east of the origin (inside the city the route builds).

#include "sim/route.hpp"

#include <eco/sim/simulator.hpp>

namespace eco::sim {

/// The vehicle's point and heading at `t` seconds: on `route` (City::routes[0]) for Route and
/// Straight, else the manoeuvre's pattern.
[[nodiscard]] RoutePoint manoeuvre_at(const SimConfig& config, const Route& route, double t);

}  // namespace eco::sim
