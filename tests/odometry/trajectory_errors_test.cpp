// The trajectory errors against figures worked out by hand: a perfect estimate, one moved
// rigidly as a whole, one stretched by a known scale, one turning at a known rate off the
// reference; and mismatched lists refused.

#include <eco/odometry/trajectory_errors.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace eco::odometry {
namespace {

/// A straight drive along x, 1 m a frame: segment ends fall on whole frames.
std::vector<Eigen::Isometry3d> straight(std::size_t frames) {
  std::vector<Eigen::Isometry3d> poses(frames, Eigen::Isometry3d::Identity());
  for (std::size_t i = 0; i < frames; ++i) poses[i].translation().x() = double(i);
  return poses;
}

/// A drive along a gentle curve, 1 m a frame.
std::vector<Eigen::Isometry3d> curve(std::size_t frames) {
  std::vector<Eigen::Isometry3d> poses;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  step.translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
  step.linear() = Eigen::AngleAxisd(0.002, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (std::size_t i = 0; i < frames; ++i) {
    poses.push_back(pose);
    pose = pose * step;
  }
  return poses;
}

TEST(TrajectoryErrors, APerfectEstimateHasNoError) {
  const std::vector<Eigen::Isometry3d> reference = curve(900);
  const TrajectoryErrors e = trajectory_errors(reference, reference);
  EXPECT_EQ(e.frames, 900u);
  EXPECT_NEAR(e.path_length, 899.0, 1e-9);
  ASSERT_EQ(e.by_length.size(), 8u);  // 100 ... 800 m all fit in 899 m
  EXPECT_EQ(e.by_length.front().segments, 80u);  // starts 0, 10, ..., 790 reach 100 m on by 899 m
  EXPECT_EQ(e.by_length.back().segments, 10u);   // starts 0, 10, ..., 90 reach 800 m on
  EXPECT_NEAR(e.translation_pct, 0.0, 1e-9);
  EXPECT_NEAR(e.rotation_deg_per_100m, 0.0, 1e-5);
  EXPECT_NEAR(e.ate_rmse, 0.0, 1e-9);
  EXPECT_NEAR(e.rpe_translation_rmse, 0.0, 1e-12);
}

TEST(TrajectoryErrors, AnEstimateMovedAsAWholeHasNoRelativeErrorAndNoneAfterAlignment) {
  const std::vector<Eigen::Isometry3d> reference = curve(300);
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  offset.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.1, 0.2, 1.0).normalized()).toRotationMatrix();
  offset.translation() = Eigen::Vector3d(5, -7, 2);
  std::vector<Eigen::Isometry3d> estimate;
  for (const Eigen::Isometry3d& p : reference) estimate.push_back(offset * p);
  const TrajectoryErrors e = trajectory_errors(estimate, reference);
  EXPECT_NEAR(e.ate_rmse, 0.0, 1e-6);
  EXPECT_NEAR(e.translation_pct, 0.0, 1e-9);
  EXPECT_NEAR(e.rpe_translation_rmse, 0.0, 1e-9);
  EXPECT_NEAR(e.rpe_rotation_rmse_deg, 0.0, 1e-5);
}

TEST(TrajectoryErrors, AStretchedEstimateErrsByItsScaleOnEverySegment) {
  const std::vector<Eigen::Isometry3d> reference = straight(500);
  std::vector<Eigen::Isometry3d> estimate = reference;
  for (Eigen::Isometry3d& p : estimate) p.translation() *= 1.01;  // 1 % too long
  const TrajectoryErrors e = trajectory_errors(estimate, reference);
  ASSERT_EQ(e.by_length.size(), 4u);  // 100 ... 400 m in 499 m
  EXPECT_NEAR(e.translation_pct, 1.0, 1e-9);
  for (const SegmentError& s : e.by_length) {
    EXPECT_NEAR(s.translation_pct, 1.0, 1e-9) << s.length << " m";
    EXPECT_NEAR(s.rotation_deg_per_100m, 0.0, 1e-5);
  }
  EXPECT_NEAR(e.rpe_translation_rmse, 0.01, 1e-6);  // 1 cm of each 1 m step
}

TEST(TrajectoryErrors, AnEstimateThatTurnsOffTheReferenceErrsByItsRate) {
  const std::vector<Eigen::Isometry3d> reference = straight(250);
  std::vector<Eigen::Isometry3d> estimate;
  const double extra = 0.001;  // rad a frame, about the vertical
  for (std::size_t i = 0; i < reference.size(); ++i) {
    Eigen::Isometry3d drift = Eigen::Isometry3d::Identity();
    drift.linear() = Eigen::AngleAxisd(extra * double(i), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    estimate.push_back(reference[i] * drift);  // the heading drifts, the positions do not
  }
  const TrajectoryErrors e = trajectory_errors(estimate, reference);
  ASSERT_EQ(e.by_length.size(), 2u);
  const double per_100m = extra * 100.0 * 180.0 / std::numbers::pi;  // 100 frames a segment of 100 m
  EXPECT_NEAR(e.by_length[0].rotation_deg_per_100m, per_100m, 1e-6);
  EXPECT_NEAR(e.by_length[1].rotation_deg_per_100m, per_100m, 1e-6);  // 200 frames, 200 m: the same rate
  EXPECT_NEAR(e.rpe_rotation_rmse_deg, extra * 180.0 / std::numbers::pi, 1e-9);
  EXPECT_NEAR(e.ate_rmse, 0.0, 1e-9);
}

TEST(TrajectoryErrors, ListsOfOtherLengthsOrTooShortAreRefused) {
  const std::vector<Eigen::Isometry3d> reference = curve(20);
  EXPECT_THROW((void)trajectory_errors(curve(19), reference), std::invalid_argument);
  EXPECT_THROW((void)trajectory_errors(curve(1), curve(1)), std::invalid_argument);
  const TrajectoryErrors short_drive = trajectory_errors(reference, reference);
  EXPECT_TRUE(short_drive.by_length.empty());  // 19 m: no 100 m segment
  EXPECT_EQ(short_drive.translation_pct, 0.0);
}

}  // namespace
}  // namespace eco::odometry
