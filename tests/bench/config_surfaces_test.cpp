// The Config field table against every surface that reads a configuration: the struct itself
// (validate), the command's flags (ConfigFlags) and config.json (config_from_json). Each field's
// good value is taken by all three, each bad value refused by all three, naming the field (and the
// file) and the value, the configuration unchanged. Python walks the same table
// (python/tests/test_config.py).

#include "bench/config_json.hpp"

#include "config_options.hpp"

#include <eco/config_fields.hpp>
#include <eco/io/error.hpp>

#include <gtest/gtest.h>

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace eco {
namespace {

/// The shortest text that reads back as `v`, as the messages write values.
std::string text_of(double v) {
  std::array<char, 32> buffer{};
  const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return std::string(buffer.data(), end);
}

/// Values each field must refuse, from its kind and range alone.
std::vector<std::string> bad_values(const ConfigField& f) {
  if (f.kind == ConfigField::Kind::Choice) return {"Sideways", "", "1"};
  if (f.kind == ConfigField::Kind::Switch) return {"maybe", "", "2", "yes"};
  std::vector<std::string> out{"abc", "", "nan", "inf", f.lo_open ? text_of(f.lo) : text_of(f.lo - 1)};
  if (std::isfinite(f.hi)) out.push_back(text_of(f.hi * 2 + 1));
  if (f.kind == ConfigField::Kind::Count) {
    out.push_back(text_of(f.lo + 0.5));
    out.push_back("-1");
  }
  return out;
}

/// A value each field takes that is not its default.
std::string good_value(const ConfigField& f) {
  if (f.kind == ConfigField::Kind::Choice || f.kind == ConfigField::Kind::Switch) {
    return std::string(f.choices[f.get(Config{}) == 0.0 ? 1 : 0]);
  }
  if (f.name == "density_cap.cell_size") return "0.5";
  if (f.name == "density_cap.max_points") return "3";
  if (f.name == "quantum_levels") return "4";
  if (f.name == "voxel_size") return "0.2";
  if (f.name == "min_cell_size") return "0.1";
  return text_of(f.get(Config{}) + 1);
}

/// Parses `--name=value` with the command's flags into `config`.
void with_flag(Config& config, const ConfigField& f, const std::string& value) {
  CLI::App app;
  const cli::ConfigFlags flags(app, config);
  const std::string argument = "--" + std::string(f.name) + "=" + value;
  std::vector<std::string> args{argument};
  app.parse(args);
  flags.apply(config);
}

nlohmann::json json_with(const ConfigField& f, const nlohmann::json& value) {
  const std::size_t dot = f.name.find('.');
  nlohmann::json j = nlohmann::json::object();
  if (dot == std::string_view::npos) {
    j[std::string(f.name)] = value;
  } else {
    j[std::string(f.name.substr(0, dot))][std::string(f.name.substr(dot + 1))] = value;
  }
  return j;
}

TEST(ConfigFields, TheTableNamesEveryFieldOnceWithDocsRangesAndValidDefaults) {
  std::set<std::string_view> names;
  for (const ConfigField& f : config_fields()) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name;
    EXPECT_FALSE(f.doc.empty()) << f.name;
    EXPECT_FALSE(f.range().empty()) << f.name;
    EXPECT_NO_THROW(f.check(f.get(Config{}))) << f.name;
    EXPECT_EQ(&config_field(f.name), &f);
    Config c;  // the default's text reads back to the default
    f.parse(c, f.default_text());
    EXPECT_EQ(f.get(c), f.get(Config{})) << f.name;
  }
  EXPECT_EQ(names.size(), 34u);
  EXPECT_THROW((void)config_field("box_sid"), std::invalid_argument);
}

TEST(ConfigFields, EverySurfaceTakesTheSameGoodValue) {
  for (const ConfigField& f : config_fields()) {
    SCOPED_TRACE(std::string(f.name));
    const std::string value = good_value(f);
    Config base;
    if (f.name == "density_cap.cell_size") base.density_cap.max_points = 1;
    if (f.name == "density_cap.max_points") base.density_cap.cell_size = 0.5;
    if (f.name == "max_age_seconds") base.attributes.time = true;
    if (f.name == "region.shape") base.region = {RegionShape::Cube, 5.0, 5.0, 1.0, 1.0, 1.0, 1.0, 1.0};  // sizes for either shape
    if (f.name == "region.lookahead" || f.name == "region.max_points") base.region = {RegionShape::Ball, 5.0};
    Config by_table = base;
    f.parse(by_table, value);
    EXPECT_NO_THROW(by_table.validate());
    EXPECT_NE(f.get(by_table), f.get(base));

    Config by_flag = base;
    with_flag(by_flag, f, value);
    EXPECT_EQ(f.get(by_flag), f.get(by_table));

    nlohmann::json j = bench::config_to_json(by_table);
    const Config by_json = bench::config_from_json(j, "config.json");
    for (const ConfigField& g : config_fields()) EXPECT_EQ(g.get(by_json), g.get(by_table)) << g.name;
  }
}

TEST(ConfigFields, EverySurfaceRefusesTheSameBadValuesByName) {
  for (const ConfigField& f : config_fields()) {
    for (const std::string& bad : bad_values(f)) {
      SCOPED_TRACE(std::string(f.name) + " = " + bad);
      const Config before;
      Config c = before;
      try {
        f.parse(c, bad);
        ADD_FAILURE() << "the table took it";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(std::string(f.name)), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
      }
      EXPECT_EQ(f.get(c), f.get(before));

      Config by_flag = before;
      try {
        with_flag(by_flag, f, bad);
        ADD_FAILURE() << "the flag took it";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(std::string(f.name)), std::string::npos) << e.what();
      } catch (const CLI::Error& e) {  // an empty value is refused by CLI11 itself, naming the flag
        EXPECT_NE(std::string(e.what()).find(std::string(f.name)), std::string::npos) << e.what();
      }

      // config.json: a number where the text is one, else the text
      double number = 0.0;
      const bool numeric = f.kind != ConfigField::Kind::Choice && f.kind != ConfigField::Kind::Switch && !bad.empty() &&
                           (std::istringstream(bad) >> number) && std::isfinite(number);
      const nlohmann::json j = json_with(f, numeric ? nlohmann::json(number) : nlohmann::json(bad));
      try {
        (void)bench::config_from_json(j, "run/config.json");
        ADD_FAILURE() << "config.json took it";
      } catch (const io::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("run/config.json"), std::string::npos) << what;
        EXPECT_NE(what.find(std::string(f.name)), std::string::npos) << what;
      }

      // the struct itself, where the value is a number the field's type can hold
      if (numeric && f.kind == ConfigField::Kind::Real) {
        Config direct;
        f.set(direct, number);
        try {
          direct.validate();
          ADD_FAILURE() << "validate() took it";
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find(std::string(f.name)), std::string::npos) << e.what();
        }
      }
    }
  }
}

