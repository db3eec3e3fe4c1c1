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

#include <cmath>
#include <fstream>
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
  MethodRun run{"eco", {}};
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

TEST_P(ShortRun, AllMethodsHoldTheSamePointsAndTheResultsFolderIsComplete) {
  BenchOptions o;
  o.workload = GetParam();
  o.sim_frames = 4;
  o.map_resolution = 0.25;  // a small map: the test is about the plumbing
  o.knn_queries = 20;
  o.check_every_frame = true;
  const BenchRun run = run_bench(o);
  ASSERT_EQ(run.methods.size(), o.methods.size());
  const MethodRun* base = nullptr;
  for (const MethodRun& m : run.methods) {
    if (m.name == "octree_base") base = &m;
  }
  ASSERT_NE(base, nullptr);
  for (const MethodRun& m : run.methods) {
    SCOPED_TRACE(m.name);
    ASSERT_EQ(m.frames.size(), 4u);
    for (std::size_t t = 0; t < 4; ++t) {
      EXPECT_GT(m.frames[t].points, 1000u);
      EXPECT_GT(m.frames[t].bytes, 12 * m.frames[t].points);  // at least the coordinates
      if (m.name == "ioctree_global") {
        EXPECT_GE(m.frames[t].points, base->frames[t].points);
      } else {
        EXPECT_EQ(m.frames[t].points, base->frames[t].points) << "frame " << t;
      }
      if (m.name == "pcl_octree") {  // PCL puts points on a voxel wall by its own rounding
        EXPECT_LT(m.frames[t].chamfer_m, 1e-4) << "frame " << t;
      } else {
        EXPECT_EQ(m.frames[t].chamfer_m, 0.0) << "frame " << t;  // same points, same voxel map
      }
    }
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
  EXPECT_EQ(config.at("workload"), to_string(o.workload));
  const std::string md = read(dir / "out/summary.md");
  EXPECT_NE(md.find("| octree_base |"), std::string::npos);
  EXPECT_NE(md.find("Table II"), std::string::npos);
  EXPECT_EQ(read(dir / "out/update_ms.svg").rfind("<svg", 0), 0u);
}

std::string workload_name(const ::testing::TestParamInfo<WorkloadKind>& param) { return to_string(param.param); }

INSTANTIATE_TEST_SUITE_P(Workloads, ShortRun, ::testing::Values(WorkloadKind::Static, WorkloadKind::Dynamic),
                         workload_name);

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
