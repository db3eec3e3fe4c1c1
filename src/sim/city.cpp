#include "sim/city.hpp"

#include <eco/io/kitti.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace eco::sim {

namespace {

namespace label = io::label;

constexpr double kSidewalkHeight = 0.15;
constexpr double kSidewalkWidth = 4.0;
constexpr double kCarLength = 4.4, kCarWidth = 1.8;

// One side of a block: local u runs along the kerb, v runs inward from it.
struct Side {
  Eigen::Vector2d start, along, inward;
  double length = 0.0;

  // The axis-aligned box over u in [u0, u1], v in [v0, v1], z in [z0, z1].
  [[nodiscard]] Eigen::AlignedBox3d box(double u0, double u1, double v0, double v1, double z0,
                                        double z1) const {
    const Eigen::Vector2d a = start + u0 * along + v0 * inward;
    const Eigen::Vector2d b = start + u1 * along + v1 * inward;
    return {Eigen::Vector3d(std::min(a.x(), b.x()), std::min(a.y(), b.y()), z0),
            Eigen::Vector3d(std::max(a.x(), b.x()), std::max(a.y(), b.y()), z1)};
  }
  [[nodiscard]] Eigen::Vector2d at(double u, double v) const { return start + u * along + v * inward; }
};

void add_box(City& city, const Eigen::AlignedBox3d& b, Surface surface) {
  city.boxes.push_back({b.min(), b.max(), surface});
}

void add_buildings(City& city, const Side& side, Rng& rng) {
  for (double u = 0.0; u < side.length - 6.0;) {
    const double width = std::min(rng.uniform(12.0, 30.0), side.length - u);
    const double setback = kSidewalkWidth + rng.uniform(0.0, 3.0);
    const double depth = rng.uniform(10.0, 20.0);
    const double height = rng.uniform(6.0, 22.0);
    add_box(city, side.box(u, u + width, setback, setback + depth, kSidewalkHeight, height),
            {label::kBuilding, static_cast<float>(rng.uniform(0.2, 0.6))});
    u += width + (rng.chance(0.3) ? rng.uniform(3.0, 10.0) : 0.0);
  }
}

void add_street_furniture(City& city, const Side& side, Rng& rng) {
  for (double u = rng.uniform(5.0, 15.0); u < side.length - 5.0; u += rng.uniform(20.0, 35.0)) {
    city.cylinders.push_back({side.at(u, 0.6), 0.12, kSidewalkHeight, rng.uniform(5.0, 8.0),
                              {label::kPole, 0.5f}});
  }
  for (double u = rng.uniform(3.0, 8.0); u < side.length - 3.0; u += rng.uniform(8.0, 14.0)) {
    if (!rng.chance(0.6)) continue;
    const double trunk = rng.uniform(2.0, 3.0), crown = rng.uniform(1.5, 2.5);
    const Eigen::Vector2d base = side.at(u, 2.0);
    city.cylinders.push_back({base, rng.uniform(0.15, 0.25), kSidewalkHeight,
                              kSidewalkHeight + trunk, {label::kTrunk, 0.25f}});
    city.spheres.push_back({{base.x(), base.y(), kSidewalkHeight + trunk + 0.6 * crown}, crown,
                            {label::kVegetation, 0.35f}});
  }
}

void add_parked_cars(City& city, const Side& side, Rng& rng, double chance) {
  for (double u = 12.0; u + 6.0 < side.length - 12.0; u += 6.0) {
    if (!rng.chance(chance)) continue;
    const Surface paint{label::kCar, static_cast<float>(rng.uniform(0.3, 0.8))};
    const double mid = u + 3.0, v = -1.2;  // in the road, beside the kerb
    add_box(city, side.box(mid - kCarLength / 2, mid + kCarLength / 2, v - kCarWidth / 2,
                           v + kCarWidth / 2, 0.25, 1.0), paint);
    add_box(city, side.box(mid - 1.4, mid + 1.0, v - 0.8, v + 0.8, 1.0, 1.45), paint);
  }
}

// Block (bx, by) lies between street centre lines bx and bx + 1 (and by, by + 1).
void add_block(City& city, const SimConfig& config, int bx, int by) {
  const CityModel& m = config.city;
  Rng rng(config.seed, 0x100000000ull + (static_cast<std::uint64_t>(bx & 0xFFFF) << 16) +
                           static_cast<std::uint64_t>(by & 0xFFFF));
  const double x0 = bx * m.block_pitch + m.road_half_width, x1 = (bx + 1) * m.block_pitch - m.road_half_width;
  const double y0 = by * m.block_pitch + m.road_half_width, y1 = (by + 1) * m.block_pitch - m.road_half_width;
  city.boxes.push_back({{x0, y0, 0.0}, {x1, y1, kSidewalkHeight}, {label::kSidewalk, 0.3f}});
  const double len = x1 - x0;
  const Side sides[4] = {{{x0, y0}, {1, 0}, {0, 1}, len},
                         {{x0, y1}, {1, 0}, {0, -1}, len},
                         {{x0, y0}, {0, 1}, {1, 0}, len},
                         {{x1, y0}, {0, 1}, {-1, 0}, len}};
  for (const Side& side : sides) {
    add_buildings(city, side, rng);
    add_street_furniture(city, side, rng);
    add_parked_cars(city, side, rng, m.parked_car_chance);
  }
}

}  // namespace

