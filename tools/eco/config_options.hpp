#pragma once
// The tree configuration as command-line options, shared by `eco bench` and `eco run`.

#include <eco/config.hpp>

#include <CLI/CLI.hpp>

#include <map>
#include <string>

namespace eco::cli {

inline void add_config_options(CLI::App& cmd, Config& config) {
  const std::map<std::string, InsertPolicy> policies{{"shift-in", InsertPolicy::ShiftInOnly},
                                                      {"all-in-box", InsertPolicy::AllInBox}};
  cmd.add_option("--box-side", config.box_side, "L: side of the ego cube [m]")->capture_default_str();
  cmd.add_option("--leaf-capacity", config.leaf_capacity, "N_max: points a leaf holds before it splits")
      ->capture_default_str();
  cmd.add_option("--min-cell", config.min_cell_size, "smallest cell side [m]")->capture_default_str();
  cmd.add_option("--quantum-levels", config.quantum_levels, "k of the quantised re-centring (1-5)")
      ->capture_default_str();
  cmd.add_option("--policy", config.insert_policy, "scan points inserted: shift-in (R_in only) or all-in-box")
      ->transform(CLI::CheckedTransformer(policies, CLI::ignore_case))
      ->capture_default_str();
  cmd.add_option("--density-cell", config.density_cap.cell_size, "density cap cell side [m]")->capture_default_str();
  cmd.add_option("--density-max", config.density_cap.max_points, "density cap: points per cell (0 = off)")
      ->capture_default_str();
  cmd.add_option("--max-age", config.max_age_frames, "drop points older than this many frames (0 = off)")
      ->capture_default_str();
}

}  // namespace eco::cli
