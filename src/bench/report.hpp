#pragma once
// The results folder of a benchmark run:
//   config.json    what reproduces the run: the resolved options under "bench" (keyed by the flags
//                  of `eco bench`), the tree's Config under "config", version, command line, machine,
//                  and what the run found under "result"; `eco bench --config` reads it back
//   <method>.csv   one row per frame
//   summary.md     a table shaped like the paper's Table II, then depth, memory and ratios to ECO
//   summary.json   per method: update_ms, voxel_ms, knn_ms (means), update_ms_p99, mean_depth,
//                  max_depth, bytes, points, chamfer_m, and more
//   update_ms.svg  update time per frame per method (the paper's Fig. 3)

#include "bench/runner.hpp"
#include "bench/summary.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace eco::bench {

/// The folder a run's results go to, holding nothing of an earlier run's: `given`, new or empty
/// (or holding other files), or without it results/bench-<UTC date>-<time> (-2, -3, ... when that
/// is taken). Throws eco::io::Error when `given` holds an earlier run's config.json or summary.md,
/// before the run rather than after it.
[[nodiscard]] std::filesystem::path fresh_results_folder(const std::filesystem::path& given);

/// Creates `folder` (and parents) and writes every file above. Throws eco::io::Error naming the
/// file that could not be written.
void write_results(const std::filesystem::path& folder, const BenchRun& run, const std::string& command_line);

/// The options of a run keyed by `eco bench`'s flags (without --out, --preset, --config).
nlohmann::json bench_options_json(const BenchOptions& options);
/// How --data is read (--start, --poses, --topic, --pose-topic, ...), keyed by flag: the options
/// given, the defaults left out.
nlohmann::json source_options_json(const workloads::SourceOptions& options);

/// The Markdown tables of summary.md (without its heading), for the terminal as well.
std::string summary_tables(const BenchRun& run, const std::vector<MethodSummary>& summaries);
/// The run in a table that fits a terminal: each method's update, voxel map and KNN, and each
/// over ECO's.
std::string brief_table(const std::vector<MethodSummary>& summaries);

}  // namespace eco::bench
