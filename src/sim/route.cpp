#include "sim/route.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace eco::sim {

namespace {

constexpr double kHalfPi = std::numbers::pi / 2.0;

Eigen::Vector2i step(int direction) {
  static const Eigen::Vector2i kSteps[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  return kSteps[direction & 3];
}

Eigen::Vector2d unit(int direction) { return step(direction).cast<double>(); }

}  // namespace

void Route::add(const Eigen::Vector2d& start, double heading, double length, double turn) {
  segments_.push_back({length_, length, start, heading, turn});
  length_ += length;
}

Route::Route(Rng& rng, Eigen::Vector2i start, int direction, double length, double pitch,
             double turn_radius, bool turns) {
  intersections_.push_back(start);
  intersection_arcs_.push_back(0.0);
  Eigen::Vector2d from = start.cast<double>() * pitch;  // where the next straight begins
  while (length_ < length) {
    const Eigen::Vector2i next = intersections_.back() + step(direction);
    intersections_.push_back(next);
    const Eigen::Vector2d corner = next.cast<double>() * pitch;
    const double r = rng.uniform();
    const int turn = !turns || r < 0.5 ? 0 : (r < 0.75 ? 1 : -1);  // +1 left, -1 right
    const double heading = direction * kHalfPi;
    if (turn == 0) {
      add(from, heading, (corner - from).norm(), 0.0);
      intersection_arcs_.push_back(length_);
      from = corner;
      continue;
    }
    const int turned = (direction + turn + 4) & 3;
    const Eigen::Vector2d arc_start = corner - turn_radius * unit(direction);
    add(from, heading, (arc_start - from).norm(), 0.0);
    intersection_arcs_.push_back(length_ + kHalfPi * turn_radius / 2.0);
    add(arc_start, heading, kHalfPi * turn_radius, turn / turn_radius);
    from = corner + turn_radius * unit(turned);
    direction = turned;
  }
}

RoutePoint Route::at(double s, double offset) const {
  s = std::clamp(s, 0.0, length_);
  auto it = std::upper_bound(segments_.begin(), segments_.end(), s,
                             [](double value, const Segment& seg) { return value < seg.begin; });
  const Segment& seg = *std::prev(it);  // segments_[0].begin == 0 <= s
  const double u = std::min(s - seg.begin, seg.length);
  RoutePoint p;
  if (seg.turn == 0.0) {
    p.heading = seg.heading;
    p.position = seg.start + u * Eigen::Vector2d(std::cos(seg.heading), std::sin(seg.heading));
  } else {
    const double radius = 1.0 / std::abs(seg.turn);
    const double side = seg.turn > 0.0 ? 1.0 : -1.0;  // the centre lies to the left on a left turn
    const Eigen::Vector2d left(-std::sin(seg.heading), std::cos(seg.heading));
    const Eigen::Vector2d centre = seg.start + side * radius * left;
    p.heading = seg.heading + seg.turn * u;
    const Eigen::Vector2d radial(std::sin(p.heading), -std::cos(p.heading));  // centre -> point, left turn
    p.position = centre + side * radius * radial;
  }
  const Eigen::Vector2d right(std::sin(p.heading), -std::cos(p.heading));
  p.position += offset * right;
  return p;
}

}  // namespace eco::sim
