#include "sim_flags.hpp"

#include "spellings.hpp"

namespace eco::cli {

SimFlags::SimFlags(CLI::App& cmd, const std::string& prefix, sim::SimConfig& config) {
  cmd.add_option(prefix + "manoeuvre", manoeuvre,
                 "the vehicle's: route (the streets), straight (one street, never turning), uturn (40 m, a U-turn, "
                 "back, again), roundabout (round an intersection), spin (turning in place), still (standing)")
      ->check(CLI::IsMember(sim::manoeuvre_names()))
      ->capture_default_str();
  cmd.add_option(prefix + "speed", config.speed, "[m/s] the vehicle's")->capture_default_str();
  cmd.add_option(both_spellings(prefix + "spin-rate"), config.spin_rate_deg, "[deg/s] spin's")->capture_default_str();
  cmd.add_option(both_spellings(prefix + "roundabout-radius"), config.roundabout_radius,
                 "[m] roundabout's (at 9.42 m/s a radius of 6 m turns 90 deg/s)")
      ->capture_default_str();
}

void SimFlags::apply(sim::SimConfig& config) const { config.manoeuvre = sim::manoeuvre_names().at(manoeuvre); }

void SimFlags::add_to(nlohmann::json& options, const std::string& prefix, const sim::SimConfig& config) const {
  const std::string key = prefix.substr(2);
  options[key + "manoeuvre"] = manoeuvre;
  options[key + "speed"] = config.speed;
  options[key + "spin-rate"] = config.spin_rate_deg;
  options[key + "roundabout-radius"] = config.roundabout_radius;
}

}  // namespace eco::cli
