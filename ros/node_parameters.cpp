#include "node_parameters.hpp"

#include "text/nearest_name.hpp"

#include <eco/config_fields.hpp>

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace eco::ros_node {
namespace {

[[noreturn]] void refuse(const std::string& name, const std::string& text, const std::string& why) {
  throw std::invalid_argument("~" + name + " = " + text + ": " + why);
}

double number(const std::string& name, const std::string& text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) refuse(name, text, "not a number");
  return value;
}

bool switch_value(const std::string& name, const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  refuse(name, text, "not true or false");
}

/// One of the node's own parameters: its name, what it is, its default as text, and how it is set.
struct NodeParameter {
  std::string name;
  std::string doc;
  std::function<std::string(const NodeParameters&)> show;  // the value, as text
  std::function<void(NodeParameters&, const std::string& text)> set;  // throws naming the parameter
};

/// A parameter's value in a copy of `p` (for the help's defaults).
template <class Field>
auto value_in(const NodeParameters& p, const Field& field) {
  NodeParameters copy = p;
  return field(copy);
}

NodeParameter text_parameter(std::string name, std::string doc, std::function<std::string&(NodeParameters&)> field,
                             bool may_be_empty) {
  return {name, std::move(doc), [field](const NodeParameters& p) { return value_in(p, field); },
          [name, field, may_be_empty](NodeParameters& p, const std::string& text) {
            if (text.empty() && !may_be_empty) refuse(name, "\"\"", "must not be empty");
            field(p) = text;
          }};
}

NodeParameter real_parameter(std::string name, std::string doc, double lo, double hi, bool zero_allowed,
                             std::function<double&(NodeParameters&)> field) {
  std::ostringstream range;
  range << (zero_allowed ? "0 or " : "") << "(" << lo << ", " << hi << "]";
  doc += " [" + range.str() + "]";
  return {name, std::move(doc),
          [field](const NodeParameters& p) {
            std::ostringstream s;
            s << value_in(p, field);
            return s.str();
          },
          [name, lo, hi, zero_allowed, field, range = range.str()](NodeParameters& p, const std::string& text) {
            const double v = number(name, text);
            if (!(zero_allowed && v == 0.0) && !(v > lo && v <= hi)) refuse(name, text, "out of range " + range);
            field(p) = v;
          }};
}

NodeParameter switch_parameter(std::string name, std::string doc, std::function<bool&(NodeParameters&)> field) {
  return {name, std::move(doc) + " [false | true]",
          [field](const NodeParameters& p) { return std::string(value_in(p, field) ? "true" : "false"); },
          [name, field](NodeParameters& p, const std::string& text) { field(p) = switch_value(name, text); }};
}

NodeParameter count_parameter(std::string name, std::string doc, double lo, double hi,
                              std::function<void(NodeParameters&, double)> set, std::function<double(const NodeParameters&)> get) {
  std::ostringstream range;
  range << lo << ".." << hi;
  return {name, std::move(doc) + " [" + range.str() + "]",
          [get](const NodeParameters& p) {
            std::ostringstream s;
            s << get(p);
            return s.str();
          },
          [name, lo, hi, set, range = range.str()](NodeParameters& p, const std::string& text) {
            const double v = number(name, text);
            if (v != std::floor(v) || v < lo || v > hi) refuse(name, text, "not a whole number in " + range);
            set(p, v);
          }};
}

const std::vector<NodeParameter>& node_parameters() {
  static const std::vector<NodeParameter> table = [] {
    std::vector<NodeParameter> t;
    t.push_back(text_parameter("cloud_topic", "sensor_msgs/PointCloud2 to map", [](NodeParameters& p) -> std::string& { return p.node.cloud_topic; }, false));
    t.push_back(count_parameter("queue_size", "clouds held while an update runs", 1, 1000,
                                [](NodeParameters& p, double v) { p.node.queue_size = int(v); },
                                [](const NodeParameters& p) { return double(p.node.queue_size); }));
    t.push_back(text_parameter("pose_topic", "nav_msgs/Odometry placing the clouds; empty: tf", [](NodeParameters& p) -> std::string& { return p.node.pose_topic; }, true));
    t.push_back(text_parameter("fixed_frame", "the frame the map is held and published in", [](NodeParameters& p) -> std::string& { return p.node.fixed_frame; }, false));
    t.push_back(real_parameter("tf_timeout", "[s] how long a cloud waits for its poses", 0.0, 60.0, false,
                               [](NodeParameters& p) -> double& { return p.node.tf_timeout; }));
    t.push_back(text_parameter("time_field", "the clouds' per-point time field; empty: found by name",
                               [](NodeParameters& p) -> std::string& { return p.time.field; }, true));
    t.push_back({"time_unit", "the time field's unit [auto | s | ms | us | ns]",
                 [](const NodeParameters& p) { return std::string(io::name_of(p.time.unit)); },
                 [](NodeParameters& p, const std::string& text) {
                   const std::optional<io::TimeUnit> unit = io::time_unit_named(text);
                   if (!unit) refuse("time_unit", text, "not auto, s, ms, us or ns");
                   p.time.unit = *unit;
                 }});
    t.push_back(switch_parameter("odometry", "ECO's LiDAR odometry estimates the poses and publishes them",
                                 [](NodeParameters& p) -> bool& { return p.node.odometry; }));
    t.push_back(real_parameter("odometry_max_range", "[m] the odometry drops farther returns", 0.0, 1e4, false,
                               [](NodeParameters& p) -> double& { return p.odometry_config.max_range; }));
    t.push_back(real_parameter("odometry_min_range", "[m] ... and nearer ones", 0.0, 1e4, true,
                               [](NodeParameters& p) -> double& { return p.odometry_config.min_range; }));
    t.push_back(real_parameter("odometry_voxel_size", "[m] the odometry's map cell", 0.0, 100.0, false,
                               [](NodeParameters& p) -> double& { return p.odometry_config.voxel_size; }));
    t.push_back(switch_parameter("odometry_deskew", "the odometry corrects each sweep by its points' times",
                                 [](NodeParameters& p) -> bool& { return p.odometry_config.deskew; }));
    t.push_back(count_parameter("publish_every", "frames between published maps", 1, 1e6,
                                [](NodeParameters& p, double v) { p.node.publish_every = std::uint32_t(v); },
                                [](const NodeParameters& p) { return double(p.node.publish_every); }));
    t.push_back(real_parameter("voxel", "[m] the published voxel map's voxel; 0: none", 0.0, 1e3, true,
                               [](NodeParameters& p) -> double& { return p.node.voxel; }));
    t.push_back(text_parameter("save_path", "where ~save and save_on_exit write the map", [](NodeParameters& p) -> std::string& { return p.node.save_path; }, false));
    t.push_back(switch_parameter("save_on_exit", "write the map to save_path when the node stops",
                                 [](NodeParameters& p) -> bool& { return p.node.save_on_exit; }));
    return t;
  }();
  return table;
}

}  // namespace

