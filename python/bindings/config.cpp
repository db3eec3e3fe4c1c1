// eco.Config and its parts, field for field with include/eco/config.hpp.

#include "bindings.hpp"
#include "config_record.hpp"

#include <eco/config_fields.hpp>
#include <eco/types.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace eco::python {

using namespace pybind11::literals;

namespace {

/// A field's line in the table (include/eco/config_fields.hpp), with its range, unit and default.
std::string doc_of(std::string_view name) { return config_field(name).summary(); }

/// The table, for Python: one dict per field.
py::list config_fields_list() {
  py::list out;
  for (const ConfigField& f : config_fields()) {
    const char* kind = f.kind == ConfigField::Kind::Real    ? "real"
                       : f.kind == ConfigField::Kind::Count  ? "count"
                       : f.kind == ConfigField::Kind::Switch ? "switch"
                                                             : "choice";
    py::list choices;
    for (const std::string_view c : f.choices) choices.append(std::string(c));
    out.append(py::dict("name"_a = std::string(f.name), "kind"_a = kind, "unit"_a = std::string(f.unit),
                        "doc"_a = std::string(f.doc), "range"_a = f.range(), "lo"_a = f.lo, "hi"_a = f.hi,
                        "lo_open"_a = f.lo_open, "choices"_a = choices, "default"_a = f.default_text()));
  }
  return out;
}

}  // namespace

// The records list the fields by member (for their C++ types); names and docs come from the table,
// and bind_config() checks that the two list the same fields.
std::vector<Field<DensityCap>> Record<DensityCap>::fields() {
  return {
      field("cell_size", &DensityCap::cell_size, doc_of("density_cap.cell_size")),
      field("max_points", &DensityCap::max_points, doc_of("density_cap.max_points")),
  };
}

std::vector<Field<FreeSpaceClearing>> Record<FreeSpaceClearing>::fields() {
  return {
      field("enabled", &FreeSpaceClearing::enabled, doc_of("clearing.enabled")),
      field("margin", &FreeSpaceClearing::margin, doc_of("clearing.margin")),
      field("arrivals", &FreeSpaceClearing::arrivals, doc_of("clearing.arrivals")),
  };
}

std::vector<Field<KeptAttributes>> Record<KeptAttributes>::fields() {
  return {
      field("ids", &KeptAttributes::ids, doc_of("attributes.ids")),
      field("intensity", &KeptAttributes::intensity, doc_of("attributes.intensity")),
      field("time", &KeptAttributes::time, doc_of("attributes.time")),
  };
}

std::vector<Field<SensorModel>> Record<SensorModel>::fields() {
  return {
      field("vertical_fov_min", &SensorModel::vertical_fov_min, doc_of("sensor.vertical_fov_min")),
      field("vertical_fov_max", &SensorModel::vertical_fov_max, doc_of("sensor.vertical_fov_max")),
      field("vertical_resolution", &SensorModel::vertical_resolution, doc_of("sensor.vertical_resolution")),
      field("horizontal_resolution", &SensorModel::horizontal_resolution, doc_of("sensor.horizontal_resolution")),
      field("max_range", &SensorModel::max_range, doc_of("sensor.max_range")),
  };
}

std::vector<Field<Region>> Record<Region>::fields() {
  return {
      field("shape", &Region::shape, doc_of("region.shape")),
      field("radius", &Region::radius, doc_of("region.radius")),
      field("ahead", &Region::ahead, doc_of("region.ahead")),
      field("behind", &Region::behind, doc_of("region.behind")),
      field("left", &Region::left, doc_of("region.left")),
      field("right", &Region::right, doc_of("region.right")),
      field("up", &Region::up, doc_of("region.up")),
      field("down", &Region::down, doc_of("region.down")),
      field("turn_with", &Region::turn_with, doc_of("region.turn_with")),
      field("lookahead", &Region::lookahead, doc_of("region.lookahead")),
      field("frame_period", &Region::frame_period, doc_of("region.frame_period")),
      field("max_points", &Region::max_points, doc_of("region.max_points")),
  };
}

std::vector<Field<Config>> Record<Config>::fields() {
  return {
      field("box_side", &Config::box_side, doc_of("box_side")),
      field("leaf_capacity", &Config::leaf_capacity, doc_of("leaf_capacity")),
      field("min_cell_size", &Config::min_cell_size, doc_of("min_cell_size")),
      field("recentring", &Config::recentring, doc_of("recentring")),
      field("quantum_levels", &Config::quantum_levels, doc_of("quantum_levels")),
      field("insert_policy", &Config::insert_policy, doc_of("insert_policy")),
      field("density_cap", &Config::density_cap, "DensityCap: at most max_points points per world-aligned cell of side "
                                                  "cell_size; off by default."),
      field("max_age_frames", &Config::max_age_frames, doc_of("max_age_frames")),
      field("max_age_seconds", &Config::max_age_seconds, doc_of("max_age_seconds")),
      field("attributes", &Config::attributes,
            "KeptAttributes: which per-point attributes (ids, intensity, time) the tree stores and returns; "
            "none by default."),
      field("clearing", &Config::clearing,
            "FreeSpaceClearing: remove held points the new scan sees through (off by default); see sensor."),
      field("sensor", &Config::sensor,
            "SensorModel: the LiDAR's field of view and range image, as free-space clearing sees it (an "
            "HDL-64E by default)."),
      field("region", &Config::region,
            "Region: the region held about the sensor inside the cube (the cube itself by default): a ball or "
            "a box turned with the sensor."),
      field("voxel_size", &Config::voxel_size, doc_of("voxel_size")),
  };
}

