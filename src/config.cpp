#include <eco/config.hpp>
#include <eco/config_fields.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace eco {
namespace {

/// `value` in the fewest digits that read back as it (100000, not 1e+05; 0.1, not 0.100000).
std::string shortest(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

[[noreturn]] void reject(const std::string& field, const std::string& value, const std::string& rule) {
  throw std::invalid_argument("eco::Config: " + field + " = " + value + " is invalid: " + rule);
}
[[noreturn]] void reject(const std::string& field, double value, const std::string& rule) {
  reject(field, shortest(value), rule);
}

constexpr int kDeepestLevel = 24;  // cells 2^-24 of the root: far below any LiDAR's noise
constexpr double kMaxPixels = 1 << 24;  // a range image of 64 MB of floats at most

}  // namespace

double Config::quantum() const {
  if (recentring == Recentring::Exact) return 0.0;
  // q * 2^k = L + q exactly would let the box touch the root's walls when the sensor sits on a
  // half-quantum tie; a relative 1e-9 margin keeps it strictly inside despite rounding.
  const double least = box_side / double((1u << quantum_levels) - 1u) * (1.0 + 1e-9);
  if (!(voxel_size > 0.0) || !(least > 0.0)) return least;  // (a box_side too small leaves none: validate refuses it)
  // the smallest voxel_size * 2^j that is at least `least`: cells below depth k are then voxels
  // (j clamped: a voxel_size near the smallest doubles makes the quotient infinite)
  int j = int(std::clamp(std::ceil(std::log2(least / voxel_size)), -1100.0, 1100.0));
  while (std::ldexp(voxel_size, j) < least) ++j;
  while (std::ldexp(voxel_size, j - 1) >= least) --j;
  return std::ldexp(voxel_size, j);
}

double Config::root_side() const {
  if (recentring == Recentring::Exact) return box_side;
  return quantum() * double(1u << quantum_levels);
}

double Region::reach() const {
  switch (shape) {
    case RegionShape::Cube: return 0.0;
    case RegionShape::Ball: return radius;
    case RegionShape::OrientedBox: {
      const double along = std::max(ahead, behind), across = std::max(left, right), height = std::max(up, down);
      // turning about the vertical sweeps the horizontal corners round; turning freely, every corner
      return turn_with == TurnWith::Yaw ? std::max(std::hypot(along, across), height)
                                        : std::sqrt(along * along + across * across + height * height);
    }
  }
  return 0.0;
}

Region Region::sized(double growth, double scale) const {
  Region r = *this;
  if (shape == RegionShape::Ball) r.radius += growth;
  if (shape == RegionShape::OrientedBox) r.ahead += growth;
  for (double* extent : {&r.radius, &r.ahead, &r.behind, &r.left, &r.right, &r.up, &r.down}) *extent *= scale;
  return r;
}

double Region::max_growth(double half_side) const {
  if (shape == RegionShape::Cube || reach() > half_side) return 0.0;
  double fits = 0.0, too_far = half_side * 2;  // the reach grows with the growth, at least as fast as ahead does
  for (int step = 0; step < 60; ++step) {
    const double middle = (fits + too_far) / 2;
    (sized(middle, 1.0).reach() <= half_side ? fits : too_far) = middle;
  }
  return fits;
}

int SensorModel::rows() const {
  return int(std::ceil((vertical_fov_max - vertical_fov_min) / vertical_resolution));
}

int SensorModel::columns() const { return int(std::ceil(360.0 / horizontal_resolution)); }

int Config::max_depth() const {
  // clamped: a min_cell_size near the smallest doubles makes the quotient infinite (validate refuses it)
  return int(std::clamp(std::floor(std::log2(root_side() / min_cell_size)), -1.0, 1100.0));
}

void Config::validate() const {
  for (const ConfigField& f : config_fields()) f.check(f.get(*this));  // each field's own range
  // rules that tie fields together
  if (min_cell_size > root_side()) {
    reject("min_cell_size", min_cell_size, "must not exceed the root cell side");
  }
  if (recentring == Recentring::Quantised && min_cell_size > quantum()) {
    reject("min_cell_size", min_cell_size,
           "must not exceed the quantum q = box_side / (2^quantum_levels - 1) = " +
               std::to_string(quantum()) + " m");
  }
  if (max_depth() > kDeepestLevel) {
    reject("min_cell_size", min_cell_size,
           "is too small for box_side: more than 24 levels below the root");
  }
  if (voxel_size > box_side) reject("voxel_size", voxel_size, "must be at most box_side");
  if (!(sensor.vertical_fov_max > sensor.vertical_fov_min)) {
    reject("sensor.vertical_fov_max", sensor.vertical_fov_max,
           "must be above sensor.vertical_fov_min = " + std::to_string(sensor.vertical_fov_min) + " deg");
  }
  // ceil() of the quotients below stays far from int's limits once the pixel count is bounded
  if ((sensor.vertical_fov_max - sensor.vertical_fov_min) / sensor.vertical_resolution *
          (360.0 / sensor.horizontal_resolution) > kMaxPixels) {
    reject("sensor.horizontal_resolution", sensor.horizontal_resolution,
           "with sensor.vertical_resolution = " + std::to_string(sensor.vertical_resolution) +
               " deg gives a range image of more than 2^24 pixels");
  }
  if (max_age_seconds > 0.0 && !attributes.time) {
    reject("max_age_seconds", max_age_seconds, "needs attributes.time = true (the age is read from each point's time)");
  }
  if (max_age_seconds > 0.0 && max_age_frames > 0) {
    reject("max_age_seconds", max_age_seconds,
           "and max_age_frames = " + std::to_string(max_age_frames) + " are both set: give the age limit in one unit");
  }
  if (region.shape != RegionShape::Cube) {
    const char* name = region.shape == RegionShape::Ball ? "region.radius" : "region.ahead";
    const double size = region.shape == RegionShape::Ball ? region.radius : region.ahead + region.behind;
    if (!(size > 0.0)) reject(name, size, "gives an empty region: the ball needs a radius, the box a length");
    if (region.reach() > box_side / 2) {
      std::ostringstream why;
      why << "makes a region that reaches " << region.reach() << " m from the sensor in some orientation, "
          << "past the cube's half side box_side / 2 = " << box_side / 2 << " m: the cube must hold the region";
      reject(name, region.shape == RegionShape::Ball ? region.radius : region.ahead, why.str());
    }
    if (insert_policy == InsertPolicy::ShiftInOnly) {
      reject("insert_policy", "ShiftInOnly", "it takes in only what the cube newly covers; a region other than the "
                                   "cube needs AllInBox");
    }
  } else {
    if (region.lookahead != 0.0) {
      reject("region.lookahead", region.lookahead, "needs region.shape = ball or oriented_box: the cube does not grow");
    }
    if (region.max_points != 0) {
      reject("region.max_points", double(region.max_points),
             "needs region.shape = ball or oriented_box: the cube does not shrink (a ball of radius box_side / 2 "
             "holds the most a budget can)");
    }
  }

  if (density_cap.enabled()) {
    const double cell = density_cap.cell_size;
    if (cell <= 0.0) reject("density_cap.cell_size", cell, "must be > 0 m while density_cap.max_points > 0");
    if (cell > box_side) reject("density_cap.cell_size", cell, "must not exceed box_side");
    // held points span at most box_side / cell + 2 cells per axis: CellCounts names them mod 2^18
    if (box_side / cell > double((1u << 18) - 2u)) {
      std::ostringstream why;
      why << "conflicts with box_side = " << box_side << " m: the cell counts reach 262142 cells along the box, so "
          << "the cell size must be at least box_side / 262142 = " << box_side / double((1u << 18) - 2u)
          << " m (or the box at most 262142 * cell_size = " << cell * double((1u << 18) - 2u) << " m)";
      reject("density_cap.cell_size", cell, why.str());
    }
  }
}

}  // namespace eco
