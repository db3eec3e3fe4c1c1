#include <eco/config_fields.hpp>

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace eco {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMaxCount = 4294967295.0;  // std::uint32_t

constexpr std::array<std::string_view, 2> kRecentring{"Quantised", "Exact"};
constexpr std::array<std::string_view, 2> kInsertPolicy{"ShiftInOnly", "AllInBox"};
constexpr std::array<std::string_view, 2> kSwitch{"false", "true"};  // a Switch's values 0 and 1
constexpr std::array<std::string_view, 3> kRegionShape{"cube", "ball", "oriented_box"};
constexpr std::array<std::string_view, 2> kTurnWith{"yaw", "full"};

// One accessor pair per field: the value as a double (a count or an enum's index are exact).
#define ECO_FIELD_ACCESS(member, type)                                  \
  [](const Config& c) { return double(c.member); },                      \
  [](Config& c, double v) { c.member = type(v); }

const std::array<ConfigField, 34> kFields{{
    {"box_side", ConfigField::Kind::Real, "m", "L: side of the ego cube held around the sensor; typical 10-100",
     0.0, 1e5, true, {}, ECO_FIELD_ACCESS(box_side, double)},
    {"leaf_capacity", ConfigField::Kind::Count, "points", "N_max: a leaf with more points splits; typical 8-128",
     1.0, kMaxCount, false, {}, ECO_FIELD_ACCESS(leaf_capacity, std::uint32_t)},
    {"min_cell_size", ConfigField::Kind::Real, "m", "cells are never split below this side; typical 0.01-0.5",
     0.0, kInf, true, {}, ECO_FIELD_ACCESS(min_cell_size, double)},
    {"recentring", ConfigField::Kind::Choice, "",
     "how the root follows the sensor: Quantised (whole quanta; re-links the top levels) or Exact (the "
     "paper's: re-centred every frame)",
     0.0, 1.0, false, kRecentring, ECO_FIELD_ACCESS(recentring, Recentring)},
    {"quantum_levels", ConfigField::Kind::Count, "",
     "k, Quantised only: the quantum is q = box_side / (2^k - 1)", 1.0, 5.0, false, {},
     ECO_FIELD_ACCESS(quantum_levels, std::uint32_t)},
    {"insert_policy", ConfigField::Kind::Choice, "",
     "scan points an update inserts: AllInBox (every point in the box: raw scans) or ShiftInOnly (the "
     "paper's: only the newly entered region)",
     0.0, 1.0, false, kInsertPolicy, ECO_FIELD_ACCESS(insert_policy, InsertPolicy)},
    {"density_cap.cell_size", ConfigField::Kind::Real, "m",
     "side of the density cap's world-aligned cell; > 0 while the cap is on, at least box_side / 262142 "
     "and at most box_side",
     0.0, 1e5, false, {}, ECO_FIELD_ACCESS(density_cap.cell_size, double)},
    {"density_cap.max_points", ConfigField::Kind::Count, "points",
     "points kept per density cell; 0 = cap off, typical 1-10", 0.0, 1023.0, false, {},
     ECO_FIELD_ACCESS(density_cap.max_points, std::uint32_t)},
    {"max_age_frames", ConfigField::Kind::Count, "frames", "drop points inserted more than this many frames ago; 0 = off",
     0.0, kMaxCount, false, {}, ECO_FIELD_ACCESS(max_age_frames, std::uint32_t)},
    {"max_age_seconds", ConfigField::Kind::Real, "s",
     "drop points whose time is more than this before the latest time taken in; 0 = off; needs "
     "attributes.time, not with max_age_frames",
     0.0, 1e9, false, {}, ECO_FIELD_ACCESS(max_age_seconds, double)},
    {"attributes.ids", ConfigField::Kind::Switch, "", "keep each scan point's uint32 id and return it with queries",
     0.0, 1.0, false, kSwitch, ECO_FIELD_ACCESS(attributes.ids, bool)},
    {"attributes.intensity", ConfigField::Kind::Switch, "",
     "keep each scan point's intensity and return it with queries", 0.0, 1.0, false, kSwitch,
     ECO_FIELD_ACCESS(attributes.intensity, bool)},
    {"attributes.time", ConfigField::Kind::Switch, "",
     "keep each scan point's time [s] and return it with queries (max_age_seconds needs it)", 0.0, 1.0, false,
     kSwitch, ECO_FIELD_ACCESS(attributes.time, bool)},
    {"clearing.enabled", ConfigField::Kind::Switch, "",
     "free-space clearing: remove held points the new scan sees through (a return farther along the same "
     "ray); off by default",
     0.0, 1.0, false, kSwitch, ECO_FIELD_ACCESS(clearing.enabled, bool)},
    {"clearing.margin", ConfigField::Kind::Real, "m",
     "clearing: the nearest return around a held point must lie this much farther than it", 0.01, 1e5, false, {},
     ECO_FIELD_ACCESS(clearing.margin, double)},
    {"clearing.arrivals", ConfigField::Kind::Switch, "",
     "clearing: a point that arrived where the scan before saw empty space (something moved in) is held "
     "until the next update only; on by default (it acts only while clearing is enabled)",
     0.0, 1.0, false, kSwitch, ECO_FIELD_ACCESS(clearing.arrivals, bool)},
    {"sensor.vertical_fov_min", ConfigField::Kind::Real, "deg", "elevation of the sensor's lowest beam", -90.0,
     90.0, false, {}, ECO_FIELD_ACCESS(sensor.vertical_fov_min, double)},
    {"sensor.vertical_fov_max", ConfigField::Kind::Real, "deg",
     "elevation just above the sensor's highest beam; above vertical_fov_min", -90.0, 90.0, false, {},
     ECO_FIELD_ACCESS(sensor.vertical_fov_max, double)},
    {"sensor.vertical_resolution", ConfigField::Kind::Real, "deg",
     "range image row height: about the beam spacing (the largest, if uneven)", 0.0, 180.0, true, {},
     ECO_FIELD_ACCESS(sensor.vertical_resolution, double)},
    {"sensor.horizontal_resolution", ConfigField::Kind::Real, "deg",
     "range image column width: two to three firing steps", 0.0, 360.0, true, {},
     ECO_FIELD_ACCESS(sensor.horizontal_resolution, double)},
    {"sensor.max_range", ConfigField::Kind::Real, "m", "returns and held points farther away are not used", 0.0,
     1e6, true, {}, ECO_FIELD_ACCESS(sensor.max_range, double)},
    {"region.shape", ConfigField::Kind::Choice, "",
     "the region held about the sensor: cube (the box itself, world axes), ball (region.radius) or "
     "oriented_box (region.ahead ... region.down in the sensor's axes)",
     0.0, 2.0, false, kRegionShape, ECO_FIELD_ACCESS(region.shape, RegionShape)},
    {"region.radius", ConfigField::Kind::Real, "m", "ball: the radius held about the sensor", 0.0, 1e5, false, {},
     ECO_FIELD_ACCESS(region.radius, double)},
    {"region.ahead", ConfigField::Kind::Real, "m", "oriented_box: held ahead of the sensor (its x)", 0.0, 1e5, false,
     {}, ECO_FIELD_ACCESS(region.ahead, double)},
    {"region.behind", ConfigField::Kind::Real, "m", "oriented_box: held behind the sensor", 0.0, 1e5, false, {},
     ECO_FIELD_ACCESS(region.behind, double)},
    {"region.left", ConfigField::Kind::Real, "m", "oriented_box: held to the sensor's left (its y)", 0.0, 1e5, false,
     {}, ECO_FIELD_ACCESS(region.left, double)},
    {"region.right", ConfigField::Kind::Real, "m", "oriented_box: held to the sensor's right", 0.0, 1e5, false, {},
     ECO_FIELD_ACCESS(region.right, double)},
    {"region.up", ConfigField::Kind::Real, "m", "oriented_box: held above the sensor (its z)", 0.0, 1e5, false, {},
     ECO_FIELD_ACCESS(region.up, double)},
    {"region.down", ConfigField::Kind::Real, "m", "oriented_box: held below the sensor", 0.0, 1e5, false, {},
     ECO_FIELD_ACCESS(region.down, double)},
    {"region.turn_with", ConfigField::Kind::Choice, "",
     "oriented_box: yaw (turns about the world's vertical, a ground vehicle) or full (every turn of the "
     "sensor, a drone or a hand-held sensor)",
     0.0, 1.0, false, kTurnWith, ECO_FIELD_ACCESS(region.turn_with, TurnWith)},
    {"region.lookahead", ConfigField::Kind::Real, "s",
     "ball or oriented_box: ahead (a ball: radius) grows by the smoothed speed times this, up to what the cube "
     "holds; 0 = a fixed size",
     0.0, 1e3, false, {}, ECO_FIELD_ACCESS(region.lookahead, double)},
    {"region.frame_period", ConfigField::Kind::Real, "s",
     "the time between scans for the lookahead's speed when scans carry no times", 0.0, 1e3, true, {},
     ECO_FIELD_ACCESS(region.frame_period, double)},
    {"region.max_points", ConfigField::Kind::Count, "points",
     "ball or oriented_box: the most points held; the region shrinks about the sensor to fit; 0 = no budget",
     0.0, kMaxCount, false, {}, ECO_FIELD_ACCESS(region.max_points, std::uint32_t)},
    {"voxel_size", ConfigField::Kind::Real, "m",
     "Quantised only: the voxel size voxel maps are asked at (cells become voxels of voxel_size * 2^i); "
     "0 = the paper's quantum; at most box_side",
     0.0, 1e5, false, {}, ECO_FIELD_ACCESS(voxel_size, double)},
}};

#undef ECO_FIELD_ACCESS

/// The shortest text that reads back as `v` ("nan", "1e-05", "7"): values in errors and config.json.
std::string number_text(double v) {
  std::array<char, 32> buffer{};
  const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return error == std::errc() ? std::string(buffer.data(), end) : std::to_string(v);
}

[[noreturn]] void reject(std::string_view name, std::string_view value, std::string_view rule) {
  std::ostringstream msg;
  msg << "eco::Config: " << name << " = " << value << " is invalid: " << rule;
  throw std::invalid_argument(msg.str());
}

bool same_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  }
  return true;
}


}  // namespace

