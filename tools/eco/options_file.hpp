#pragma once
// --config FILE.json on every command, and the config.json every command writes: what reproduces
// a run. A file holds the command's options under its name ("bench", "run", "simulate"), keyed by
// the flags without their dashes, and the tree's Config under "config" (src/bench/config_json.hpp);
// "version", "command_line", "date", "machine" and "result" are informational.

#include <eco/config.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace eco::cli {

class OptionsFile {
 public:
  /// Adds --config to `cmd`, the subcommand called `command`.
  OptionsFile(CLI::App& cmd, std::string command);

  /// After parsing, if --config was given: the file's values for the options not given on the
  /// command line are taken as if they had been (flags given override the file). Sections of other
  /// commands are ignored, so one command's file can seed another's Config. Throws io::Error
  /// naming the file, the key and the value for an unknown key or a bad value.
  void load() const;

 private:
  CLI::App* cmd_;
  std::string command_;
  std::string path_;
};

/// Writes `folder`/config.json for `command`: version, command line, date, `options` (keyed by
/// flag) under the command's name and, if given, the tree's `config`. Creates `folder`.
void write_options_file(const std::filesystem::path& folder, const std::string& command,
                        const std::string& command_line, const nlohmann::json& options, const Config* config);

}  // namespace eco::cli
