#pragma once
// --data and how it is read, the same on eco run, odometry and bench: --poses, --topic,
// --time-field and --time-unit (eco/workloads/scan_source.hpp says what --data may name).

#include <eco/workloads/scan_source.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace eco::cli {

struct SourceFlags {
  std::string data;
  workloads::SourceOptions options;
  std::string time_unit = "auto";

  /// Adds the flags to `cmd`; `without_data` says what runs when --data is not given.
  SourceFlags(CLI::App& cmd, const std::string& without_data);

  /// The options with --time-unit applied.
  [[nodiscard]] workloads::SourceOptions resolved() const;
  /// Opens --data (which must be given) from --start on, its warnings printed on stderr.
  [[nodiscard]] workloads::OpenedSource open() const;
  /// `frames` from --start on (the simulator's drive, which is made without --data).
  [[nodiscard]] std::unique_ptr<workloads::Workload> from_start(std::unique_ptr<workloads::Workload> frames) const;
  /// The flags given, keyed as config.json keys options (paths made absolute).
  void add_to(nlohmann::json& options) const;
};

}  // namespace eco::cli
