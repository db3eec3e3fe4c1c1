#pragma once
// How the simulator's vehicle moves (sim::SimConfig's manoeuvre, speed, spin rate, roundabout),
// the same flags on eco simulate and eco bench.

#include <eco/sim/simulator.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace eco::cli {

struct SimFlags {
  std::string manoeuvre = "route";

  /// Adds the flags to `cmd`, `prefix` before each name ("--" or "--sim-"), writing into `config`
  /// (which must outlive the command's parsing).
  SimFlags(CLI::App& cmd, const std::string& prefix, sim::SimConfig& config);
  /// `config` with the manoeuvre the flag names.
  void apply(sim::SimConfig& config) const;
  /// The flags given, as config.json keys them (without the prefix's dashes).
  void add_to(nlohmann::json& options, const std::string& prefix, const sim::SimConfig& config) const;
};

}  // namespace eco::cli
