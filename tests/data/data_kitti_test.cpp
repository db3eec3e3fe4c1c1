// The real frames in ../shared/data: the readers take them, and the lidar-pose convention
// (Tr^-1 * P * Tr for KITTI's camera poses; BALM's poses as they are) registers them.

#include <eco/eco.hpp>
#include <eco/io/kitti_sequence.hpp>

#include "support/overlap.hpp"
#include "support/shared_data.hpp"

#include <gtest/gtest.h>

#include <iostream>

namespace eco::io {
namespace {

struct Overlaps {
  double lidar_poses = 0.0, camera_poses_as_is = 0.0, identity = 0.0;
};

// Scan j placed against scan i three ways: with the lidar poses, with poses.txt taken as lidar
// poses (the mistake of skipping Tr), and with no motion at all.
Overlaps overlaps(const KittiSequence& lidar, const KittiSequence& raw, std::size_t i, std::size_t j) {
  const KittiFrame a = lidar.read(i), b = lidar.read(j);
  const Eigen::Isometry3d id = Eigen::Isometry3d::Identity();
  const double above_road = -1.3;  // the Velodyne is 1.73 m above the road
  return {test::voxel_overlap(a.cloud.points, a.world_T_lidar, b.cloud.points, b.world_T_lidar, above_road),
          test::voxel_overlap(a.cloud.points, raw.poses()[i], b.cloud.points, raw.poses()[j], above_road),
          test::voxel_overlap(a.cloud.points, id, b.cloud.points, id, above_road)};
}

TEST(RealKitti, LidarPoseConventionRegistersConsecutiveScans) {
  for (const char* name : {"kitti_mini_00", "kitti_mini_02", "kitti_mini_08"}) {
    ECO_REQUIRE_DATASET(folder, name);
    const KittiSequence sequence(folder);
    ASSERT_TRUE(sequence.poses_were_camera_frame());
    ASSERT_EQ(sequence.size(), 10u);
    const KittiSequence raw(folder, {PoseFrame::Lidar});
    Overlaps mean;
    for (std::size_t i = 0; i + 1 < sequence.size(); ++i) {
      const Overlaps o = overlaps(sequence, raw, i, i + 1);
      mean.lidar_poses += o.lidar_poses / 9.0;
      mean.camera_poses_as_is += o.camera_poses_as_is / 9.0;
      mean.identity += o.identity / 9.0;
    }
    std::cout << name << ": mean overlap of consecutive scans (0.2 m voxels, range < 30 m, above the road): lidar poses "
              << mean.lidar_poses << ", camera poses as is " << mean.camera_poses_as_is
              << ", identity " << mean.identity << "\n";
    EXPECT_GT(mean.lidar_poses, 1.5 * mean.identity) << name;
    EXPECT_GT(mean.lidar_poses, 3.0 * mean.camera_poses_as_is) << name;
  }
}

TEST(RealKitti, ScansReadWholeAndFinite) {
  ECO_REQUIRE_DATASET(folder, "kitti_mini_00");
  const KittiSequence sequence(folder);
  const KittiFrame frame = sequence.read(0);
  EXPECT_EQ(frame.cloud.size() * 16, std::filesystem::file_size(sequence.scan_path(0)));
  EXPECT_GT(frame.cloud.size(), 100000u);
  for (const auto& p : frame.cloud.points) ASSERT_TRUE(p.allFinite());
  EXPECT_EQ(sequence.times().size(), 10u);
  // ECO takes the scan with its pose as read.
  Config config;
  config.insert_policy = InsertPolicy::AllInBox;
  EgoOctree tree(config);
  const UpdateStats& stats = tree.update(frame.world_T_lidar, frame.cloud.view());
  EXPECT_EQ(stats.scan_points, frame.cloud.size());
  EXPECT_GT(tree.size(), 10000u);
  EXPECT_EQ(tree.check_invariants(), "");
}

TEST(RealBalm, LidarFramePosesWithoutCalib) {
  ECO_REQUIRE_DATASET(folder, "balm2_realworld_f20-99");
  const KittiSequence sequence(folder);  // no calib.txt: poses are taken as lidar poses
  EXPECT_FALSE(sequence.poses_were_camera_frame());
  ASSERT_EQ(sequence.size(), 80u);
  double posed = 0.0, identity = 0.0;
  for (std::size_t i = 0; i + 10 < sequence.size(); i += 10) {
    const KittiFrame a = sequence.read(i), b = sequence.read(i + 10);
    posed += test::voxel_overlap(a.cloud.points, a.world_T_lidar, b.cloud.points, b.world_T_lidar) / 7.0;
    identity += test::voxel_overlap(a.cloud.points, Eigen::Isometry3d::Identity(), b.cloud.points,
                                    Eigen::Isometry3d::Identity()) / 7.0;
  }
  std::cout << "balm2: mean overlap of scans 10 apart: poses " << posed << ", identity " << identity << "\n";
  EXPECT_GT(posed, 2.0 * identity);
}

}  // namespace
}  // namespace eco::io