std::string parameter_name(std::string_view field) {
  std::string name(field);
  std::ranges::replace(name, '.', '/');
  return name;
}

NodeParameters read_parameters(const ParameterLookup& lookup, const std::vector<std::string>& given) {
  std::vector<std::string> known;
  for (const ConfigField& f : config_fields()) known.push_back(parameter_name(f.name));
  for (const NodeParameter& p : node_parameters()) known.push_back(p.name);
  for (const std::string& name : given) {
    if (std::ranges::find(known, name) != known.end()) continue;
    const std::string meant = text::nearest_name(name, known);
    throw std::invalid_argument("~" + name + " is not a parameter of eco_node" +
                                (meant.empty() ? std::string() : ": did you mean ~" + meant + "?") +
                                " (eco_node --help lists them)");
  }

  NodeParameters out;
  std::string config_given;
  for (const ConfigField& f : config_fields()) {
    const std::string name = parameter_name(f.name);
    const std::optional<std::string> text = lookup(name);
    if (!text) continue;
    try {
      f.parse(out.config, *text);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("~" + name + " = " + *text + ": " + e.what());
    }
    config_given += (config_given.empty() ? "" : ", ") + ("~" + name + " = " + *text);
  }
  try {
    out.config.validate();
  } catch (const std::invalid_argument& e) {  // a rule between fields: name what was given
    throw std::invalid_argument(std::string(e.what()) + (config_given.empty() ? "" : " (given: " + config_given + ")"));
  }
  for (const NodeParameter& p : node_parameters()) {
    if (const std::optional<std::string> text = lookup(p.name)) p.set(out, *text);
  }
  try {
    out.odometry_config.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("~odometry_max_range, ~odometry_min_range, ~odometry_voxel_size: ") + e.what());
  }
  return out;
}

std::string describe_parameters() {
  std::ostringstream s;
  s << "The map (the eco command's tree configuration, the same names, ranges and defaults):\n";
  for (const ConfigField& f : config_fields()) s << "  ~" << parameter_name(f.name) << "  " << f.summary() << "\n";
  s << "The node:\n";
  const NodeParameters defaults;
  for (const NodeParameter& p : node_parameters()) {
    s << "  ~" << p.name << "  " << p.doc << "; default " << (p.show(defaults).empty() ? "\"\"" : p.show(defaults)) << "\n";
  }
  return s.str();
}

}  // namespace eco::ros_node
