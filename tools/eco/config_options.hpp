#pragma once
// The tree configuration on the command line: one flag per Config field, named after it
// (--box_side, --density_cap.cell_size, --insert_policy AllInBox), from the field table, so the flags
// take the same names and values as config.json and Python and refuse the same ones.

#include "spellings.hpp"

#include <eco/config_fields.hpp>

#include <CLI/CLI.hpp>

#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace eco::cli {

/// The settings a command runs with, in one line, for the start of its output.
inline std::string describe_settings(const Config& c) {
  std::ostringstream s;
  s << "L = " << c.box_side << " m, N_max = " << c.leaf_capacity << ", "
    << (c.insert_policy == InsertPolicy::AllInBox ? "AllInBox" : "ShiftInOnly") << ", "
    << (c.recentring == Recentring::Exact ? "exact" : "quantised") << " re-centring, density cap ";
  if (c.density_cap.enabled()) {
    s << c.density_cap.max_points << " per " << c.density_cap.cell_size << " m cell";
  } else {
    s << "off";
  }
  s << ", free-space clearing " << (!c.clearing.enabled ? "off" : c.clearing.arrivals ? "on, with arrivals" : "on");
  const Region& r = c.region;
  if (r.shape == RegionShape::Ball) s << ", region: a ball of " << r.radius << " m";
  if (r.shape == RegionShape::OrientedBox) {
    s << ", region: a box " << r.ahead << " m ahead, " << r.behind << " behind, " << r.left << " left, " << r.right
      << " right, " << r.up << " up, " << r.down << " down, turned by " << (r.turn_with == TurnWith::Yaw ? "heading" : "every turn");
  }
  if (r.lookahead > 0.0) s << ", leading by " << r.lookahead << " s of its speed";
  if (r.max_points > 0) s << ", at most " << r.max_points << " points";
  return s.str();
}

class ConfigFlags {
 public:
  /// Adds the flags to `cmd`; `defaults` is what the command uses when a flag is not given.
  ConfigFlags(CLI::App& cmd, const Config& defaults) : texts_(config_fields().size()) {
    std::size_t i = 0;
    for (const ConfigField& f : config_fields()) {
      const char* type = f.kind == ConfigField::Kind::Real    ? "REAL"
                         : f.kind == ConfigField::Kind::Count  ? "UINT"
                         : f.kind == ConfigField::Kind::Switch ? "BOOL"
                                                               : "NAME";
      options_.push_back(
          cmd.add_option(both_spellings("--" + std::string(f.name)), texts_[i++], f.summary(defaults))
              ->type_name(type)
              ->group("Tree configuration"));
    }
  }

  /// Sets in `config` the fields whose flags were given, then validates it. Throws
  /// std::invalid_argument naming the field and value.
  void apply(Config& config) const {
    std::size_t i = 0;
    for (const ConfigField& f : config_fields()) {
      if (options_[i]->count() > 0) f.parse(config, texts_[i]);
      ++i;
    }
    try {
      config.validate();
    } catch (const std::invalid_argument& e) {  // name what was given as it was typed
      const std::string what = e.what();
      const std::string named = given([&](const std::string& name) { return what.find(name + " = ") != std::string::npos; });
      if (named.empty()) throw;
      throw std::invalid_argument(what + " (given: " + named + ")");
    }
  }

  /// The flags given (of the fields `pick` takes, when given), as typed: "--box_side 30,
  /// --leaf_capacity 64"; empty when none.
  [[nodiscard]] std::string given(const std::function<bool(const std::string&)>& pick = {}) const {
    std::string out;
    std::size_t i = 0;
    for (const ConfigField& f : config_fields()) {
      const std::string name(f.name);
      if (options_[i]->count() > 0 && (!pick || pick(name))) out += (out.empty() ? "--" : ", --") + name + " " + texts_[i];
      ++i;
    }
    return out;
  }

 private:
  std::vector<std::string> texts_;
  std::vector<CLI::Option*> options_;
};

}  // namespace eco::cli
