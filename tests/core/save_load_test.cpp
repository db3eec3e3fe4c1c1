// Save and load (EgoOctree::save, EgoOctree::load; docs/map-format.md): a loaded tree answers as
// the saved one did and, fed the same frames, stays identical to it; a file that is not a whole
// map is refused naming its path and byte; a save that fails keeps the file it would replace.

#include "support/temp_dir.hpp"

#include <eco/ego_octree.hpp>
#include <eco/sim/simulator.hpp>

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace eco::test {
namespace {

sim::SimConfig small_drive(std::size_t frames) {
  sim::SimConfig s;
  s.seed = 8;
  s.frames = frames;
  s.lidar.beams = 16;
  s.lidar.columns = 360;
  s.city.moving_cars = 40;
  return s;
}

/// Gives `scan` ids numbered per frame, intensities, and times 7.3 s apart a frame (the time
/// origin moves every ~9 frames), kept in the three vectors.
void add_attributes(ScanView& scan, std::size_t t, std::vector<std::uint32_t>& ids, std::vector<float>& intensities,
                    std::vector<double>& times) {
  const std::size_t n = scan.count;
  ids.resize(n);
  intensities.resize(n);
  times.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    ids[i] = std::uint32_t(t * 100000 + i);
    intensities[i] = float(i % 97);
    times[i] = 1.7e9 + 7.3 * double(t) + 1e-5 * double(i);
  }
  scan.ids = ids.data();
  scan.intensities = intensities.data();
  scan.times = times.data();
}

void expect_same_neighbors(const std::vector<Neighbor>& a, const std::vector<Neighbor>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].point, b[i].point) << what << ", neighbour " << i;
    EXPECT_EQ(a[i].sq_dist, b[i].sq_dist) << what << ", neighbour " << i;
    EXPECT_EQ(a[i].attributes, b[i].attributes) << what << ", neighbour " << i;
  }
}

/// Every answer of `loaded` equals `saved`'s, in the same order: the held points, KNN, radius
/// and box queries, voxel maps, the frame, pose and origins.
void expect_identical(const EgoOctree& saved, const EgoOctree& loaded, std::mt19937& rng, const std::string& when) {
  SCOPED_TRACE(when);
  ASSERT_EQ(loaded.check_invariants(), "");
  ASSERT_EQ(loaded.size(), saved.size());
  EXPECT_EQ(loaded.frame_count(), saved.frame_count());
  EXPECT_TRUE(loaded.pose().isApprox(saved.pose(), 0.0));
  EXPECT_EQ(loaded.precision_origin(), saved.precision_origin());
  EXPECT_EQ(loaded.time_origin(), saved.time_origin());
  EXPECT_EQ(loaded.stats().points, saved.stats().points);
  EXPECT_EQ(loaded.stats().nodes, saved.stats().nodes);
  const std::vector<HeldPoint> a = saved.points_with_attributes(), b = loaded.points_with_attributes();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].point, b[i].point) << "held point " << i;
    ASSERT_EQ(a[i].attributes, b[i].attributes) << "held point " << i;
  }
  if (a.empty()) return;
  std::uniform_int_distribution<std::size_t> pick(0, a.size() - 1);
  std::normal_distribution<double> jitter(0.0, 0.3);
  for (int q = 0; q < 20; ++q) {
    const Eigen::Vector3d p = a[pick(rng)].point + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    for (const std::size_t k : {1, 5, 40}) {
      expect_same_neighbors(saved.knn(p, k), loaded.knn(p, k), "knn, k = " + std::to_string(k));
    }
    expect_same_neighbors(saved.radius(p, 1.5), loaded.radius(p, 1.5), "radius");
    const Eigen::Vector3d lo = p - Eigen::Vector3d(2, 2, 1), hi = p + Eigen::Vector3d(2, 2, 1);
    EXPECT_EQ(saved.box(lo, hi), loaded.box(lo, hi)) << "box";
  }
  for (const double res : {0.1, 0.35}) EXPECT_EQ(saved.voxel_keys(res), loaded.voxel_keys(res)) << "voxels " << res;
}

using Params = std::tuple<Recentring, bool>;  // re-centring; clearing, density cap, attributes and age limit

