// The benchmark itself: Chamfer against hand-computed values, summaries against hand-made
// records, and a short simulated run end to end — every method holds the same points every
// frame, and the results folder has every file with every promised field.

#include "support/temp_dir.hpp"

#include "bench/chamfer.hpp"
#include "bench/report.hpp"
#include "bench/runner.hpp"
#include "bench/summary.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace eco::bench {
namespace {

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Chamfer, EqualMapsAreZeroAndAShiftIsItsLength) {
  const std::vector<VoxelKey> a{{0, 0, 0}, {1, 0, 0}, {5, 5, 5}};
  EXPECT_EQ(chamfer_distance(a, a, 0.1), 0.0);
  const std::vector<VoxelKey> shifted{{0, 0, 1}, {1, 0, 1}, {5, 5, 6}};
  EXPECT_NEAR(chamfer_distance(a, shifted, 0.1), 0.1, 1e-12);  // every voxel one voxel away
  // b lacks one voxel of a, 3 voxels from its nearest: a -> b mean 3/3 = 1 voxel, b -> a 0.
  const std::vector<VoxelKey> b{{0, 0, 0}, {1, 0, 0}, {5, 5, 2}};
  EXPECT_NEAR(chamfer_distance(a, b, 1.0), (3.0 / 3.0 + 3.0 / 3.0) / 2.0, 1e-12);
  EXPECT_TRUE(std::isinf(chamfer_distance(a, {}, 0.1)));
}

TEST(Chamfer, ClipKeepsTheVoxelsThatMeetTheBox) {
  const std::vector<VoxelKey> keys{{-1, 0, 0}, {0, 0, 0}, {9, 0, 0}, {10, 0, 0}};
  // box [0, 1) at 0.1 m voxels: voxel -1 spans [-0.1, 0) (misses), 9 spans [0.9, 1) (meets), 10 misses
  const std::vector<VoxelKey> kept = clip_to_box(keys, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 0.1);
  EXPECT_EQ(kept, (std::vector<VoxelKey>{{0, 0, 0}, {9, 0, 0}}));
}

TEST(Summary, MeansSkipTheFirstBuildAndP99IsANearestRank) {
  MethodRun run{"eco", {}, std::nullopt};
  for (int i = 0; i <= 100; ++i) {
    FrameRecord r;
    r.frame = std::size_t(i);
    r.update_ms = i == 0 ? 1000.0 : double(i);  // frame 0 is the build
    r.knn_ms = 2.0;
    r.points = 10;
    r.bytes = 200;
    r.mean_depth = i == 0 ? 4.0 : 5.0;
    r.max_depth = i == 50 ? 9 : 6;
    run.frames.push_back(r);
  }
  const MethodSummary s = summarize(run);
  EXPECT_EQ(s.frames, 101u);
  EXPECT_DOUBLE_EQ(s.first_update_ms, 1000.0);
  EXPECT_DOUBLE_EQ(s.update_ms, 50.5);     // mean of 1..100
  EXPECT_DOUBLE_EQ(s.update_ms_p99, 99.0);  // 99th of 100 sorted
  EXPECT_DOUBLE_EQ(s.knn_ms, 2.0);
  EXPECT_DOUBLE_EQ(s.bytes_per_point, 20.0);
  EXPECT_EQ(s.max_depth, 9);
  EXPECT_DOUBLE_EQ(s.first_depth, 4.0);
  EXPECT_DOUBLE_EQ(s.last_depth, 5.0);
}

class ShortRun : public ::testing::TestWithParam<WorkloadKind> {};

/// The cells of a markdown table row, trimmed.
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::istringstream in(row.substr(1));
  std::string cell;
  while (std::getline(in, cell, '|')) {
    const auto first = cell.find_first_not_of(' ');
    const auto last = cell.find_last_not_of(' ');
    out.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  return out;
}

