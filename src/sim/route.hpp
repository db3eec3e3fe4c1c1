#pragma once
// A drive through the street grid: straights along centre lines joined by quarter-circle turns
// at intersections, parameterised by arc length.

#include "sim/random.hpp"

#include <Eigen/Core>

#include <vector>

namespace eco::sim {

struct RoutePoint {
  Eigen::Vector2d position;  ///< on the street's centre line
  double heading = 0.0;      ///< [rad] from +x, counter-clockwise
};

class Route {
 public:
  /// Starts at intersection `start` (grid units) heading along `direction` (0 E, 1 N, 2 W, 3 S);
  /// at each intersection goes straight (1/2), left or right (1/4 each) until `length` metres; with
  /// `turns` false, straight on at every one (the draws made all the same). The draws are made an
  /// intersection at a time: a longer route begins as a shorter one does.
  Route(Rng& rng, Eigen::Vector2i start, int direction, double length, double pitch, double turn_radius,
        bool turns = true);

  /// The point at arc length s (clamped to the route), moved `offset` metres to the right.
  [[nodiscard]] RoutePoint at(double s, double offset = 0.0) const;
  [[nodiscard]] double length() const { return length_; }
  /// Intersections passed through, in grid units, the start included.
  [[nodiscard]] const std::vector<Eigen::Vector2i>& intersections() const { return intersections_; }
  /// [m] the arc length at each intersection (the middle of a turn's arc).
  [[nodiscard]] const std::vector<double>& intersection_arcs() const { return intersection_arcs_; }

 private:
  struct Segment {
    double begin = 0.0;  // arc length where it starts
    double length = 0.0;
    Eigen::Vector2d start;
    double heading = 0.0;  // at the start
    double turn = 0.0;     // signed curvature: 0 straight, +1/R left, -1/R right
  };
  void add(const Eigen::Vector2d& start, double heading, double length, double turn);

  std::vector<Segment> segments_;
  std::vector<Eigen::Vector2i> intersections_;
  std::vector<double> intersection_arcs_;
  double length_ = 0.0;
};

}  // namespace eco::sim
