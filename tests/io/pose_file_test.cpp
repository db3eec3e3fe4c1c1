// Trajectory files as --poses takes them: KITTI's and TUM's told apart, TUM's quaternions and
// times read exactly, poses between two lines interpolated (against a hand-worked slerp), and every
// malformed line refused naming the file and line.

#include <eco/io/error.hpp>
#include <eco/io/pose_file.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace eco::io {
namespace {

TEST(PoseFile, KittiAndTumAreToldApart) {
  const PoseTrack kitti = parse_pose_file("1 0 0 5 0 1 0 6 0 0 1 7\n1 0 0 8 0 1 0 9 0 0 1 10\n", "poses.txt");
  ASSERT_EQ(kitti.poses.size(), 2u);
  EXPECT_FALSE(kitti.timed());
  EXPECT_EQ(kitti.poses[1].translation(), Eigen::Vector3d(8, 9, 10));

  // a quarter turn about z: q = (cos 45°, 0, 0, sin 45°)
  const double h = std::sqrt(0.5);
  const PoseTrack tum = parse_pose_file("# timestamp tx ty tz qx qy qz qw\n10.5 1 2 3 0 0 0 1\n\n11.5 3 2 3 0 0 " +
                                            std::to_string(h) + " " + std::to_string(h) + "\n",
                                        "traj.tum");
  ASSERT_EQ(tum.poses.size(), 2u);
  EXPECT_EQ(tum.times, (std::vector<double>{10.5, 11.5}));
  EXPECT_EQ(tum.poses[0].translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR((tum.poses[1].linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-6);
}

TEST(PoseFile, PosesBetweenTwoLinesAreInterpolated) {
  const double h = std::sqrt(0.5);
  const PoseTrack tum = parse_pose_file("10 0 0 0 0 0 0 1\n12 4 0 0 0 0 " + std::to_string(h) + " " + std::to_string(h) + "\n", "t");
  const std::optional<Eigen::Isometry3d> mid = pose_at(tum, 11.0);
  ASSERT_TRUE(mid);
  EXPECT_NEAR((mid->translation() - Eigen::Vector3d(2, 0, 0)).norm(), 0.0, 1e-12);
  const double yaw = std::atan2(mid->linear()(1, 0), mid->linear()(0, 0));
  EXPECT_NEAR(yaw, std::numbers::pi / 4, 1e-6);  // halfway through the quarter turn
  EXPECT_EQ(pose_at(tum, 10.0)->translation(), Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(pose_at(tum, 12.0)->translation(), Eigen::Vector3d(4, 0, 0));
  EXPECT_FALSE(pose_at(tum, 9.999));
  EXPECT_FALSE(pose_at(tum, 12.001));
  EXPECT_FALSE(pose_at(parse_pose_file("1 0 0 0 0 1 0 0 0 0 1 0\n", "k"), 0.0)) << "KITTI's lines have no times";
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_pose_file(text, "traj.txt");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PoseFile, BadLinesAreRefusedByLine) {
  EXPECT_EQ(error_of(""), "traj.txt: holds no poses");
  EXPECT_EQ(error_of("# only a comment\n"), "traj.txt: holds no poses");
  EXPECT_EQ(error_of("1 2 3\n"), "traj.txt: line 1: a pose line of 3 numbers: neither KITTI's 12 nor TUM's 8");
  EXPECT_EQ(error_of("0 0 0 0 0 0 0 1\n1 0 0 0 0 0 1\n"),
            "traj.txt: line 2: expected 8 numbers (TUM: timestamp tx ty tz qx qy qz qw), found 7");
  EXPECT_EQ(error_of("0 0 0 0 0 0 0 1\n1 0 x 0 0 0 0 1\n"), "traj.txt: line 2: malformed number 'x'");
  EXPECT_EQ(error_of("0 0 0 0 0 0 0 2\n"), "traj.txt: line 1: the quaternion's length is 2.000000, not 1");
  EXPECT_EQ(error_of("5 0 0 0 0 0 0 1\n4 0 0 0 0 0 0 1\n"), "traj.txt: line 2: time 4 goes back from the line before's");
  EXPECT_EQ(error_of("0 nan 0 0 0 0 0 1\n"), "traj.txt: line 1: value 2 is not finite");
  EXPECT_NE(error_of("1 0 0 5 0 1 0 6 0 0 1\n").find("line 1"), std::string::npos);
}

}  // namespace
}  // namespace eco::io