void bind_config(py::module_& m) {
  {  // the records and the table must list the same fields, in the same order
    std::vector<std::string> listed;
    auto list_parts = [&]<class Part>(const std::string& prefix, const Part*) {
      for (const Field<Part>& g : Record<Part>::fields()) listed.push_back(prefix + "." + g.name);
    };
    for (const Field<Config>& f : Record<Config>::fields()) {
      if (f.name == "density_cap") {
        list_parts(f.name, static_cast<const DensityCap*>(nullptr));
      } else if (f.name == "clearing") {
        list_parts(f.name, static_cast<const FreeSpaceClearing*>(nullptr));
      } else if (f.name == "attributes") {
        list_parts(f.name, static_cast<const KeptAttributes*>(nullptr));
      } else if (f.name == "sensor") {
        list_parts(f.name, static_cast<const SensorModel*>(nullptr));
      } else if (f.name == "region") {
        list_parts(f.name, static_cast<const Region*>(nullptr));
      } else {
        listed.push_back(f.name);
      }
    }
    std::vector<std::string> table;
    for (const ConfigField& f : config_fields()) table.emplace_back(f.name);
    if (listed != table) throw std::logic_error("eco.Config's fields differ from include/eco/config_fields.hpp");
  }
  m.def("config_fields", &config_fields_list,
        "The table of Config's fields (as C++, the eco command and config.json use it): one dict per field "
        "with name (dotted for the parts' fields: density_cap., attributes., clearing., sensor., region.), kind ('real', 'count', 'choice' or 'switch': a bool), unit, doc, range, lo, hi, "
        "lo_open, choices and default.");
  py::enum_<Recentring>(m, "Recentring", "How the root cell follows the sensor.")
      .value("Quantised", Recentring::Quantised,
             "The root moves in whole quanta q = L / (2^k - 1); re-centring re-links the top k "
             "levels. Default.")
      .value("Exact", Recentring::Exact,
             "The root is re-centred on the sensor every frame (the paper's algorithm).");
  py::enum_<InsertPolicy>(m, "InsertPolicy", "Which scan points an update inserts.")
      .value("ShiftInOnly", InsertPolicy::ShiftInOnly,
             "Only points in Box(p_t) minus Box(p_t-1): a static, pre-aggregated map streamed by "
             "pose (the paper's policy).")
      .value("AllInBox", InsertPolicy::AllInBox,
             "Every scan point inside Box(p_t): raw scans (pair with a density cap or age limit). "
             "Default.");
  py::enum_<RegionShape>(m, "RegionShape", "The region's shape (Config.region.shape).")
      .value("cube", RegionShape::Cube, "The cube itself, world axes: the paper's region. Default.")
      .value("ball", RegionShape::Ball, "Points within region.radius of the sensor.")
      .value("oriented_box", RegionShape::OrientedBox,
             "A box in the sensor's axes (x ahead, y left, z up): region.ahead ... region.down.");
  py::enum_<TurnWith>(m, "TurnWith", "How an oriented box turns with the sensor (Config.region.turn_with).")
      .value("yaw", TurnWith::Yaw, "About the world's vertical, by the sensor's heading: a ground vehicle. Default.")
      .value("full", TurnWith::Full, "With the sensor's whole orientation: a drone, a hand-held sensor.");
  py::enum_<Frame>(m, "Frame", "The frame in which query points are given and results returned.")
      .value("World", Frame::World, "The fixed world frame of the poses. Default.")
      .value("Ego", Frame::Ego, "World axes, origin at the current sensor position.")
      .value("Sensor", Frame::Sensor, "The sensor's own frame: origin at the sensor, axes turned with it (x ahead).");

  bind_record<DensityCap>(
      m, "Optional cap on points per world-aligned cell (off while max_points == 0).",
      Access::ReadWrite);
  bind_record<FreeSpaceClearing>(
      m, "Free-space clearing: each update removes the held points the new scan sees through.",
      Access::ReadWrite);
  bind_record<KeptAttributes>(
      m,
      "Which per-point attributes of the scans the tree stores and returns with every query (each costs 4 "
      "bytes per held point); a kept one must come with every scan.",
      Access::ReadWrite);
  bind_record<SensorModel>(
      m,
      "The LiDAR as free-space clearing sees it: a range image of rows of vertical_resolution degrees "
      "from vertical_fov_min to vertical_fov_max and columns of horizontal_resolution degrees.",
      Access::ReadWrite);
  bind_record<Region>(
      m,
      "The region the map holds about the sensor inside its cube: shape cube (the default), ball "
      "(radius) or oriented_box (ahead, behind, left, right, up, down in the sensor's axes, turned by "
      "turn_with); it may lead the sensor by its speed (lookahead) and keep to a budget (max_points).",
      Access::ReadWrite);
  bind_record<Config>(m,
                      "Configuration of an EgoOctree, field for field with eco::Config in C++.\n\n"
                      "Config(**fields) checks every value and validates the whole (ValueError "
                      "naming the field); enums may be given by name, density_cap as a dict.",
                      Access::ReadWrite)
      // Derived values; validated first, as attributes may have been assigned since.
      .def_property_readonly(
          "quantum", [](const Config& c) { return c.validate(), c.quantum(); },
          "The re-centring quantum q = L / (2^k - 1) [m]; 0 in Exact mode.")
      .def_property_readonly(
          "root_side", [](const Config& c) { return c.validate(), c.root_side(); },
          "Side [m] of the root cell: L in Exact mode, q * 2^k in Quantised mode.")
      .def_property_readonly(
          "max_depth", [](const Config& c) { return c.validate(), c.max_depth(); },
          "The deepest level a cell may reach.");
}

}  // namespace eco::python
