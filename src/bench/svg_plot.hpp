#pragma once
// A line chart of update time per frame, one line per method (the paper's Fig. 3), written as
// SVG directly: no plotting package needed to read a results folder.

#include "bench/runner.hpp"

#include <filesystem>

namespace eco::bench {

/// Writes the chart to `path`; throws eco::io::Error if the file cannot be written.
void write_update_plot(const std::filesystem::path& path, const BenchRun& run);

}  // namespace eco::bench