/// Every markdown table of `md` has as many cells in each row as in its header, and the
/// per-method table's headings stand over the values summary.json gives for them.
void expect_tables_line_up(const std::string& md, const nlohmann::json& summary) {
  std::istringstream lines(md);
  std::string line;
  std::vector<std::vector<std::string>> table;
  int tables = 0, checked_rows = 0, caller_rows = 0, map_rows = 0;
  auto finish = [&] {
    if (table.empty()) return;
    ++tables;
    const std::vector<std::string>& header = table.front();
    for (std::size_t r = 1; r < table.size(); ++r) {
      ASSERT_EQ(table[r].size(), header.size()) << "table " << tables << " row " << r;
    }
    if (header.size() < 2) return;
    if (header[1] == "update faults") {  // what each map costs its caller
      for (std::size_t r = 2; r < table.size(); ++r) {
        const nlohmann::json& m = summary.at("methods").at(table[r][0]);
        EXPECT_NEAR(std::stod(table[r][1]), m.at("update_faults").get<double>(), 0.5 + 1e-9);
        EXPECT_NEAR(std::stod(table[r][2]), m.at("caller_ms").get<double>(), 5e-4 + 1e-9);
        EXPECT_NEAR(std::stod(table[r][3]), m.at("caller_faults").get<double>(), 0.5 + 1e-9);
        ++caller_rows;
      }
      return;
    }
    if (header[1] == "file MB") {  // the map file (the methods that are an EgoOctree)
      for (std::size_t r = 2; r < table.size(); ++r) {
        const nlohmann::json& m = summary.at("methods").at(table[r][0]);
        EXPECT_NEAR(std::stod(table[r][1]), m.at("map_file_bytes").get<double>() / 1e6, 5e-3 + 1e-9);
        EXPECT_NEAR(std::stod(table[r][3]), m.at("map_save_ms").get<double>(), 5e-3 + 1e-9);
        EXPECT_NEAR(std::stod(table[r][4]), m.at("map_load_ms").get<double>(), 5e-3 + 1e-9);
        EXPECT_GT(m.at("map_file_bytes").get<double>(), m.at("map_point_bytes").get<double>());
        ++map_rows;
      }
      return;
    }
    if (header[1] != "first update ms") return;
    auto column = [&](const std::string& heading) {
      const auto at = std::find(header.begin(), header.end(), heading);
      EXPECT_NE(at, header.end()) << heading;
      return std::size_t(at - header.begin());
    };
    for (std::size_t r = 2; r < table.size(); ++r) {  // after the alignment row
      const nlohmann::json& m = summary.at("methods").at(table[r][0]);
      auto expect_cell = [&](const std::string& heading, const char* key, double tolerance) {
        const std::string& cell = table[r][column(heading)];
        if (m.at(key).is_null()) {  // not measured (a query the method does not answer)
          EXPECT_EQ(cell, "–") << heading;
        } else {
          EXPECT_NEAR(std::stod(cell), m.at(key).get<double>(), tolerance) << heading;
        }
      };
      // a cell is its value rounded to the digits shown: within half a unit of the last, and a
      // hair more for the binary fractions on both sides (0.053 against 0.0535 differ by 5e-4 + 4e-19)
      constexpr double kHair = 1e-9;
      expect_cell("update ms", "update_ms", 5e-4 + kHair);
      expect_cell("p99 ms", "update_ms_p99", 5e-4 + kHair);
      expect_cell("voxel ms", "voxel_ms", 5e-4 + kHair);
      expect_cell("KNN ms", "knn_ms", 5e-4 + kHair);
      expect_cell("held points", "points", 0.5 + kHair);
      expect_cell("bytes/point", "bytes_per_point", 0.05 + kHair);
      ++checked_rows;
    }
  };
  while (std::getline(lines, line)) {
    if (line.rfind("|", 0) == 0) {
      table.push_back(cells(line));
    } else {
      finish();
      table.clear();
    }
  }
  finish();
  int trees = 0;  // the methods that are an EgoOctree have a map file
  for (const auto& [name, m] : summary.at("methods").items()) trees += m.contains("map_file_bytes") ? 1 : 0;
  EXPECT_EQ(tables, trees > 0 ? 4 : 3);
  EXPECT_EQ(map_rows, trees);
  EXPECT_EQ(checked_rows, int(summary.at("methods").size()));
  EXPECT_EQ(caller_rows, int(summary.at("methods").size()));
}