class SaveLoad : public ::testing::TestWithParam<Params> {};

/// After every frame of a drive with moving cars, carried 2 km out so that the precision origin
/// moves under held points: the map saved and loaded answers as the saved one, and each loaded
/// copy, fed the next three frames beside it, stays identical to it.
TEST_P(SaveLoad, EveryFrameRoundTripsAndTheCopyContinuesIdentically) {
  const auto [recentring, everything] = GetParam();
  const sim::Simulator drive(small_drive(24));
  Config cfg;
  cfg.recentring = recentring;
  cfg.box_side = 40.0;
  if (everything) {
    cfg.clearing.enabled = true;
    cfg.sensor.vertical_fov_min = drive.config().lidar.fov_down_deg - 0.5;
    cfg.sensor.vertical_fov_max = drive.config().lidar.fov_up_deg + 0.5;
    cfg.sensor.vertical_resolution =
        (drive.config().lidar.fov_up_deg - drive.config().lidar.fov_down_deg) / (drive.config().lidar.beams - 1);
    cfg.sensor.horizontal_resolution = 2.0;
    cfg.sensor.max_range = 60.0;
    cfg.density_cap = {0.3, 2};
    cfg.attributes = {true, true, true};
    cfg.max_age_seconds = 20.0;
  }
  TempDir dir("eco-save-load");
  const std::string path = (dir / "map.eco").string();
  EgoOctree tree(cfg);
  std::mt19937 rng(5);
  {  // a tree that has taken no frame
    tree.save(path);
    const EgoOctree fresh = EgoOctree::load(path);
    expect_identical(tree, fresh, rng, "before the first frame");
    EXPECT_EQ(fresh.config().clearing.enabled, cfg.clearing.enabled);
  }
  struct Copy {
    EgoOctree tree;
    std::size_t frames_left;
  };
  std::vector<Copy> copies;
  std::vector<std::uint32_t> ids;
  std::vector<float> intensities;
  std::vector<double> times;
  const double x10 = drive.pose(10).translation().x();
  bool rebased = false;
  for (std::size_t t = 0; t < drive.size(); ++t) {
    sim::SimFrame frame = drive.frame(t);
    if (t >= 10) frame.world_T_lidar.translation().x() += 2040.0 - x10 + 3.0 * double(t - 10);
    ScanView scan(frame.cloud.points);
    if (everything) add_attributes(scan, t, ids, intensities, times);
    rebased = tree.update(frame.world_T_lidar, scan).rebased || rebased;
    for (Copy& c : copies) {
      c.tree.update(frame.world_T_lidar, scan);
      --c.frames_left;
      expect_identical(tree, c.tree, rng, "frame " + std::to_string(t) + ", a copy loaded " +
                                              std::to_string(3 - c.frames_left) + " frames before");
      if (HasFatalFailure()) return;
    }
    std::erase_if(copies, [](const Copy& c) { return c.frames_left == 0; });
    tree.save(path);
    copies.push_back({EgoOctree::load(path), 3});
    expect_identical(tree, copies.back().tree, rng, "frame " + std::to_string(t) + ", just loaded");
    if (HasFatalFailure()) return;
  }
  EXPECT_TRUE(rebased) << "the precision origin never moved under held points";
}

INSTANTIATE_TEST_SUITE_P(Modes, SaveLoad,
                         ::testing::Combine(::testing::Values(Recentring::Quantised, Recentring::Exact),
                                            ::testing::Bool()),
                         [](const ::testing::TestParamInfo<Params>& p) {
                           return std::string(std::get<0>(p.param) == Recentring::Exact ? "Exact" : "Quantised") +
                                  (std::get<1>(p.param) ? "_ClearingCapAttributesAge" : "");
                         });

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

/// A small saved map with every section: clearing on, ids, intensity, time.
std::string saved_map(const TempDir& dir) {
  const sim::Simulator drive(small_drive(3));
  Config cfg;
  cfg.clearing.enabled = true;
  cfg.attributes = {true, true, true};
  EgoOctree tree(cfg);
  std::vector<std::uint32_t> ids;
  std::vector<float> intensities;
  std::vector<double> times;
  for (std::size_t t = 0; t < drive.size(); ++t) {
    const sim::SimFrame frame = drive.frame(t);
    ScanView scan(frame.cloud.points);
    add_attributes(scan, t, ids, intensities, times);
    tree.update(frame.world_T_lidar, scan);
  }
  const std::string path = (dir / "good.eco").string();
  tree.save(path);
  return path;
}

