#pragma once
// eco::Config in config.json: nested like the struct, each field under its name in the field
// table (include/eco/config_fields.hpp), choices by their C++ spelling. The reader goes through the
// same table as the command's flags and Python, so all three accept and refuse the same values.

#include <eco/config.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace eco::bench {

/// {"box_side": 20.0, ..., "density_cap": {"cell_size": 0.0, "max_points": 0}, ...}
[[nodiscard]] nlohmann::json config_to_json(const Config& config);

/// The fields `j` names, as (dotted name, text) pairs in the file's order: "density_cap.cell_size"
/// for {"density_cap": {"cell_size": 0.2}}. Throws io::Error naming `source` and the key for a
/// key that is no field, or a value that is neither a number nor a name.
[[nodiscard]] std::vector<std::pair<std::string, std::string>> config_entries(const nlohmann::json& j,
                                                                            const std::string& source);

/// `base` with every field `j` names set, validated. Throws io::Error naming `source`, the key and
/// the value (an unknown key, a value out of range, fields that do not fit together).
[[nodiscard]] Config config_from_json(const nlohmann::json& j, const std::string& source, Config base = {});

}  // namespace eco::bench
