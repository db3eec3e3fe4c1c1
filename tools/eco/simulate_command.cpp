// eco simulate: writes a synthetic drive (eco::sim) in KITTI's layout.

#include "commands.hpp"
#include "spellings.hpp"
#include "options_file.hpp"
#include "sim_flags.hpp"

#include <eco/sim/simulator.hpp>

#include <chrono>
#include <cstdio>
#include <memory>

namespace eco::cli {

Run add_simulate(CLI::App& app, const std::string& command_line) {
  auto options = std::make_shared<sim::SimConfig>();
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("simulate", "Write a synthetic LiDAR drive (HDL-64E-like, 10 Hz) in KITTI's layout");
  cmd->add_option("--out", *out, "folder to write (velodyne/, labels/, poses.txt, calib.txt, times.txt)")->required();
  cmd->add_option("--frames", options->frames, "scans to write")->capture_default_str();
  cmd->add_option("--seed", options->seed, "city and noise seed: the same seed gives the same bytes")->capture_default_str();
  cmd->add_option("--beams", options->lidar.beams, "the LiDAR's beams (fewer: a lighter drive)")->capture_default_str();
  cmd->add_option("--columns", options->lidar.columns, "its columns over 360 degrees")->capture_default_str();
  auto motion = std::make_shared<SimFlags>(*cmd, "--", *options);
  cmd->add_option(both_spellings("--rolling-sweep"), options->lidar.rolling_sweep,
                  "fire the columns over the frame (a moving sensor's smear; times.txt stays per frame)")
      ->capture_default_str();
  auto file = std::make_shared<OptionsFile>(*cmd, "simulate");
  cmd->footer("The folder also gets config.json (feed it back with --config to write the same drive).\n"
              "Example:\n  eco simulate --out data/sim --frames 300 --seed 1");
  return [options, out, file, command_line, motion] {
    file->load();
    motion->apply(*options);
    const auto start = std::chrono::steady_clock::now();
    const sim::Simulator simulator(*options);
    simulator.write_kitti(*out);
    nlohmann::json given{{"frames", options->frames}, {"seed", options->seed}, {"beams", options->lidar.beams},
                         {"columns", options->lidar.columns}, {"rolling-sweep", options->lidar.rolling_sweep}};
    motion->add_to(given, "--", *options);
    write_options_file(*out, "simulate", command_line, given, nullptr);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("wrote %zu frames (seed %llu) to %s in %.1f s\n", simulator.size(),
                static_cast<unsigned long long>(options->seed), out->c_str(), seconds);
    return 0;
  };
}

}  // namespace eco::cli
