// Every format written and read back gives the same values, bit for bit; files written by other
// tools' conventions (extra fields, other types, other elements) read as they should.

#include <eco/io/kitti.hpp>
#include <eco/io/kitti_sequence.hpp>
#include <eco/io/pcd.hpp>
#include <eco/io/ply.hpp>

#include "support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>

namespace eco::io {
namespace {

PointCloud random_cloud(std::size_t n, bool with_intensity, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coordinate(-80.0f, 80.0f), unit(0.0f, 1.0f);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng) / 8.0f);
    if (with_intensity) cloud.intensity.push_back(unit(rng));
  }
  // Values that stress text formatting: tiny, huge, negative zero, exact integers.
  cloud.points.emplace_back(1e-38f, -3.4e38f, -0.0f);
  cloud.points.emplace_back(1.0f, 2.0f, 123456.789f);
  if (with_intensity) cloud.intensity.insert(cloud.intensity.end(), {1e-7f, 1.0f});
  return cloud;
}

void expect_same_bits(const PointCloud& a, const PointCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.intensity.size(), b.intensity.size());
  ASSERT_GT(a.size(), 0u);
  EXPECT_EQ(0, std::memcmp(a.points.data(), b.points.data(), a.size() * sizeof(Eigen::Vector3f)));
  if (!a.intensity.empty()) {  // (memcmp may not be given the null data() of an empty vector)
    EXPECT_EQ(0, std::memcmp(a.intensity.data(), b.intensity.data(), a.intensity.size() * sizeof(float)));
  }
}

class CloudRoundTrip : public ::testing::TestWithParam<bool> {};  // with intensity or not

TEST_P(CloudRoundTrip, Ply) {
  test::TempDir dir;
  const PointCloud cloud = random_cloud(500, GetParam(), 1);
  for (const PlyFormat format : {PlyFormat::Ascii, PlyFormat::BinaryLittleEndian}) {
    write_ply(dir / "c.ply", cloud, format);
    expect_same_bits(cloud, read_ply(dir / "c.ply"));
  }
}

TEST_P(CloudRoundTrip, Pcd) {
  test::TempDir dir;
  const PointCloud cloud = random_cloud(500, GetParam(), 2);
  for (const PcdFormat format : {PcdFormat::Ascii, PcdFormat::Binary, PcdFormat::BinaryCompressed}) {
    write_pcd(dir / "c.pcd", cloud, format);
    expect_same_bits(cloud, read_pcd(dir / "c.pcd"));
  }
}

TEST_P(CloudRoundTrip, KittiScan) {
  test::TempDir dir;
  const PointCloud cloud = random_cloud(500, GetParam(), 3);
  write_kitti_scan(dir / "000000.bin", cloud);
  const PointCloud back = read_kitti_scan(dir / "000000.bin");
  EXPECT_EQ(std::filesystem::file_size(dir / "000000.bin"), cloud.size() * 16);
  if (GetParam()) {
    expect_same_bits(cloud, back);
  } else {  // KITTI always has a reflectance: zero when the cloud had none
    PointCloud expected = cloud;
    expected.intensity.assign(cloud.size(), 0.0f);
    expect_same_bits(expected, back);
  }
}

INSTANTIATE_TEST_SUITE_P(Intensity, CloudRoundTrip, ::testing::Bool(),
                         [](const auto& param_info) { return param_info.param ? "with" : "without"; });

TEST(RoundTrip, EmptyCloudsInPlyAndPcd) {
  for (const auto format : {PlyFormat::Ascii, PlyFormat::BinaryLittleEndian}) {
    EXPECT_EQ(parse_ply(format_ply({}, format), "empty").size(), 0u);
  }
  for (const auto format : {PcdFormat::Ascii, PcdFormat::Binary, PcdFormat::BinaryCompressed}) {
    EXPECT_EQ(parse_pcd(format_pcd({}, format), "empty").size(), 0u);
  }
}

