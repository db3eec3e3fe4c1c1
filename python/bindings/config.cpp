// eco.Config and its parts, field for field with include/eco/config.hpp.

#include "bindings.hpp"
#include "config_record.hpp"

#include <eco/types.hpp>

namespace eco::python {

std::vector<Field<DensityCap>> Record<DensityCap>::fields() {
  return {
      field("cell_size", &DensityCap::cell_size,
            "[m] side of the density cell; typical 0.05-0.5; in (box_side / 262142, box_side] "
            "when the cap is on."),
      field("max_points", &DensityCap::max_points,
            "points per cell; 0 = cap off, typical 1-10, at most 1023."),
  };
}

std::vector<Field<Config>> Record<Config>::fields() {
  return {
      field("box_side", &Config::box_side,
            "L [m]: side of the ego cube held around the sensor; typical 10-100."),
      field("leaf_capacity", &Config::leaf_capacity,
            "N_max: a leaf with more points splits; typical 8-64."),
      field("min_cell_size", &Config::min_cell_size,
            "[m] cells are never split below this side; typical 0.01-0.5."),
      field("recentring", &Config::recentring,
            "Recentring.Quantised (default: the root moves in whole quanta) or "
            "Recentring.Exact (the paper's: re-centred on the sensor every frame)."),
      field("quantum_levels", &Config::quantum_levels,
            "k, Quantised only: quantum q = L / (2^k - 1); range 1-5."),
      field("insert_policy", &Config::insert_policy,
            "InsertPolicy.AllInBox (default: every scan point in the box, for raw scans) or "
            "InsertPolicy.ShiftInOnly (the paper's: only points in the newly entered region)."),
      field("density_cap", &Config::density_cap,
            "DensityCap: at most max_points points per world-aligned cell of side cell_size; "
            "off by default."),
      field("max_age_frames", &Config::max_age_frames,
            "drop points inserted more than this many frames ago; 0 = off."),
      field("voxel_size", &Config::voxel_size,
            "[m] Quantised only: the voxel size voxel maps will be asked at; the quantum is "
            "rounded up to voxel_size * 2^j so voxel_keys(voxel_size * 2^i) walks nodes, not "
            "points. 0 = the paper's quantum L / (2^k - 1)."),
  };
}

void bind_config(py::module_& m) {
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
  py::enum_<Frame>(m, "Frame", "The frame in which query points are given and results returned.")
      .value("World", Frame::World, "The fixed world frame of the poses. Default.")
      .value("Ego", Frame::Ego, "World axes, origin at the current sensor position.");

  bind_record<DensityCap>(
      m, "Optional cap on points per world-aligned cell (off while max_points == 0).",
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