/// The chart labels both axes with ticks: frames from 0 by a whole step, ms from 0 upwards (or,
/// on a log axis, from a power of ten).
void expect_ticks_on_both_axes(const std::string& svg, int frames) {
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  for (const std::string axis : {"x", "y"}) {
    SCOPED_TRACE(axis);
    std::vector<double> labels;
    const std::string marker = "class='" + axis + "-tick-label'";
    for (auto at = svg.find(marker); at != std::string::npos; at = svg.find(marker, at + 1)) {
      const auto text = svg.find('>', at) + 1;
      labels.push_back(std::stod(svg.substr(text, svg.find('<', text) - text)));
    }
    std::size_t ticks = 0;
    for (auto at = svg.find("class='" + axis + "-tick'"); at != std::string::npos;
         at = svg.find("class='" + axis + "-tick'", at + 1)) {
      ++ticks;
    }
    ASSERT_GE(labels.size(), 2u);
    EXPECT_EQ(ticks, labels.size());
    const bool log_axis = axis == "y" && svg.find("log scale") != std::string::npos;
    if (log_axis) {  // from a power of ten up, each label 1, 2 or 5 times one
      EXPECT_GT(labels.front(), 0.0);
      for (double v : labels) {
        const double mantissa = v / std::pow(10.0, std::floor(std::log10(v) + 1e-9));
        EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 || std::abs(mantissa - 5) < 1e-6) << v;
      }
    } else {
      EXPECT_EQ(labels.front(), 0.0);
    }
    EXPECT_TRUE(std::is_sorted(labels.begin(), labels.end()));
    if (axis == "x") {
      EXPECT_LE(labels.back(), frames - 1);
      for (double f : labels) EXPECT_EQ(f, std::floor(f));
    }
  }
}

TEST_P(ShortRun, AllMethodsHoldTheSamePointsAndTheResultsFolderIsComplete) {
  BenchOptions o;
  o.workload = GetParam();
  o.sim_frames = 4;
  o.map_resolution = 0.25;  // a small map: the test is about the plumbing
  o.knn_queries = 20;
  o.check_every_frame = true;
  const BenchRun run = run_bench(o);
  const bool dynamic = o.workload == WorkloadKind::Dynamic;
  // the dynamic workload's voxel maps are compared with the current scan's alone (the paper's)
  ASSERT_EQ(run.chamfer_reference, dynamic ? "scan_only" : "octree_base");
  ASSERT_EQ(run.methods.size(), o.methods.size() + (dynamic ? 1 : 0));
  if (dynamic) o.methods.push_back("scan_only");
  const MethodRun* base = nullptr;
  const MethodRun* eco = nullptr;
  for (const MethodRun& m : run.methods) {
    if (m.name == "octree_base") base = &m;
    if (m.name == "eco") eco = &m;
  }
  ASSERT_NE(base, nullptr);
  ASSERT_NE(eco, nullptr);
  for (const MethodRun& m : run.methods) {
    SCOPED_TRACE(m.name);
    ASSERT_EQ(m.frames.size(), 4u);
    for (std::size_t t = 0; t < 4; ++t) {
      EXPECT_GT(m.frames[t].points, 1000u);
      EXPECT_GT(m.frames[t].bytes, 12 * m.frames[t].points);  // at least the coordinates
      if (m.name == "ioctree_global") {
        EXPECT_GE(m.frames[t].points, base->frames[t].points);
      } else if (m.name != "scan_only") {
        EXPECT_EQ(m.frames[t].points, base->frames[t].points) << "frame " << t;
      }
      if (m.name == run.chamfer_reference) {
        EXPECT_EQ(m.frames[t].chamfer_m, 0.0) << "frame " << t;
      } else if (m.name == "pcl_octree") {  // PCL puts points on a voxel wall by its own rounding
        EXPECT_NEAR(m.frames[t].chamfer_m, eco->frames[t].chamfer_m, 1e-4) << "frame " << t;
      } else {
        EXPECT_EQ(m.frames[t].chamfer_m, eco->frames[t].chamfer_m) << "frame " << t;  // same points, same map
      }
    }
  }
  if (dynamic) {
    // The paper's figure: a map that keeps the box (ShiftInOnly here, as Table II) is not the
    // current scan; on the first frame both hold the scan's in-box points.
    EXPECT_EQ(eco->frames[0].chamfer_m, 0.0);
    EXPECT_GT(eco->frames[3].chamfer_m, 0.0);
  } else {
    for (std::size_t t = 0; t < 4; ++t) EXPECT_EQ(eco->frames[t].chamfer_m, 0.0) << "frame " << t;
  }
  test::TempDir dir("eco-bench");
  write_results(dir / "out", run, "eco bench (test)");
  const nlohmann::json summary = nlohmann::json::parse(read(dir / "out/summary.json"));
  for (const std::string& name : o.methods) {
    SCOPED_TRACE(name);
    const nlohmann::json& m = summary.at("methods").at(name);
    for (const char* key : {"update_ms", "voxel_ms", "knn_ms", "update_ms_p99", "mean_depth", "max_depth", "bytes",
                            "points", "chamfer_m"}) {
      EXPECT_TRUE(m.contains(key)) << key;
    }
    std::ifstream csv(dir / ("out/" + name + ".csv"));
    std::string line;
    int lines = 0;
    while (std::getline(csv, line)) ++lines;
    EXPECT_EQ(lines, 5);  // header + 4 frames
  }
  const nlohmann::json config = nlohmann::json::parse(read(dir / "out/config.json"));
  EXPECT_EQ(config.at("config").at("leaf_capacity"), 8);
  EXPECT_EQ(config.at("config").at("insert_policy"), "ShiftInOnly");
  EXPECT_EQ(config.at("bench").at("workload"), to_string(o.workload));
  EXPECT_EQ(config.at("bench").at("methods"), o.methods);
  const std::string md = read(dir / "out/summary.md");
  EXPECT_NE(md.find("| octree_base |"), std::string::npos);
  EXPECT_NE(md.find("Table II"), std::string::npos);
  expect_tables_line_up(md, summary);
  expect_ticks_on_both_axes(read(dir / "out/update_ms.svg"), 4);
}

