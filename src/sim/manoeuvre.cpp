#include "sim/manoeuvre.hpp"

#include <cmath>
#include <numbers>

namespace eco::sim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLeg = 40.0;    // [m] UTurn's straight between its turns
constexpr double kStart = 10.0;  // [m] east of the origin's intersection, where the patterns begin

/// On the stadium UTurn drives anticlockwise: east on the right-hand lane (y = -lane), a half
/// circle about the centre line, west on the other lane, a half circle back; `s` metres along it.
RoutePoint stadium(double s, double lane) {
  const double turn = kPi * lane;
  s = std::fmod(s, 2.0 * (kLeg + turn));
  if (s < kLeg) return {{kStart + s, -lane}, 0.0};
  s -= kLeg;
  if (s < turn) {
    const double a = s / lane;  // turned so far
    return {{kStart + kLeg + lane * std::sin(a), -lane * std::cos(a)}, a};
  }
  s -= turn;
  if (s < kLeg) return {{kStart + kLeg - s, lane}, kPi};
  s -= kLeg;
  const double a = s / lane;
  return {{kStart - lane * std::sin(a), lane * std::cos(a)}, kPi + a};
}

}  // namespace

RoutePoint manoeuvre_at(const SimConfig& c, const Route& route, double t) {
  const double lane = c.city.lane_offset;
  const double s = c.speed * t;
  switch (c.manoeuvre) {
    case Manoeuvre::Route:
    case Manoeuvre::Straight: return route.at(s, lane);
    case Manoeuvre::UTurn: return stadium(s, lane);
    case Manoeuvre::Roundabout: {
      const double a = s / c.roundabout_radius - kPi / 2;  // from the circle's south, anticlockwise
      return {{c.roundabout_radius * std::cos(a), c.roundabout_radius * std::sin(a)}, a + kPi / 2};
    }
    case Manoeuvre::Spin: return {{kStart, -lane}, c.spin_rate_deg * kPi / 180.0 * t};
    case Manoeuvre::Still: return {{kStart, -lane}, 0.0};
  }
  return route.at(s, lane);
}

}  // namespace eco::sim
