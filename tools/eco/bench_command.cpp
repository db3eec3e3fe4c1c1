// eco bench: every method over the same stream, timed per frame; writes the results folder and
// prints the summary tables.

#include "commands.hpp"
#include "source_flags.hpp"
#include "config_options.hpp"
#include "options_file.hpp"
#include "sim_flags.hpp"

#include "bench/machine.hpp"
#include "bench/progress_bar.hpp"
#include "bench/report.hpp"
#include "bench/runner.hpp"

#include "baselines/method.hpp"

#include <cstdio>
#include <memory>

namespace eco::cli {

Run add_bench(CLI::App& app, const std::string& command_line) {
  auto o = std::make_shared<bench::BenchOptions>();
  auto preset = std::make_shared<std::string>("robot");  // the library's defaults, on raw scans
  CLI::App* cmd = app.add_subcommand("bench", "Compare ECO with its baselines on one stream (the paper's Table II)");
  auto data = std::make_shared<SourceFlags>(*cmd, "the simulator's drive");
  auto workload = std::make_shared<std::string>(bench::to_string(o->workload));
  cmd->add_option("--workload", *workload, "static (aggregated map) or dynamic (raw scans)")
      ->check(CLI::IsMember({"static", "dynamic"}, CLI::ignore_case))
      ->capture_default_str();
  std::string known;
  for (const std::string& n : baselines::method_names()) known += (known.empty() ? "" : ",") + n;
  cmd->add_option("--methods", o->methods, "comma-separated, from: " + known)
      ->delimiter(',')
      ->check(CLI::IsMember(baselines::method_names()))
      ->capture_default_str();
  cmd->add_option("--frames", o->frames, "frames to run (0 = all)")->capture_default_str();
  cmd->add_option("--out", o->out, "results folder, new or empty (default: results/bench-<date>-<time>, new each run)");
  cmd->add_option("--map-resolution", o->map_resolution, "static map voxel [m]")->capture_default_str();
  cmd->add_option("--voxel", o->voxel_resolution, "voxel map resolution [m]")->capture_default_str();
  cmd->add_option("--knn-queries", o->knn_queries, "KNN queries per frame")->capture_default_str();
  cmd->add_option("--k", o->knn_k, "neighbours per query")->capture_default_str();
  cmd->add_option("--seed", o->seed, "query seed, and the simulator's without --data")->capture_default_str();
  cmd->add_option("--sim-frames", o->sim_frames, "length of the simulated drive without --data")->capture_default_str();
  auto motion = std::make_shared<SimFlags>(*cmd, "--sim-", o->sim);
  cmd->add_flag("--check", o->check_every_frame, "check every method's invariants after every frame (slow)");
  auto brief = std::make_shared<bool>(false);
  cmd->add_flag("--brief", *brief, "print one table that fits a terminal (summary.md has them all)");
  cmd->add_flag("--snapshots", o->time_snapshots,
                "then time publishing a snapshot every frame, with a reader thread on it, against a tree alone");
  cmd->add_option("--preset", *preset,
                  "paper (Table II: ShiftInOnly, N_max 8), robot (raw scans: AllInBox, N_max 128, dynamic), "
                  "robot-cap-0.2 (+ 1 point per 0.2 m cell, voxel 0.2), robot-cap-0.1 (+ 2 per 0.1 m, voxel 0.1); "
                  "options given explicitly override it")
      ->check(CLI::IsMember({"paper", "robot", "robot-cap-0.2", "robot-cap-0.1"}))
      ->capture_default_str();
  auto flags = std::make_shared<ConfigFlags>(*cmd, o->config);
  auto file = std::make_shared<OptionsFile>(*cmd, "bench");
  cmd->footer(
      "Defaults are the library's (--preset robot): raw scans, AllInBox, N_max = 128, no density cap, L = 20 m;\n"
      "the paper's Table II is --preset paper (ShiftInOnly, N_max = 8). The settings are printed first. All\n"
      "methods see the same frames, one frame at a time, on one core. The results folder gets config.json\n"
      "(feed it back with --config to repeat the run), <method>.csv, summary.md, summary.json, update_ms.svg.\n"
      "Examples:\n"
      "  eco bench --preset paper --workload static --frames 100 --out results/static\n"
      "  eco bench --preset paper --data ../shared/data/kitti_mini_00 --workload dynamic --out results/kitti00-dynamic\n"
      "  eco bench --methods eco,nanoflann --knn-queries 5000 --k 10\n"
      "  eco bench --data ../shared/data/kitti_mini_08 --preset robot-cap-0.2 --out results/kitti08-robot-cap\n"
      "  eco bench --config results/kitti08-robot-cap/config.json --out results/again");
  return [o, data, workload, preset, brief, cmd, flags, file, command_line, motion] {
    file->load();  // a config.json's values, for the options not given here
    motion->apply(o->sim);
    // the preset first; every option given (on the command line or in the file) then overrides it
    const bench::BenchOptions given = *o;
    bench::apply_preset(*preset, *o);
    if (cmd->count("--workload") > 0) {
      const bool dynamic = CLI::detail::to_lower(*workload) == "dynamic";
      o->workload = dynamic ? bench::WorkloadKind::Dynamic : bench::WorkloadKind::Static;
    }
    if (cmd->count("--voxel") > 0) o->voxel_resolution = given.voxel_resolution;
    // the lattice (and PCL's leaves) at the voxel size every method is asked at, unless given
    if (cmd->count("--voxel_size") == 0) o->config.voxel_size = o->voxel_resolution;
    flags->apply(o->config);
    if (!data->data.empty()) {
      o->data = data->data;
      o->source = data->resolved();
    }
    std::printf("preset %s: %s, %s workload, voxel map at %g m\n", preset->c_str(), describe_settings(o->config).c_str(),
                bench::to_string(o->workload).c_str(), o->voxel_resolution);
    std::fflush(stdout);  // the settings before the progress (on stderr), also into a pipe
    o->out = bench::fresh_results_folder(o->out);  // refused before the run, not after it
    bench::pin_to_one_core();
    const bench::BenchRun run = bench::run_bench(*o, bench::terminal_progress());
    bench::write_results(o->out, run, command_line);
    const std::vector<bench::MethodSummary> summaries = bench::summarize(run);
    std::printf("%s workload, %s\n\n%s\nresults: %s (%.1f s)\n", bench::to_string(o->workload).c_str(),
                run.source.c_str(),
                (*brief ? bench::brief_table(summaries) : bench::summary_tables(run, summaries)).c_str(), o->out.c_str(),
                run.seconds);
    return 0;
  };
}

}  // namespace eco::cli
