// Bad files give an eco::io::Error naming the file and the line or byte offset, never a crash.

#include <eco/io/kitti.hpp>
#include <eco/io/kitti_sequence.hpp>
#include <eco/io/pcd.hpp>
#include <eco/io/ply.hpp>

#include "support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <initializer_list>

namespace eco::io {
namespace {

namespace fs = std::filesystem;

// Runs `call`, which must throw eco::io::Error whose message holds every one of `parts`.
void expect_error(const std::function<void()>& call, std::initializer_list<std::string> parts) {
  try {
    call();
    ADD_FAILURE() << "no error; expected one mentioning '" << *parts.begin() << "'";
  } catch (const Error& e) {
    const std::string message = e.what();
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\n  lacks: " << part;
  }
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A valid two-scan KITTI folder (lidar-frame poses) to break one piece at a time.
void make_sequence(const fs::path& folder) {
  KittiWriter writer(folder, std::nullopt);
  PointCloud cloud;
  cloud.points = {{1, 2, 3}, {4, 5, 6}};
  for (int i = 0; i < 2; ++i) writer.write(Eigen::Isometry3d::Identity(), cloud);
}

TEST(KittiBadInput, ScanSizeNotAMultipleOf16) {
  test::TempDir dir;
  write_text(dir / "000000.bin", std::string(16 * 3 + 5, '\0'));
  expect_error([&] { (void)read_kitti_scan(dir / "000000.bin"); },
               {(dir / "000000.bin").string(), "byte 48", "not a multiple of 16"});
}

TEST(KittiBadInput, EmptyFiles) {
  test::TempDir dir;
  for (const char* name : {"000000.bin", "poses.txt", "calib.txt", "times.txt", "a.label"}) {
    write_text(dir / name, "");
  }
  expect_error([&] { (void)read_kitti_scan(dir / "000000.bin"); }, {"000000.bin", "empty"});
  expect_error([&] { (void)read_kitti_poses(dir / "poses.txt"); }, {"poses.txt", "empty"});
  expect_error([&] { (void)read_kitti_calib(dir / "calib.txt"); }, {"calib.txt", "empty"});
  expect_error([&] { (void)read_kitti_times(dir / "times.txt"); }, {"times.txt", "empty"});
  expect_error([&] { (void)read_kitti_labels(dir / "a.label"); }, {"a.label", "empty"});
  write_text(dir / "poses.txt", "\n  \n");
  expect_error([&] { (void)read_kitti_poses(dir / "poses.txt"); }, {"poses.txt", "no poses"});
}

TEST(KittiBadInput, MalformedPoses) {
  const std::string good = "1 0 0 0 0 1 0 0 0 0 1 0\n";
  expect_error([&] { (void)parse_kitti_poses(good + good + "1 0 0 0 0 1 0 O.5 0 0 1 0\n", "p.txt"); },
               {"p.txt", "line 3", "malformed number 'O.5'"});
  expect_error([&] { (void)parse_kitti_poses(good + "1 0 0 0 0 1 0 0 0 0 1\n", "p.txt"); },
               {"p.txt", "line 2", "expected 12 numbers", "found 11"});
  expect_error([&] { (void)parse_kitti_poses("1 0 0 0 0 1 0 0 0 0 1 nan\n", "p.txt"); },
               {"line 1", "not finite"});
  expect_error([&] { (void)parse_kitti_poses("2 0 0 0 0 1 0 0 0 0 1 0\n", "p.txt"); },
               {"line 1", "not a rotation"});
  expect_error([&] { (void)parse_kitti_poses("-1 0 0 0 0 1 0 0 0 0 1 0\n", "p.txt"); },
               {"line 1", "not a rotation"});  // a reflection
  expect_error([&] { (void)parse_kitti_poses("1 0 0 1e999 0 1 0 0 0 0 1 0\n", "p.txt"); },
               {"line 1", "out of range"});
  expect_error([&] { (void)parse_kitti_times("0.1\n0.2 0.3\n", "t.txt"); }, {"t.txt", "line 2"});
}

TEST(KittiBadInput, CalibWithoutTr) {
  expect_error([&] { (void)parse_kitti_calib("P0: 1 0 0 0 0 1 0 0 0 0 1 0\nP1: 1 0 0 0 0 1 0 0 0 0 1 0\n", "calib.txt"); },
               {"calib.txt", "no 'Tr:' line"});
  expect_error([&] { (void)parse_kitti_calib("P0: 1\nTr: 1 0 0 0 0 1 0 0 0 0 1\n", "calib.txt"); },
               {"calib.txt", "line 2", "expected 12 numbers"});
}

TEST(KittiBadInput, Folders) {
  test::TempDir dir;
  expect_error([&] { KittiSequence s(dir / "nowhere"); }, {(dir / "nowhere").string(), "no such folder"});
  expect_error([&] { KittiSequence s(dir.path()); }, {(dir / "velodyne").string(), "no such folder"});

  make_sequence(dir / "few_poses");
  write_text(dir / "few_poses" / "poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n");
  expect_error([&] { KittiSequence s(dir / "few_poses"); }, {"poses.txt", "1 poses for 2 scans"});

  make_sequence(dir / "gap");
  fs::rename(dir / "gap" / "velodyne" / "000001.bin", dir / "gap" / "velodyne" / "000002.bin");
  expect_error([&] { KittiSequence s(dir / "gap"); }, {"000001.bin", "is missing"});

  make_sequence(dir / "no_calib");
  expect_error([&] { KittiSequence s(dir / "no_calib", {PoseFrame::Camera}); }, {"calib.txt", "cannot open"});

  make_sequence(dir / "no_poses");
  fs::remove(dir / "no_poses" / "poses.txt");
  expect_error([&] { KittiSequence s(dir / "no_poses"); }, {"poses.txt", "cannot open"});
  KittiOptions scans_alone;  // poses not required: read without them, frames at the identity
  scans_alone.require_poses = false;
  const KittiSequence without(dir / "no_poses", scans_alone);
  EXPECT_FALSE(without.has_poses());
  EXPECT_TRUE(without.poses().empty());
  EXPECT_EQ(without.size(), 2u);
  EXPECT_TRUE(without.read(1).world_T_lidar.isApprox(Eigen::Isometry3d::Identity()));
  make_sequence(dir / "few_poses_not_required");  // a poses file that exists is still checked
  write_text(dir / "few_poses_not_required" / "poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n");
  expect_error([&] { KittiSequence s(dir / "few_poses_not_required", scans_alone); }, {"1 poses for 2 scans"});

  make_sequence(dir / "few_times");
  write_text(dir / "few_times" / "times.txt", "0\n");
  expect_error([&] { KittiSequence s(dir / "few_times"); }, {"times.txt", "1 times for 2 scans"});

  make_sequence(dir / "bad_scan");
  write_text(dir / "bad_scan" / "velodyne" / "000001.bin", std::string(17, 'x'));
  const KittiSequence sequence(dir / "bad_scan");
  EXPECT_NO_THROW((void)sequence.read(0));
  expect_error([&] { (void)sequence.read(1); }, {"000001.bin", "byte 16"});

  fs::create_directories(dir / "bad_scan" / "labels");
  write_kitti_labels(dir / "bad_scan" / "labels" / "000000.label", std::vector<std::uint32_t>{1, 2, 3});
  expect_error([&] { (void)sequence.read_labels(0); }, {"000000.label", "3 labels for the 2 points"});
}

TEST(KittiBadInput, WriterRefusesMismatchedLabels) {
  test::TempDir dir;
  KittiWriter writer(dir.path());
  PointCloud cloud;
  cloud.points = {{1, 2, 3}};
  const std::vector<std::uint32_t> labels = {1, 2};
  EXPECT_THROW(writer.write(Eigen::Isometry3d::Identity(), cloud, labels), std::invalid_argument);
  EXPECT_EQ(writer.size(), 0u);
  cloud.intensity = {0.1f, 0.2f};
  expect_error([&] { write_ply(dir / "x.ply", cloud); }, {"x.ply", "1 points with 2 intensities"});
  expect_error([&] { write_kitti_scan(dir / "x.bin", PointCloud{}); }, {"x.bin", "at least one point"});
}

const std::string kPlyHead = "ply\nformat ascii 1.0\nelement vertex 2\n";
const std::string kXyz = "property float x\nproperty float y\nproperty float z\n";

TEST(PlyBadInput, Header) {
  expect_error([] { (void)parse_ply("", "e.ply"); }, {"e.ply", "line", "not a PLY file"});
  expect_error([] { (void)parse_ply("PLY\n", "e.ply"); }, {"e.ply", "line 1", "not a PLY file"});
  expect_error([] { (void)parse_ply(kPlyHead + kXyz + "property list uchar int idx\nend_header\n", "l.ply"); },
               {"l.ply", "line 7", "unsupported property"});
  expect_error([] { (void)parse_ply(kPlyHead + "property int128 x\n", "t.ply"); },
               {"t.ply", "line 4", "unsupported property type 'int128'"});
  expect_error([] { (void)parse_ply("ply\nformat binary_big_endian 1.0\n", "b.ply"); },
               {"b.ply", "line 2", "unsupported format"});
  expect_error([] { (void)parse_ply(kPlyHead + kXyz, "h.ply"); }, {"h.ply", "no 'end_header'"});
  expect_error([] { (void)parse_ply(kPlyHead + "property float x\nproperty float y\nend_header\n", "z.ply"); },
               {"z.ply", "no 'z' field"});
  expect_error([] { (void)parse_ply("ply\nformat ascii 1.0\nelement vertex x2\n", "n.ply"); },
               {"n.ply", "line 3", "malformed number 'x2'"});
  expect_error([] { (void)parse_ply("ply\nformat ascii 1.0\nelement face 2\nend_header\n3 0 1 2\n3 0 1 2\n", "f.ply"); },
               {"f.ply", "no 'vertex' element"});
}

TEST(PlyBadInput, Data) {
  expect_error([] { (void)parse_ply(kPlyHead + kXyz + "end_header\n1 2 3\n4 5\n", "a.ply"); },
               {"a.ply", "line 9", "expected 3 numbers, found 2"});
  expect_error([] { (void)parse_ply(kPlyHead + kXyz + "end_header\n1 2 3\n4 5 six\n", "a.ply"); },
               {"a.ply", "line 9", "malformed number 'six'"});
  expect_error([] { (void)parse_ply(kPlyHead + kXyz + "end_header\n1 2 3\n", "a.ply"); },
               {"a.ply", "ends after 1 of 2 points"});
  const std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n" + kXyz + "end_header\n";
  expect_error([&] { (void)parse_ply(binary + std::string(20, '\0'), "b.ply"); },
               {"b.ply", "byte " + std::to_string(binary.size()), "4000000000 points of 12 bytes"});
}

TEST(PcdBadInput, HeaderAndData) {
  const std::string fields = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n";
  expect_error([] { (void)parse_pcd("", "e.pcd"); }, {"e.pcd", "no DATA line"});
  expect_error([&] { (void)parse_pcd(fields + "WIDTH 1\nDATA lzma\n", "d.pcd"); },
               {"d.pcd", "line 5", "unsupported DATA 'lzma'"});
  expect_error([&] { (void)parse_pcd("FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nDATA ascii\n", "s.pcd"); },
               {"s.pcd", "different numbers of fields"});
  expect_error([&] { (void)parse_pcd("FIELDS x y z\nSIZE 4 4 3\nTYPE F F F\nWIDTH 1\nDATA ascii\n", "s.pcd"); },
               {"s.pcd", "unsupported field 'z'"});
  expect_error([&] { (void)parse_pcd(fields + "WIDTH 2\nHEIGHT 1\nPOINTS 3\nDATA ascii\n", "p.pcd"); },
               {"p.pcd", "line 6", "POINTS 3 differs"});
  expect_error([&] { (void)parse_pcd(fields + "WIDTH 2\nDATA ascii\n1 2 3\n1 2 3 4\n", "a.pcd"); },
               {"a.pcd", "line 7", "expected 3 numbers, found 4"});
  expect_error([&] { (void)parse_pcd(fields + "WIDTH 2\nDATA binary\n" + std::string(13, '\0'), "b.pcd"); },
               {"b.pcd", "byte 55", "2 points of 12 bytes"});
  std::string compressed = fields + "WIDTH 2\nDATA binary_compressed\n";
  const std::uint32_t sizes[2] = {5, 24};
  compressed.append(reinterpret_cast<const char*>(sizes), 8);
  expect_error([&] { (void)parse_pcd(compressed + "\x1f\x01\x02\x03\x04", "c.pcd"); },
               {"c.pcd", "corrupt LZF data"});
  expect_error([&] { (void)parse_pcd(compressed, "c.pcd"); }, {"c.pcd", "runs past the end"});
}

TEST(FileBadInput, MissingFilesAndFolders) {
  test::TempDir dir;
  expect_error([&] { (void)read_ply(dir / "absent.ply"); }, {"absent.ply", "cannot open"});
  expect_error([&] { (void)read_pcd(dir.path()); }, {dir.path().string(), "is a directory"});
  expect_error([&] { write_pcd(dir / "no" / "such" / "x.pcd", PointCloud{}); }, {"x.pcd", "cannot create"});
}

}  // namespace
}  // namespace eco::io
