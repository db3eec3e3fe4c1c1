// eco_node's parameters (ros/node_parameters.hpp) without a roscore: every Config field through
// the one table under its parameter name, the node's own, and each refusal named.

#include "node_parameters.hpp"

#include <eco/config_fields.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace eco::ros_node {
namespace {

using Given = std::map<std::string, std::string>;

NodeParameters read(const Given& given) {
  std::vector<std::string> names;
  for (const auto& [name, value] : given) names.push_back(name);
  return read_parameters(
      [&](const std::string& name) -> std::optional<std::string> {
        const auto it = given.find(name);
        if (it == given.end()) return std::nullopt;
        return it->second;
      },
      names);
}

/// The message read(given) throws.
std::string refusal(const Given& given) {
  try {
    (void)read(given);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(not refused)";
}

TEST(NodeParameters, NoneGivenIsTheLibrarysDefaults) {
  const NodeParameters p = read({});
  for (const ConfigField& f : config_fields()) EXPECT_EQ(f.format(p.config), f.default_text()) << f.name;
  EXPECT_EQ(p.node.cloud_topic, "points");
  EXPECT_TRUE(p.node.pose_topic.empty());
  EXPECT_EQ(p.node.fixed_frame, "map");
  EXPECT_FALSE(p.node.odometry);
  EXPECT_EQ(p.node.publish_every, 1u);
}

TEST(NodeParameters, EveryConfigFieldIsAParameterOfItsName) {
  // what a field's other value needs beside it (a rule between fields), as parameters
  const std::map<std::string, Given> beside = {
      {"density_cap.max_points", {{"density_cap/cell_size", "0.2"}}},
      {"max_age_seconds", {{"attributes/time", "true"}}},
      {"region.shape", {{"region/ahead", "6"}, {"region/behind", "2"}, {"region/left", "3"}, {"region/right", "3"},
                        {"region/up", "2"}, {"region/down", "2"}}},
      {"region.lookahead", {{"region/shape", "ball"}, {"region/radius", "6"}}},
      {"region.max_points", {{"region/shape", "ball"}, {"region/radius", "6"}}}};
  // each field given a value of its range other than its default, as text, one at a time
  for (const ConfigField& f : config_fields()) {
    const double was = f.get(Config{});
    std::string text;
    if (f.kind == ConfigField::Kind::Switch) {
      text = was != 0.0 ? "false" : "true";
    } else if (f.kind == ConfigField::Kind::Choice) {
      text = std::string(f.choices[f.choices.size() - 1 - std::size_t(was)]);
    } else {
      for (const double v : {2 * was, was / 2, was + 1, f.lo + 1, (f.lo + f.hi) / 2}) {
        if (v == was || (f.kind == ConfigField::Kind::Count && v != std::floor(v))) continue;
        try {
          f.check(v);
        } catch (const std::invalid_argument&) {
          continue;
        }
        Config other;
        f.set(other, v);
        text = f.format(other);
        break;
      }
    }
    ASSERT_FALSE(text.empty()) << f.name;
    const auto needs = beside.find(std::string(f.name));
    Given given = needs == beside.end() ? Given{} : needs->second;
    given[parameter_name(f.name)] = text;
    Config want;
    for (const auto& [name, value] : given) {
      std::string field = name;
      std::ranges::replace(field, '/', '.');
      config_field(field).parse(want, value);
    }
    ASSERT_NE(f.get(want), was) << f.name;
    const NodeParameters p = read(given);
    for (const ConfigField& g : config_fields()) EXPECT_EQ(g.format(p.config), g.format(want)) << f.name << ": " << g.name;
  }
  const NodeParameters p = read({{"density_cap/cell_size", "0.1"}, {"density_cap/max_points", "2"}, {"box_side", "33"},
                                 {"insert_policy", "ShiftInOnly"}, {"clearing/enabled", "true"}});
  EXPECT_EQ(p.config.density_cap.cell_size, 0.1);
  EXPECT_EQ(p.config.density_cap.max_points, 2u);
  EXPECT_EQ(p.config.box_side, 33.0);
  EXPECT_EQ(p.config.insert_policy, InsertPolicy::ShiftInOnly);
  EXPECT_TRUE(p.config.clearing.enabled);
}

TEST(NodeParameters, TheNodesOwnAreRead) {
  const NodeParameters p = read({{"cloud_topic", "/os/points"}, {"pose_topic", "/odom"}, {"fixed_frame", "odom"},
                                 {"tf_timeout", "0.25"}, {"time_field", "t"}, {"time_unit", "ns"},
                                 {"odometry", "true"}, {"odometry_voxel_size", "0.5"}, {"odometry_deskew", "false"},
                                 {"publish_every", "5"}, {"voxel", "0"}, {"save_path", "/tmp/m.eco"},
                                 {"save_on_exit", "true"}, {"queue_size", "3"}});
  EXPECT_EQ(p.node.cloud_topic, "/os/points");
  EXPECT_EQ(p.node.pose_topic, "/odom");
  EXPECT_EQ(p.node.fixed_frame, "odom");
  EXPECT_EQ(p.node.tf_timeout, 0.25);
  EXPECT_EQ(p.time.field, "t");
  EXPECT_EQ(p.time.unit, io::TimeUnit::Nanoseconds);
  EXPECT_TRUE(p.node.odometry);
  EXPECT_EQ(p.odometry_config.voxel_size, 0.5);
  EXPECT_FALSE(p.odometry_config.deskew);
  EXPECT_EQ(p.node.publish_every, 5u);
  EXPECT_EQ(p.node.voxel, 0.0);
  EXPECT_EQ(p.node.save_path, "/tmp/m.eco");
  EXPECT_TRUE(p.node.save_on_exit);
  EXPECT_EQ(p.node.queue_size, 3);
}

TEST(NodeParameters, BadValuesAreRefusedByNameAndValue) {
  const std::vector<std::pair<Given, std::string>> cases = {
      {{{"box_side", "-3"}}, "~box_side = -3"},
      {{{"box_side", "lots"}}, "~box_side = lots"},
      {{{"insert_policy", "Sideways"}}, "~insert_policy = Sideways"},
      {{{"clearing/enabled", "maybe"}}, "~clearing/enabled = maybe"},
      {{{"tf_timeout", "0"}}, "~tf_timeout = 0: out of range (0, 60]"},
      {{{"publish_every", "1.5"}}, "~publish_every = 1.5: not a whole number"},
      {{{"voxel", "-1"}}, "~voxel = -1"},
      {{{"time_unit", "parsecs"}}, "~time_unit = parsecs"},
      {{{"odometry", "yes"}}, "~odometry = yes: not true or false"},
      {{{"cloud_topic", ""}}, "~cloud_topic = \"\": must not be empty"},
      {{{"odometry_voxel_size", "0"}}, "~odometry_voxel_size = 0"},
      {{{"box_sid", "30"}}, "~box_sid is not a parameter of eco_node: did you mean ~box_side?"},
      {{{"zzz", "1"}}, "~zzz is not a parameter of eco_node (eco_node --help"},
      // a rule between fields: the fields given are named
      {{{"max_age_seconds", "2"}}, "(given: ~max_age_seconds = 2)"},
  };
  for (const auto& [given, said] : cases) {
    const std::string what = refusal(given);
    EXPECT_NE(what.find(said), std::string::npos) << "said: " << what << "\nwanted: " << said;
  }
}

TEST(NodeParameters, TheHelpListsEveryParameter) {
  const std::string help = describe_parameters();
  for (const ConfigField& f : config_fields()) {
    std::string listed = "~";  // (built in steps: GCC 12 warns falsely of a chain of +)
    listed += parameter_name(f.name);
    listed += ' ';
    EXPECT_NE(help.find(listed), std::string::npos) << f.name;
  }
  for (const char* name : {"~cloud_topic", "~pose_topic", "~fixed_frame", "~tf_timeout", "~odometry ", "~publish_every",
                           "~voxel ", "~save_path", "~save_on_exit", "~time_field", "~time_unit", "~queue_size"}) {
    EXPECT_NE(help.find(name), std::string::npos) << name;
  }
}

}  // namespace
}  // namespace eco::ros_node