TEST(RoundTrip, LabelsPosesCalibTimes) {
  test::TempDir dir;
  const std::vector<std::uint32_t> labels = {0, 40, 252, 0xFFFF00FCu, 7};
  write_kitti_labels(dir / "l.label", labels);
  EXPECT_EQ(read_kitti_labels(dir / "l.label"), labels);

  std::vector<Eigen::Isometry3d> poses;
  std::mt19937 rng(4);
  for (int i = 0; i < 20; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    pose.translation() = Eigen::Vector3d::Random() * std::pow(10.0, i % 7);
    poses.push_back(pose);
  }
  write_kitti_poses(dir / "poses.txt", poses);
  const auto back = read_kitti_poses(dir / "poses.txt");
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(back[i].translation(), poses[i].translation()) << i;  // exact: shortest round trip
    EXPECT_LT((back[i].linear() - poses[i].linear()).cwiseAbs().maxCoeff(), 1e-15) << i;
  }

  write_kitti_calib(dir / "calib.txt", kitti_velo_to_cam());
  EXPECT_LT((read_kitti_calib(dir / "calib.txt").matrix() - kitti_velo_to_cam().matrix()).cwiseAbs().maxCoeff(), 1e-15);

  std::ofstream(dir / "times.txt") << "0.0\n1.036e-1\n\n2.5\n";
  EXPECT_EQ(read_kitti_times(dir / "times.txt"), (std::vector<double>{0.0, 0.1036, 2.5}));
}

TEST(RoundTrip, CameraAndLidarPosesInvertEachOther) {
  Eigen::Isometry3d lidar = Eigen::Isometry3d::Identity();
  lidar.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  lidar.translation() = Eigen::Vector3d(12.0, -4.0, 1.7);
  const Eigen::Isometry3d tr = kitti_velo_to_cam();
  const Eigen::Isometry3d camera = camera_pose_from_lidar(lidar, tr);
  EXPECT_LT((lidar_pose_from_camera(camera, tr).matrix() - lidar.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  // The convention itself: P = Tr * L * Tr^-1, checked on a point.
  const Eigen::Vector3d p_lidar(3.0, 1.0, -0.5);
  EXPECT_LT((camera * (tr * p_lidar) - tr * (lidar * p_lidar)).norm(), 1e-12);
}

TEST(RoundTrip, KittiFolderInBothPoseFrames) {
  for (const bool camera : {true, false}) {
    test::TempDir dir;
    std::vector<PointCloud> clouds;
    std::vector<Eigen::Isometry3d> poses;
    {
      KittiWriter writer(dir.path(), camera ? std::optional(kitti_velo_to_cam()) : std::nullopt);
      for (int i = 0; i < 3; ++i) {
        clouds.push_back(random_cloud(50 + 10 * static_cast<std::size_t>(i), true, 10u + static_cast<unsigned>(i)));
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.linear() = Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        pose.translation() = Eigen::Vector3d(1.0 * i, 0.5 * i, 0.0);
        poses.push_back(pose);
        std::vector<std::uint32_t> labels(clouds.back().size(), label::kRoad);
        writer.write(pose, clouds.back(), labels, 0.1 * i);
      }
    }
    EXPECT_EQ(std::filesystem::exists(dir / "calib.txt"), camera);
    const KittiSequence sequence(dir.path());
    EXPECT_EQ(sequence.poses_were_camera_frame(), camera);
    ASSERT_EQ(sequence.size(), 3u);
    ASSERT_TRUE(sequence.has_labels());
    for (std::size_t i = 0; i < 3; ++i) {
      const KittiFrame frame = sequence.read(i);
      expect_same_bits(clouds[i], frame.cloud);
      EXPECT_LT((frame.world_T_lidar.matrix() - poses[i].matrix()).cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_EQ(sequence.read_labels(i).size(), clouds[i].size());
      EXPECT_DOUBLE_EQ(sequence.times()[i], 0.1 * static_cast<double>(i));
    }
    EXPECT_THROW((void)sequence.read(3), std::out_of_range);
  }
}

TEST(ForeignFiles, PlyWithDoublesExtraPropertiesAndOtherElements) {
  // A "camera" element before the vertices and a face list after them, as meshing tools write.
  std::string text =
      "ply\r\nformat binary_little_endian 1.0\r\ncomment from elsewhere\r\n"
      "element camera 1\r\nproperty float view_px\r\nproperty uchar flag\r\n"
      "element vertex 2\r\nproperty double x\r\nproperty double y\r\nproperty double z\r\n"
      "property uchar red\r\nproperty ushort reflectance\r\n"
      "element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n";
  const auto append = [&](const auto& value) {
    text.append(reinterpret_cast<const char*>(&value), sizeof value);
  };
  append(1.5f);
  append(std::uint8_t{9});
  for (const double v : {1.25, -2.5, 3.0}) append(v);
  append(std::uint8_t{200});
  append(std::uint16_t{700});
  for (const double v : {4.0, 5.0, -6.0}) append(v);
  append(std::uint8_t{1});
  append(std::uint16_t{65535});
  text += "face bytes that are never read";
  const PointCloud cloud = parse_ply(text, "mesh.ply");
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1.25f, -2.5f, 3.0f));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4.0f, 5.0f, -6.0f));
  EXPECT_EQ(cloud.intensity, (std::vector<float>{700.0f, 65535.0f}));
}

