// eco — the command-line tool: simulate a drive, benchmark ECO against its baselines, or stream
// a sequence through ECO, run a LiDAR odometry on it, or look at a run in a web browser.

#include "commands.hpp"
#include "spellings.hpp"

#include <eco/process_heap.hpp>
#include <eco/version.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  eco::keep_freed_heap();  // every command is a frame loop: what a frame frees, the next reuses
  std::string command_line = "eco";
  for (int i = 1; i < argc; ++i) command_line += std::string(" ") + argv[i];
  CLI::App app{"ECO: an ego-centric octree for LiDAR streams (version " + std::string(eco::kVersion) + ")", "eco"};
  app.require_subcommand(1);
  app.set_version_flag("--version", eco::kVersion);
  app.footer(
      "Examples:\n"
      "  eco simulate --out data/sim --frames 300 --seed 1     write a synthetic KITTI-layout drive\n"
      "  eco bench --preset paper --workload static --frames 100 --out results/static\n"
      "                                                        all methods on the simulator's default drive\n"
      "  eco bench --data data/sim --methods eco,octree_base,nanoflann --out results/robot\n"
      "  eco run --data ../shared/data/kitti_mini_00 --export-every 5 --out results/run00\n"
      "  eco odometry --frames 200 --map all                  a LiDAR odometry on five maps, same frames\n"
      "  eco run --frames 60 --record --out results/run && eco view results/run\n"
      "                                                        the run in a web browser, frame by frame\n"
      "Run 'eco <command> --help' for each command's options.");
  const eco::cli::Run simulate = eco::cli::add_simulate(app, command_line);
  const eco::cli::Run bench = eco::cli::add_bench(app, command_line);
  const eco::cli::Run run = eco::cli::add_run(app, command_line);
  const eco::cli::Run odometry = eco::cli::add_odometry(app, command_line);
  const eco::cli::Run view = eco::cli::add_view(app, command_line);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    std::fputs(eco::cli::did_you_mean(app).c_str(), stderr);
    return code;
  }
  try {
    if (app.got_subcommand("simulate")) return simulate();
    if (app.got_subcommand("bench")) return bench();
    if (app.got_subcommand("odometry")) return odometry();
    if (app.got_subcommand("view")) return view();
    return run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "eco: %s\n", e.what());
    return 1;
  }
}
