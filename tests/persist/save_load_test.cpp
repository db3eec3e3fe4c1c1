// Save and load (EgoOctree::save, EgoOctree::load; docs/map-format.md): a loaded tree answers as
// the saved one did and, fed the same frames, stays identical to it; a file that is not a whole
// map is refused naming its path and byte; a save that fails keeps the file it would replace.

#include "support/map_answers.hpp"
#include "support/temp_dir.hpp"

#include <eco/ego_octree.hpp>
#include <eco/sim/simulator.hpp>

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

namespace eco::test {
namespace {

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
  if (everything) with_everything(cfg, drive);
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
  bad[8] = 4;  // version 4
  expect_refused(dir, bad, {"byte 8", "version 4", "reads versions 1 to 3"}, "version");
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

/// A process killed in the middle of its save leaves the earlier file loadable and unchanged. The
/// kill lands mid-write for certain: the child may write half the map's bytes a file and keeps the
/// default action of SIGXFSZ, so the kernel ends it in the write that crosses the limit.
TEST(Save, AProcessKilledMidSaveLeavesTheEarlierFile) {
  TempDir dir("eco-save");
  const std::string path = saved_map(dir);
  const std::string before = read_bytes(path);
  EgoOctree tree = EgoOctree::load(path);
  tree.update(Eigen::Isometry3d(Eigen::Translation3d(1.0, 0.0, 0.0)), ScanView());  // a different map
  const pid_t child = fork();  // this test runs no other thread
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_DFL);
    rlimit half{};
    half.rlim_cur = half.rlim_max = before.size() / 2;
    if (setrlimit(RLIMIT_FSIZE, &half) != 0) _exit(3);
    try {
      tree.save(path);
    } catch (...) {
      _exit(2);
    }
    _exit(0);  // not reached: the write past the limit ends the process
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the child ended by itself, status " << status;
  EXPECT_EQ(WTERMSIG(status), SIGXFSZ);
  EXPECT_EQ(read_bytes(path), before);
  EXPECT_NO_THROW((void)EgoOctree::load(path));
}

/// Killed at any moment while it saves two maps in turn, a process leaves one of the two whole.
TEST(Save, KilledAtAnyMomentTheFileIsOneOfTheTwoMaps) {
  TempDir dir("eco-save");
  const std::string path = saved_map(dir);
  const std::string first = read_bytes(path);
  EgoOctree other = EgoOctree::load(path);
  other.update(Eigen::Isometry3d(Eigen::Translation3d(3.0, 0.0, 0.0)), ScanView());
  const std::string second_path = (dir / "second.eco").string();
  other.save(second_path);
  const std::string second = read_bytes(second_path);
  ASSERT_NE(first, second);
  const EgoOctree maps[2] = {EgoOctree::load(path), EgoOctree::load(second_path)};
  std::mt19937 rng(11);
  for (int trial = 0; trial < 12; ++trial) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      for (std::size_t i = 0;; ++i) maps[i % 2].save(path);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(0, 30000)(rng)));
    kill(child, SIGKILL);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    const std::string now = read_bytes(path);
    EXPECT_TRUE(now == first || now == second) << "trial " << trial << ": a file of " << now.size() << " bytes";
    EXPECT_NO_THROW((void)EgoOctree::load(path)) << "trial " << trial;
  }
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
