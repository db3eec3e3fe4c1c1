#include "options_file.hpp"

#include "bench/config_json.hpp"
#include "bench/machine.hpp"

#include <eco/config_fields.hpp>
#include <eco/io/error.hpp>
#include <eco/version.hpp>

#include <ctime>
#include <fstream>
#include <set>
#include <sstream>

namespace eco::cli {
namespace {

/// A JSON value as the command line would give it: numbers and names as text, a list item by item.
std::vector<std::string> as_arguments(const nlohmann::json& value) {
  if (value.is_array()) {
    std::vector<std::string> out;
    for (const nlohmann::json& item : value) {
      const std::vector<std::string> one = as_arguments(item);
      out.insert(out.end(), one.begin(), one.end());
    }
    return out;
  }
  if (value.is_string()) return {value.get<std::string>()};
  return {value.dump()};  // numbers, true, false
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io::Error(path, "", "cannot open the configuration file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw io::Error(path, "", std::string("not valid JSON: ") + e.what());
  }
}

}  // namespace

OptionsFile::OptionsFile(CLI::App& cmd, std::string command) : cmd_(&cmd), command_(std::move(command)) {
  cmd.add_option("--config", path_,
                 "a config.json (as every command writes): its values are taken for the options not given")
      ->check(CLI::ExistingFile);
}

void OptionsFile::load() const {
  if (path_.empty()) return;
  const nlohmann::json file = read_json(path_);
  if (!file.is_object()) throw io::Error(path_, "", "must hold a JSON object");
  const std::set<std::string> informational{"version", "command_line", "date", "machine", "result"};
  const std::set<std::string> commands{"bench", "run", "simulate"};
  auto feed = [&](const std::string& key, const nlohmann::json& value) {
    CLI::Option* option = cmd_->get_option_no_throw("--" + key);
    if (option == nullptr || key == "config") {
      throw io::Error(path_, "", "unknown key " + command_ + "." + key + " (not an option of eco " + command_ + ")");
    }
    if (option->count() > 0) return;  // given on the command line: it wins
    try {
      for (const std::string& argument : as_arguments(value)) option->add_result(argument);
      option->run_callback();
    } catch (const CLI::Error& e) {
      throw io::Error(path_, "", command_ + "." + key + " = " + value.dump() + ": " + e.what());
    }
  };
  for (const auto& [key, value] : file.items()) {
    if (informational.count(key) > 0) continue;
    if (key == "config") {
      Config scratch;  // each value checked here, so that the error names the file
      for (const auto& [name, text] : bench::config_entries(value, path_)) {
        try {
          config_field(name).parse(scratch, text);
        } catch (const std::invalid_argument& e) {
          throw io::Error(path_, "", e.what());
        }
        feed(name, text);
      }
    } else if (key == command_) {
      if (!value.is_object()) throw io::Error(path_, "", "\"" + key + "\" must be an object of options");
      for (const auto& [option, option_value] : value.items()) feed(option, option_value);
    } else if (commands.count(key) == 0) {
      throw io::Error(path_, "", "unknown key " + key);
    }
  }
}

void write_options_file(const std::filesystem::path& folder, const std::string& command,
                        const std::string& command_line, const nlohmann::json& options, const Config* config) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw io::Error(folder.string(), "", "cannot create the folder: " + error.message());
  nlohmann::json out{{"version", kVersion}, {"command_line", command_line}, {"machine", bench::describe_machine()},
                     {command, options}};
  if (config) out["config"] = bench::config_to_json(*config);
  const std::filesystem::path path = folder / "config.json";
  std::ofstream file(path);
  file << out.dump(2) << "\n";
  if (!file) throw io::Error(path.string(), "", "cannot write the configuration");
}

}  // namespace eco::cli