std::string ConfigField::range() const {
  switch (kind) {
    case Kind::Choice:
    case Kind::Switch: {
      std::string out;
      for (const std::string_view c : choices) out += (out.empty() ? "" : " | ") + std::string(c);
      return out;
    }
    case Kind::Count:
      return number_text(lo) + ".." + number_text(hi);
    case Kind::Real: {
      std::ostringstream s;
      if (hi == kInf) {
        s << (lo_open ? "> " : ">= ") << number_text(lo);
      } else {
        s << (lo_open ? "(" : "[") << number_text(lo) << ", " << number_text(hi) << "]";
      }
      return s.str();
    }
  }
  return {};
}

std::string ConfigField::summary(const Config& defaults) const {
  std::ostringstream s;
  s << doc << " [" << range() << (unit.empty() ? "" : " ") << unit << "; default " << format(defaults) << "]";
  return s.str();
}

std::string ConfigField::format(const Config& config) const {
  const double v = get(config);
  if (kind == Kind::Choice || kind == Kind::Switch) {
    const auto i = std::size_t(v);
    return v >= 0.0 && i < choices.size() ? std::string(choices[i]) : number_text(v);
  }
  return number_text(v);
}

namespace {

/// ConfigField::check, naming the value as `shown` (what the user typed, where there is text).
void check_value(const ConfigField& f, double v, std::string_view shown) {
  using Kind = ConfigField::Kind;
  if (f.kind == Kind::Choice || f.kind == Kind::Switch) {
    if (!(v >= 0.0 && v < double(f.choices.size()) && v == std::floor(v))) {
      reject(f.name, shown, "is not one of " + f.range());
    }
    return;
  }
  const bool below = f.lo_open ? !(v > f.lo) : !(v >= f.lo);
  if (!std::isfinite(v) || below || v > f.hi || (f.kind == Kind::Count && v != std::floor(v))) {
    std::ostringstream rule;
    rule << (f.kind == Kind::Count ? "must be a whole number in " : "must be finite and in ") << f.range();
    if (!f.unit.empty() && f.kind == Kind::Real) rule << ' ' << f.unit;
    reject(f.name, shown, rule.str());
  }
}

}  // namespace

