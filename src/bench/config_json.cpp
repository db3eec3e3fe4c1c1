#include "bench/config_json.hpp"

#include <eco/config_fields.hpp>
#include <eco/io/error.hpp>

#include <stdexcept>

namespace eco::bench {

nlohmann::json config_to_json(const Config& config) {
  nlohmann::json out = nlohmann::json::object();
  for (const ConfigField& f : config_fields()) {
    nlohmann::json value;
    if (f.kind == ConfigField::Kind::Choice) {
      value = f.format(config);
    } else if (f.kind == ConfigField::Kind::Switch) {
      value = f.get(config) != 0.0;
    } else if (f.kind == ConfigField::Kind::Count) {
      value = static_cast<std::uint64_t>(f.get(config));
    } else {
      value = f.get(config);
    }
    const std::size_t dot = f.name.find('.');  // a nested field: its struct's object
    if (dot == std::string_view::npos) {
      out[std::string(f.name)] = value;
    } else {
      out[std::string(f.name.substr(0, dot))][std::string(f.name.substr(dot + 1))] = value;
    }
  }
  return out;
}

namespace {

void collect(const nlohmann::json& j, const std::string& prefix, const std::string& source,
             std::vector<std::pair<std::string, std::string>>& out) {
  if (!j.is_object()) throw io::Error(source, "", "\"config\" must be an object of Config's fields");
  for (const auto& [key, value] : j.items()) {
    const std::string name = prefix + key;
    if (value.is_object()) {
      collect(value, name + ".", source, out);
      continue;
    }
    try {
      (void)config_field(name);
    } catch (const std::invalid_argument& e) {
      throw io::Error(source, "", std::string("unknown key: ") + e.what());
    }
    if (value.is_number()) {
      out.emplace_back(name, value.dump());
    } else if (value.is_string()) {
      out.emplace_back(name, value.get<std::string>());
    } else if (value.is_boolean()) {  // a switch's; any other field refuses the text
      out.emplace_back(name, value.get<bool>() ? "true" : "false");
    } else {
      throw io::Error(source, "", "config key " + name + " = " + value.dump() + " must be a number or a name");
    }
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> config_entries(const nlohmann::json& j, const std::string& source) {
  std::vector<std::pair<std::string, std::string>> out;
  collect(j, "", source, out);
  return out;
}

Config config_from_json(const nlohmann::json& j, const std::string& source, Config base) {
  try {
    for (const auto& [name, text] : config_entries(j, source)) config_field(name).parse(base, text);
    base.validate();
  } catch (const std::invalid_argument& e) {
    throw io::Error(source, "", e.what());
  }
  return base;
}

}  // namespace eco::bench