std::string workload_name(const ::testing::TestParamInfo<WorkloadKind>& param) { return to_string(param.param); }

INSTANTIATE_TEST_SUITE_P(Workloads, ShortRun, ::testing::Values(WorkloadKind::Static, WorkloadKind::Dynamic),
                         workload_name);

TEST(Bench, SummaryStatesClearingsFigureWhenEcoClearingRan) {
  BenchRun run;
  MethodSummary eco{.name = "eco", .frames = 3, .update_ms = 2.0, .chamfer_m = 0.125};
  MethodSummary clearing{.name = "eco_clearing", .frames = 3, .update_ms = 3.5, .chamfer_m = 0.0625};
  EXPECT_EQ(summary_tables(run, {eco}).find("Free-space clearing"), std::string::npos);
  const std::string md = summary_tables(run, {eco, clearing});
  EXPECT_NE(md.find("Free-space clearing: eco_clearing update / eco 1.75×, Chamfer 0.0625 m against eco's 0.1250 m."),
            std::string::npos)
      << md;
}

/// --snapshots times a publishing tree against a tree alone on the run's own frames, and the page
/// and summary.json say what it measured: the reader ran, and the ratios are the means' ratios.
TEST(Bench, SnapshotTimingRunsOnTheSameFramesAndIsReported) {
  BenchOptions o;
  o.methods = {"eco"};
  o.sim_frames = 3;  // each frame runs three trees and a reader: what is reported is the same with more
  o.knn_queries = 50;
  o.config.insert_policy = InsertPolicy::AllInBox;
  o.time_snapshots = true;
  const BenchRun run = run_bench(o);
  ASSERT_TRUE(run.snapshots.has_value());
  const SnapshotTiming& t = *run.snapshots;
  EXPECT_EQ(t.frames, 2u);  // the first frame left out
  EXPECT_GT(t.reader_queries, 0u);
  for (const double v :
       {t.update_alone_ms, t.update_read_ms, t.update_beside_ms, t.publish_ms, t.knn_live_ms, t.knn_snapshot_ms}) {
    EXPECT_GT(v, 0.0);
  }
  EXPECT_GT(t.bytes_with_snapshot, t.bytes_alone) << "a snapshot a frame behind holds the pages changed since";
  const std::vector<MethodSummary> summaries = summarize(run);
  const std::string md = summary_tables(run, summaries);
  std::ostringstream publish;
  publish << std::fixed << std::setprecision(3) << t.publish_ms / t.update_alone_ms << "×";
  EXPECT_NE(md.find("| " + publish.str() + " |"), std::string::npos) << md;
  test::TempDir dir("eco-bench-snapshots");
  write_results(dir.path(), run, "eco bench --snapshots");
  const auto json = nlohmann::json::parse(std::ifstream(dir.path() / "summary.json"));
  EXPECT_EQ(json.at("snapshots").at("frames").get<std::size_t>(), 2u);
  EXPECT_DOUBLE_EQ(json.at("snapshots").at("knn_snapshot_ms").get<double>(), t.knn_snapshot_ms);
}

TEST(Bench, BadOptionsAreRejectedByName) {
  BenchOptions o;
  o.methods = {"eco", "octree"};
  try {
    (void)run_bench(o);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'octree'"), std::string::npos);
  }
  o.methods = {"eco"};
  o.config.leaf_capacity = 0;
  EXPECT_THROW((void)run_bench(o), std::invalid_argument);
}

}  // namespace
}  // namespace eco::bench
