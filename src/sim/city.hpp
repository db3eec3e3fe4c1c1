#pragma once
// The procedural city: blocks of buildings, sidewalks, poles, trees and parked cars around the
// sensor vehicle's route, and cars driving routes of their own.

#include <eco/sim/simulator.hpp>

#include "sim/route.hpp"
#include "sim/shapes.hpp"

#include <vector>

namespace eco::sim {

struct MovingCar {
  std::size_t route = 0;  ///< index into City::routes
  double start = 0.0;     ///< [m] arc length when it sets off
  double speed = 0.0;     ///< [m/s]
  Surface paint;
  double sets_off = 0.0;  ///< [s] the time it appears and starts driving; absent before
};

struct City {
  std::vector<Route> routes;  ///< routes[0] is the sensor vehicle's
  std::vector<MovingCar> cars;
  std::vector<Box> boxes;
  std::vector<Cylinder> cylinders;
  std::vector<Sphere> spheres;
};

/// Everything the configuration and its seed describe. What lies within the sensor's reach during
/// the first n frames is the same for any drive of n frames or more: a longer drive only adds.
[[nodiscard]] City build_city(const SimConfig& config);

/// The body and cabin of a moving car at time t, appended to `out` (nothing before it sets off).
void car_bodies(const City& city, const MovingCar& car, double lane_offset, double t,
                std::vector<TurnedBox>& out);

}  // namespace eco::sim
