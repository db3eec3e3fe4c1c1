#pragma once
// The subcommands of `eco`, each in its own file: it adds its options to the app and returns
// the function that runs it once the command line is parsed.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace eco::cli {

using Run = std::function<int()>;

Run add_simulate(CLI::App& app, const std::string& command_line);
Run add_bench(CLI::App& app, const std::string& command_line);
Run add_run(CLI::App& app, const std::string& command_line);
Run add_odometry(CLI::App& app, const std::string& command_line);
Run add_view(CLI::App& app, const std::string& command_line);

}  // namespace eco::cli