/// Loading `bytes` is refused with a message naming the file, "byte N" and `words`.
void expect_refused(const TempDir& dir, const std::string& bytes, const std::vector<std::string>& words,
                    const std::string& what) {
  SCOPED_TRACE(what);
  const std::string path = (dir / "bad.eco").string();
  write_bytes(path, bytes);
  try {
    (void)EgoOctree::load(path);
    ADD_FAILURE() << "loaded";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path + ": byte "), std::string::npos) << message;
    for (const std::string& w : words) EXPECT_NE(message.find(w), std::string::npos) << message;
  }
}

TEST(LoadRefuses, TruncatedFilesAtEveryLength) {
  TempDir dir("eco-load");
  const std::string good = read_bytes(saved_map(dir));
  ASSERT_GT(good.size(), 1000u);
  for (std::size_t n = 0; n < good.size(); n += 1 + n / 4) {
    expect_refused(dir, good.substr(0, n), {}, "first " + std::to_string(n) + " bytes");
  }
  expect_refused(dir, good.substr(0, good.size() - 1), {"truncated"}, "one byte short");
  expect_refused(dir, good + "x", {"extended"}, "one byte more");
}

TEST(LoadRefuses, FlippedBitsAnywhere) {
  TempDir dir("eco-load");
  const std::string good = read_bytes(saved_map(dir));
  std::mt19937 rng(2);
  std::uniform_int_distribution<std::size_t> at(20, good.size() - 5);  // past the header, before the checksum
  for (int i = 0; i < 50; ++i) {
    std::string bad = good;
    const std::size_t byte = at(rng);
    bad[byte] = char(bad[byte] ^ (1 << (i % 8)));
    expect_refused(dir, bad, {"checksum mismatch"}, "bit " + std::to_string(i % 8) + " of byte " + std::to_string(byte));
  }
}

TEST(LoadRefuses, WrongMagicOrVersionByName) {
  TempDir dir("eco-load");
  const std::string good = read_bytes(saved_map(dir));
  std::string bad = good;
  bad[0] = 'X';
  expect_refused(dir, bad, {"byte 0", "wrong magic"}, "magic");
  bad = good;
  bad[8] = 2;  // version 2
  expect_refused(dir, bad, {"byte 8", "version 2", "reads version 1"}, "version");
  expect_refused(dir, "", {"byte 0", "the file ends here"}, "an empty file");
}

TEST(LoadRefuses, AMissingFileByName) {
  TempDir dir("eco-load");
  const std::string path = (dir / "none.eco").string();
  try {
    (void)EgoOctree::load(path);
    ADD_FAILURE() << "loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": cannot open"), std::string::npos) << e.what();
  }
}

/// A save that cannot write its file (the process may write no more than 4 KB a file) throws,
/// leaves the earlier file at the path as it was and no temporary file beside it.
TEST(Save, AFailedSaveKeepsTheEarlierFile) {
  TempDir dir("eco-save");
  const std::string path = saved_map(dir);
  const std::string before = read_bytes(path);
  ASSERT_GT(before.size(), 4096u);
  EgoOctree tree = EgoOctree::load(path);
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);  // a write past the limit fails instead
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string message;
  try {
    tree.save(path);
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_NE(message.find(path + ": cannot write"), std::string::npos) << message;
  EXPECT_EQ(read_bytes(path), before);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u) << "a temporary file was left";
  tree.save(path);  // and with room again, the same map
  EXPECT_EQ(read_bytes(path), before);
}

TEST(Save, IntoAMissingFolderThrowsNamingThePath) {
  TempDir dir("eco-save");
  const std::string path = (dir / "no" / "map.eco").string();
  try {
    EgoOctree().save(path);
    ADD_FAILURE() << "saved";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": cannot create"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace eco::test