TEST(ForeignFiles, PlyAsciiWithOtherOrderAndElementBefore) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement note 2\nproperty int a\nelement vertex 2\n"
      "property float intensity\nproperty float z\nproperty float y\nproperty float x\nend_header\n"
      "1\n2\n0.5 3 2 1\n+0.25 -3e0 -2 -1\n";
  const PointCloud cloud = parse_ply(text, "ascii.ply");
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(-1, -2, -3));
  EXPECT_EQ(cloud.intensity, (std::vector<float>{0.5f, 0.25f}));
}

TEST(ForeignFiles, PcdOrganisedWithPaddingNanAndOtherTypes) {
  std::string text =
      "# .PCD v.7\nVERSION .7\nFIELDS x y z _ rgb intensity\nSIZE 8 8 8 1 4 2\nTYPE F F F U U U\n"
      "COUNT 1 1 1 3 1 1\nWIDTH 2\nHEIGHT 2\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA binary\n";
  for (int i = 0; i < 4; ++i) {
    const double xyz[3] = {i == 2 ? std::numeric_limits<double>::quiet_NaN() : 1.0 * i, 2.0, -1.0};
    text.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    text.append(3, '\0');
    const std::uint32_t rgb = 0xFF00FF;
    const std::uint16_t intensity = static_cast<std::uint16_t>(10 * i);
    text.append(reinterpret_cast<const char*>(&rgb), 4);
    text.append(reinterpret_cast<const char*>(&intensity), 2);
  }
  const PointCloud cloud = parse_pcd(text, "organised.pcd");
  ASSERT_EQ(cloud.size(), 4u);  // organised clouds keep their NaN holes; ECO's update skips them
  EXPECT_EQ(cloud.points[3], Eigen::Vector3f(3, 2, -1));
  EXPECT_TRUE(std::isnan(cloud.points[2].x()));
  EXPECT_EQ(cloud.intensity, (std::vector<float>{0, 10, 20, 30}));

  const PointCloud ascii = parse_pcd(
      "FIELDS intensity x y z\nSIZE 4 4 4 4\nTYPE F F F F\nWIDTH 2\nDATA ascii\n7 1 2 3\n8 nan 5 6\n",
      "minimal.pcd");
  ASSERT_EQ(ascii.size(), 2u);
  EXPECT_EQ(ascii.points[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_TRUE(std::isnan(ascii.points[1].x()));
  EXPECT_EQ(ascii.intensity, (std::vector<float>{7, 8}));
}

TEST(ForeignFiles, KittiCalibWithTrVeloToCamKey) {
  const Eigen::Isometry3d tr = parse_kitti_calib(
      "P0: 1 0 0 0 0 1 0 0 0 0 1 0\nTr_velo_to_cam: 0 -1 0 0.1 0 0 -1 0.2 1 0 0 0.3\n", "object.txt");
  EXPECT_EQ(tr.translation(), Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_TRUE((tr * Eigen::Vector3d(1, 0, 0) - tr.translation()).isApprox(Eigen::Vector3d(0, 0, 1), 1e-15));
}

}  // namespace
}  // namespace eco::io