TEST(ConfigFields, ConfigJsonRefusesUnknownKeysAndWrongTypesNamingTheFile) {
  for (const nlohmann::json& j : {nlohmann::json{{"box_sid", 3}}, nlohmann::json{{"density_cap", {{"cells", 1}}}},
                                  nlohmann::json{{"box_side", true}}, nlohmann::json{{"box_side", {1, 2}}},
                                  nlohmann::json::array()}) {
    SCOPED_TRACE(j.dump());
    try {
      (void)bench::config_from_json(j, "x/config.json");
      ADD_FAILURE() << "taken";
    } catch (const io::Error& e) {
      EXPECT_NE(std::string(e.what()).find("x/config.json"), std::string::npos) << e.what();
    }
  }
  // fields that do not fit together are refused as validate() refuses them
  const nlohmann::json j{{"box_side", 10.0}, {"density_cap", {{"cell_size", 20.0}, {"max_points", 1}}}};
  EXPECT_THROW((void)bench::config_from_json(j, "x/config.json"), io::Error);
  for (const nlohmann::json& apart : {nlohmann::json{{"max_age_seconds", 5.0}},  // without attributes.time
                                      nlohmann::json{{"max_age_seconds", 5.0},
                                                     {"max_age_frames", 3},
                                                     {"attributes", {{"time", true}}}}}) {
    SCOPED_TRACE(apart.dump());
    try {
      (void)bench::config_from_json(apart, "x/config.json");
      ADD_FAILURE() << "taken";
    } catch (const io::Error& e) {
      EXPECT_NE(std::string(e.what()).find("max_age_seconds"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace eco
