// The recorder against the tree's own counts: on a simulated street with free-space clearing, what
// it finds inserted, dropped and cleared each frame is what the update reported; every held point's
// age is the frames since its scan (the scan's frame rides in its id); dropped points lie outside
// the new box and cleared ones inside; the table of births agrees with std::map; frames.csv reads
// back what was written, and a damaged line is named.

#include "view/recorder.hpp"
#include "view/run_index.hpp"

#include "support/temp_dir.hpp"

#include <eco/ego_octree.hpp>
#include <eco/sim/simulator.hpp>

#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <map>
#include <random>

namespace eco::view {
namespace {

constexpr std::uint32_t kIdsAFrame = 1000000;

TEST(Recorder, FindsWhatTheUpdateInsertedDroppedAndCleared) {
  sim::SimConfig drive;
  drive.frames = 10;
  drive.speed = 40.0;  // 4 m a frame: points leave the box every frame
  drive.city.cars_per_intersection = 5.0;  // cars that move on, leaving space the scans see free
  drive.lidar.beams = 16;
  drive.lidar.columns = 600;
  Config config;
  config.clearing.enabled = true;
  config.sensor.vertical_resolution = 1.7;  // the 16 beams' spacing
  config.sensor.horizontal_resolution = 1.2;
  config.attributes.ids = true;
  EgoOctree tree(config);
  const sim::Simulator simulator(drive);
  test::TempDir dir;
  Recorder recorder((dir / "view").string(), {"street", config.box_side, 0.5, drive.frames});
  std::size_t dropped = 0, cleared = 0;
  std::vector<FrameFigures> figures;
  for (std::uint32_t t = 0; t < drive.frames; ++t) {
    const sim::SimFrame frame = simulator.frame(t);
    std::vector<std::uint32_t> ids(frame.cloud.points.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = t * kIdsAFrame + std::uint32_t(i);
    ScanView scan(frame.cloud.points);
    scan.ids = ids.data();
    const UpdateStats& u = tree.update(frame.world_T_lidar, scan);
    figures.push_back({u.scan_points, u.inserted, u.pruned, u.cleared, tree.size(), 1.5, {}});
    const FrameChanges found = recorder.record(t, tree.pose(), tree.points_with_attributes(), tree.voxel_keys(0.5),
                                               figures.back());
    ASSERT_EQ(found.inserted, u.inserted) << "frame " << t;
    // every point gone is found, as dropped (outside the new box) or cleared (inside it); the
    // tree counts as cleared the arrivals it lets go before its box moves, some of which the
    // move would have dropped too
    ASSERT_EQ(found.dropped + found.cleared, u.pruned + u.cleared + u.aged_out) << "frame " << t;
    ASSERT_GE(found.dropped, u.pruned) << "frame " << t;
    dropped += found.dropped;
    cleared += found.cleared;

    const FrameRecord r = read_frame_file((dir / "view" / frame_file_name(t)).string());
    ASSERT_EQ(r.held.size(), tree.size());
    ASSERT_EQ(r.id.size(), tree.size());
    for (std::size_t i = 0; i < r.held.size(); ++i) {
      ASSERT_EQ(r.age[i], t - r.id[i] / kIdsAFrame) << "frame " << t << ", point " << i;
    }
    const float half = float(config.box_side / 2);
    for (const Eigen::Vector3f& p : r.dropped) EXPECT_GE(p.cwiseAbs().maxCoeff(), half - 1e-3f);
    for (const Eigen::Vector3f& p : r.cleared) EXPECT_LT(p.cwiseAbs().maxCoeff(), half + 1e-3f);
    EXPECT_EQ(r.voxels, tree.voxel_keys(0.5));
  }
  EXPECT_GT(dropped, 1000u);  // the drive makes both happen
  EXPECT_GT(cleared, 0u);

  const Index index = read_index((dir / "view" / kIndexFile).string());
  EXPECT_EQ(index.error, "");
  ASSERT_EQ(index.rows.size(), drive.frames);
  for (std::uint32_t t = 0; t < drive.frames; ++t) {
    EXPECT_EQ(index.rows[t].frame, t);
    EXPECT_LT((index.rows[t].sensor - simulator.pose(t).translation()).norm(), 1e-5);
    EXPECT_FALSE(index.rows[t].reference);
    EXPECT_EQ(index.rows[t].figures.held, figures[t].held);
    EXPECT_EQ(index.rows[t].figures.inserted, figures[t].inserted);
    EXPECT_EQ(index.rows[t].figures.pruned, figures[t].pruned);
    EXPECT_EQ(index.rows[t].figures.cleared, figures[t].cleared);
    EXPECT_EQ(index.rows[t].figures.update_ms, 1.5);
  }
}

TEST(Recorder, CountsItselfForAMapThatDoesNot) {
  test::TempDir dir;
  RunInfo info{"odometry", 20.0, 1.0, 0, true, false};
  Recorder recorder(dir.path().string(), info);
  const auto held = [](std::initializer_list<Eigen::Vector3d> points) {
    std::vector<HeldPoint> out;
    for (const Eigen::Vector3d& p : points) out.push_back({p, {}});
    return out;
  };
  const Eigen::Isometry3d at0 = Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d at5(Eigen::Translation3d(5, 0, 0));
  const std::vector<HeldPoint> first = held({{-9, 0, 0}, {1, 1, 1}, {1, 1, 1}, {2, 0, 0}});
  recorder.record(0, at0, first, occupied_voxels(first, 1.0), {100, 0, 0, 0, 4, 0.5, {}}, Eigen::Vector3d(0, 0, 0.1));
  // (-9, 0, 0) leaves the box around x = 5; one of the twin points and (2, 0, 0) go inside it
  const std::vector<HeldPoint> second = held({{1, 1, 1}, {7, 0, 0}});
  const FrameChanges c = recorder.record(1, at5, second, occupied_voxels(second, 1.0), {100, 0, 0, 0, 2, 0.5, {}},
                                         Eigen::Vector3d(5, 0, 0.1));
  EXPECT_EQ(c.inserted, 1u);
  EXPECT_EQ(c.dropped, 1u);
  EXPECT_EQ(c.cleared, 2u);
  const FrameRecord r = read_frame_file((dir / frame_file_name(1)).string());
  EXPECT_EQ(r.age, (std::vector<std::uint16_t>{1, 0}));
  EXPECT_EQ(r.voxels.size(), 2u);
  const Index index = read_index((dir / kIndexFile).string());
  ASSERT_EQ(index.rows.size(), 2u);
  EXPECT_EQ(index.rows[1].figures.inserted, 1u);
  EXPECT_EQ(index.rows[1].figures.pruned, 1u);
  EXPECT_EQ(index.rows[1].figures.cleared, 2u);
  ASSERT_TRUE(index.rows[1].reference);
  EXPECT_EQ(*index.rows[1].reference, Eigen::Vector3d(5, 0, 0.1));
}

TEST(Recorder, GoesOnFromAMapItDidNotRecord) {
  test::TempDir dir;
  Recorder recorder(dir.path().string(), {"loaded", 20.0, 1.0});
  const std::vector<HeldPoint> loaded{{{1, 0, 0}, {}}, {{2, 0, 0}, {}}};
  recorder.carry(49, loaded);
  std::vector<HeldPoint> next = loaded;
  next.push_back({{3, 0, 0}, {}});
  const FrameChanges c = recorder.record(50, Eigen::Isometry3d::Identity(), next, {}, {});
  EXPECT_EQ(c.inserted, 1u);
  EXPECT_EQ(read_frame_file((dir / frame_file_name(50)).string()).age, (std::vector<std::uint16_t>{1, 1, 0}));
  EXPECT_FALSE(std::filesystem::exists(dir / frame_file_name(49)));
}

TEST(BirthTable, KeepsWhatAMapWouldThroughGrowthAndDeletions) {
  // against std::map over 40 frames of random positions on a coarse grid (so that many repeat),
  // each frame keeping a random half of the last one's and adding new ones
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> cell(-40, 40);
  using Key = std::array<double, 3>;
  std::map<Key, std::pair<std::uint32_t, int>> oracle;  // birth frame, points held before
  BirthTable table;
  std::vector<Key> held;
  for (std::uint32_t frame = 0; frame < 40; ++frame) {
    std::vector<Key> now;
    for (const Key& k : held) {
      if (rng() % 2) now.push_back(k);
    }
    for (int i = 0; i < 3000; ++i) now.push_back({cell(rng) * 0.25, cell(rng) * 0.25, cell(rng) * 0.25});
    std::map<Key, int> counts;
    for (const Key& k : now) {
      BirthTable::Entry& e = table.at(Eigen::Vector3d(k[0], k[1], k[2]), frame);
      ++e.now;
      ++counts[k];
      const auto known = oracle.find(k);
      ASSERT_EQ(e.frame, known == oracle.end() ? frame : known->second.first);
      ASSERT_EQ(e.before, known == oracle.end() ? 0 : known->second.second);
    }
    std::size_t visited = 0;
    table.end_frame([&](const BirthTable::Entry& e) {
      ++visited;
      const Key k{e.x, e.y, e.z};
      ASSERT_EQ(e.now, counts.count(k) ? counts[k] : 0);
    });
    EXPECT_EQ(visited, oracle.size() + std::count_if(counts.begin(), counts.end(), [&](const auto& c) {
                         return !oracle.count(c.first);
                       }));
    std::map<Key, std::pair<std::uint32_t, int>> next;
    for (const auto& [k, n] : counts) next[k] = {oracle.count(k) ? oracle[k].first : frame, n};
    oracle = std::move(next);
    EXPECT_EQ(table.size(), oracle.size());
    held = std::move(now);
  }
}

TEST(RunIndex, NamesTheLineAndFieldThatIsWrong) {
  test::TempDir dir;
  const auto index_of = [&](const std::string& text) {
    std::ofstream(dir / "frames.csv") << text;
    return read_index((dir / "frames.csv").string());
  };
  const std::string header = std::string(kIndexHeader) + "\n";
  const std::string row = "0,1,2,3,,,,10,5,0,0,5,0.25,8,0,0,0,0,0,0\n";
  EXPECT_EQ(index_of(header + row).rows.size(), 1u);
  EXPECT_EQ(index_of(header + row + "1,1,2,3,,,,10,5").rows.size(), 1u);  // a line still being written
  Index bad = index_of(header + row + "1,1,2,3,,,,10,five,0,0,5,0.25,8,0,0,0,0,0,0\n");
  EXPECT_EQ(bad.error, "frames.csv, line 3: field inserted is \"five\", not a number");
  EXPECT_EQ(bad.rows.size(), 1u);
  EXPECT_EQ(index_of(header + "1,2\n").error, "frames.csv, line 2: 2 fields, not 20");
  EXPECT_EQ(index_of(header + "1,1,2,3,,,,-10,5,0,0,5,0.25,0,0,0,0,0,0,0\n").error,
            "frames.csv, line 2: field scan is \"-10\", not a count");
  EXPECT_EQ(index_of(header + "1,1,2,3,,,,10,5,0,0,5,0.25,0,4,-1,0,0,0,0\n").error,
            "frames.csv, line 2: field region_behind is negative");
  EXPECT_EQ(index_of(header + row).rows[0].figures.region.radius, 8.0);
  EXPECT_EQ(index_of("frame,x\n").error.rfind("frames.csv, line 1: not the header", 0), 0u);
  EXPECT_EQ(read_index((dir / "none.csv").string()).error, "frames.csv: cannot be opened");
}

}  // namespace
}  // namespace eco::view