void ConfigField::check(double v) const { check_value(*this, v, number_text(v)); }

void ConfigField::parse(Config& config, std::string_view text) const {
  std::ostringstream quoted;
  quoted << '"' << text << '"';
  const std::string shown = quoted.str();
  if (kind == Kind::Choice || kind == Kind::Switch) {
    for (std::size_t i = 0; i < choices.size(); ++i) {
      if (same_ignoring_case(text, choices[i])) {
        set(config, double(i));
        return;
      }
    }
    reject(name, shown, "is not one of " + range());
  }
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto [at, error] = std::from_chars(text.data(), end, v);
  if (text.empty() || error != std::errc() || at != end) {
    reject(name, shown, kind == Kind::Count ? "is not a whole number" : "is not a number");
  }
  check_value(*this, v, text);  // named as typed: 1e5, not 1e+05
  set(config, v);
}

std::span<const ConfigField> config_fields() { return kFields; }

const ConfigField& config_field(std::string_view name) {
  std::string known;
  for (const ConfigField& f : kFields) {
    if (f.name == name) return f;
    known += (known.empty() ? "" : ", ") + std::string(f.name);
  }
  throw std::invalid_argument("eco::Config has no field \"" + std::string(name) + "\" (fields: " + known + ")");
}

}  // namespace eco
