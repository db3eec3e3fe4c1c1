// eco bench: every method over the same stream, timed per frame; writes the results folder and
// prints the summary tables.

#include "commands.hpp"
#include "config_options.hpp"

#include "bench/machine.hpp"
#include "bench/progress_bar.hpp"
#include "bench/report.hpp"
#include "bench/runner.hpp"

#include <eco/baselines/method.hpp>

#include <cstdio>
#include <memory>

namespace eco::cli {

Run add_bench(CLI::App& app, const std::string& command_line) {
  auto o = std::make_shared<bench::BenchOptions>();
  auto data = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("bench", "Compare ECO with its baselines on one stream (the paper's Table II)");
  cmd->add_option("--data", *data, "KITTI-layout folder (velodyne/, poses.txt[, calib.txt]); default: simulate")
      ->check(CLI::ExistingDirectory);
  const std::map<std::string, bench::WorkloadKind> kinds{{"static", bench::WorkloadKind::Static},
                                                         {"dynamic", bench::WorkloadKind::Dynamic}};
  cmd->add_option("--workload", o->workload, "static (aggregated map) or dynamic (raw scans)")
      ->transform(CLI::CheckedTransformer(kinds, CLI::ignore_case))
      ->capture_default_str();
  std::string known;
  for (const std::string& n : baselines::method_names()) known += (known.empty() ? "" : ",") + n;
  cmd->add_option("--methods", o->methods, "comma-separated, from: " + known)
      ->delimiter(',')
      ->check(CLI::IsMember(baselines::method_names()))
      ->capture_default_str();
  cmd->add_option("--frames", o->frames, "frames to run (0 = all)")->capture_default_str();
  cmd->add_option("--out", o->out, "results folder")->capture_default_str();
  cmd->add_option("--map-resolution", o->map_resolution, "static map voxel [m]")->capture_default_str();
  cmd->add_option("--voxel", o->voxel_resolution, "voxel map resolution [m]")->capture_default_str();
  cmd->add_option("--knn-queries", o->knn_queries, "KNN queries per frame")->capture_default_str();
  cmd->add_option("--k", o->knn_k, "neighbours per query")->capture_default_str();
  cmd->add_option("--seed", o->seed, "query seed, and the simulator's without --data")->capture_default_str();
  cmd->add_option("--sim-frames", o->sim_frames, "length of the simulated drive without --data")->capture_default_str();
  cmd->add_flag("--check", o->check_every_frame, "check every method's invariants after every frame (slow)");
  add_config_options(*cmd, o->config);
  cmd->footer(
      "Defaults are the paper's: L = 20 m, N_max = 8, ShiftInOnly. All methods see the same frames, one\n"
      "frame at a time, on one core. The results folder gets config.json, <method>.csv, summary.md,\n"
      "summary.json and update_ms.svg.\n"
      "Examples:\n"
      "  eco bench --workload static --frames 100 --out results/static\n"
      "  eco bench --data ../shared/data/kitti_mini_00 --workload dynamic --out results/kitti00-dynamic\n"
      "  eco bench --workload dynamic --methods eco,nanoflann --knn-queries 5000 --k 10");
  return [o, data, command_line] {
    if (!data->empty()) o->data = *data;
    bench::pin_to_one_core();
    const bench::BenchRun run = bench::run_bench(*o, bench::terminal_progress());
    bench::write_results(o->out, run, command_line);
    std::printf("%s workload, %s\n\n%s\nresults: %s (%.1f s)\n", bench::to_string(o->workload).c_str(),
                run.source.c_str(), bench::summary_tables(run, bench::summarize(run)).c_str(), o->out.c_str(),
                run.seconds);
    return 0;
  };
}

}  // namespace eco::cli
