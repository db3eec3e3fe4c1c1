#pragma once
// eco_node's parameters: the tree's configuration through the one field table (each Config field
// a private parameter of the same name, a dotted one's dots as slashes: ~density_cap/cell_size),
// then the node's own. Read through a lookup, so that the rules are tested without a roscore.

#include "node_settings.hpp"

#include <eco/config.hpp>
#include <eco/io/point_cloud2.hpp>
#include <eco/odometry/odometry.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace eco::ros_node {

struct NodeParameters {
  Config config;                 ///< the map's
  io::TimeOptions time;          ///< the clouds' per-point times (field, unit)
  odometry::OdometryConfig odometry_config;  ///< with node.odometry
  NodeSettings node;
};

/// A parameter's value as text (a number, true/false, or a string), or nullopt when it is not set.
using ParameterLookup = std::function<std::optional<std::string>(const std::string& name)>;

/// The node's parameters from `lookup` (names without the leading ~); `given` lists every private
/// parameter set, to refuse those the node does not know. Throws std::invalid_argument naming the
/// parameter (as ~name) and its value.
[[nodiscard]] NodeParameters read_parameters(const ParameterLookup& lookup, const std::vector<std::string>& given);

/// The parameters with their ranges and defaults, a line each, for `eco_node --help`.
[[nodiscard]] std::string describe_parameters();

/// A Config field's parameter name: "density_cap.cell_size" -> "density_cap/cell_size".
[[nodiscard]] std::string parameter_name(std::string_view field);

}  // namespace eco::ros_node