City build_city(const SimConfig& config) {
  const CityModel& m = config.city;
  const double duration = static_cast<double>(config.frames) / config.rate_hz;
  const double margin = 2.0 * m.block_pitch;
  City city;
  Rng ego_rng(config.seed, 1);
  city.routes.emplace_back(ego_rng, Eigen::Vector2i(0, 0), 0, config.speed * duration + margin,
                           m.block_pitch, m.turn_radius, config.manoeuvre != Manoeuvre::Straight);

  // The blocks within two of every intersection the sensor passes: all it can see at 120 m.
  std::set<std::pair<int, int>> blocks;
  for (const auto& c : city.routes[0].intersections()) {
    for (int dx = -2; dx <= 1; ++dx) {
      for (int dy = -2; dy <= 1; ++dy) blocks.insert({c.x() + dx, c.y() + dy});
    }
  }
  for (const auto& [bx, by] : blocks) add_block(city, config, bx, by);

  // Moving cars: one leads the sensor vehicle along its route; the others set off from the
  // intersections it passes, in any direction, at their own speeds, each as the vehicle comes
  // within kSetOffAhead of it along the route. Each intersection's cars come from draws of their
  // own, and only the cars set off before the drive ends are made, so that a longer drive adds
  // cars later on but changes none of a shorter one's.
  Rng lead_rng(config.seed, 2);
  city.cars.push_back({0, lead_rng.uniform(15.0, 25.0), config.speed,
                       {io::label::kMovingCar, static_cast<float>(lead_rng.uniform(0.3, 0.8))}, 0.0});
  constexpr double kSetOffAhead = 150.0;  // [m] beyond the sensor's 120 m, along the route
  const Route& ego = city.routes[0];
  const std::vector<Eigen::Vector2i> stops = ego.intersections();  // routes grows below
  const std::vector<double> arcs = ego.intersection_arcs();
  for (std::size_t j = 0; j < stops.size(); ++j) {
    const double sets_off = std::max(0.0, (arcs[j] - kSetOffAhead) / config.speed);
    if (sets_off > duration) break;
    Rng count_rng(config.seed, 0x200000000ull + j);
    const int cars = count_rng.poisson(m.cars_per_intersection);
    for (int i = 0; i < cars; ++i) {
      Rng car_rng(config.seed, 0x300000000ull + (static_cast<std::uint64_t>(j) << 12) + static_cast<std::uint64_t>(i));
      const Surface paint{io::label::kMovingCar, static_cast<float>(car_rng.uniform(0.3, 0.8))};
      const double speed = car_rng.uniform(4.0, 12.0);
      const double start = car_rng.uniform(0.0, m.block_pitch);
      const int direction = car_rng.below(4);
      city.routes.emplace_back(car_rng, stops[j], direction, start + speed * (duration - sets_off) + margin,
                               m.block_pitch, m.turn_radius);
      city.cars.push_back({city.routes.size() - 1, start, speed, paint, sets_off});
    }
  }
  return city;
}

void car_bodies(const City& city, const MovingCar& car, double lane_offset, double t,
                std::vector<TurnedBox>& out) {
  if (t < car.sets_off) return;
  const RoutePoint p = city.routes[car.route].at(car.start + car.speed * (t - car.sets_off), lane_offset);
  const Eigen::Vector2d forward(std::cos(p.heading), std::sin(p.heading));
  const Eigen::Vector2d cabin = p.position - 0.2 * forward;
  out.push_back({{p.position.x(), p.position.y(), 0.625}, {kCarLength / 2, kCarWidth / 2, 0.375},
                 p.heading, car.paint});
  out.push_back({{cabin.x(), cabin.y(), 1.225}, {1.2, 0.8, 0.225}, p.heading, car.paint});
}

}  // namespace eco::sim
