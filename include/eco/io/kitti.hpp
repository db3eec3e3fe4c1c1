#pragma once
/// @file kitti.hpp
/// The files of a KITTI odometry sequence, one at a time: scans (`velodyne/NNNNNN.bin`, float32
/// x, y, z, reflectance), SemanticKITTI labels (`labels/NNNNNN.label`, uint32), poses
/// (`poses.txt`, 3x4 row-major per line), calibration (`calib.txt`, its `Tr:` line) and times.
/// For whole folders see kitti_sequence.hpp.

#include <eco/io/error.hpp>
#include <eco/io/point_cloud.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace eco::io {

/// Every reader throws eco::io::Error naming the file and the line or byte offset at fault.
/// parse_* take the bytes in memory; `source` names them in errors.

[[nodiscard]] PointCloud read_kitti_scan(const std::filesystem::path& path);
[[nodiscard]] PointCloud parse_kitti_scan(std::string_view bytes, const std::string& source);
/// Writes reflectance 0 when the cloud has no intensities.
void write_kitti_scan(const std::filesystem::path& path, const PointCloud& cloud);

[[nodiscard]] std::vector<std::uint32_t> read_kitti_labels(const std::filesystem::path& path);
[[nodiscard]] std::vector<std::uint32_t> parse_kitti_labels(std::string_view bytes,
                                                            const std::string& source);
void write_kitti_labels(const std::filesystem::path& path, std::span<const std::uint32_t> labels);

/// One pose per non-empty line. Rotations are re-orthonormalised (text keeps ~6 digits); a line
/// whose rotation is more than 1e-3 from orthonormal, or holds a non-finite value, is an error.
[[nodiscard]] std::vector<Eigen::Isometry3d> read_kitti_poses(const std::filesystem::path& path);
[[nodiscard]] std::vector<Eigen::Isometry3d> parse_kitti_poses(std::string_view text,
                                                               const std::string& source);
/// Shortest round-trip decimal form: reading it back gives the same doubles.
void write_kitti_poses(const std::filesystem::path& path, std::span<const Eigen::Isometry3d> poses);
[[nodiscard]] std::string format_kitti_pose(const Eigen::Isometry3d& pose);

/// The velodyne-to-camera transform: the `Tr:` line (or `Tr_velo_to_cam:`) of calib.txt.
[[nodiscard]] Eigen::Isometry3d read_kitti_calib(const std::filesystem::path& path);
[[nodiscard]] Eigen::Isometry3d parse_kitti_calib(std::string_view text, const std::string& source);
void write_kitti_calib(const std::filesystem::path& path, const Eigen::Isometry3d& velo_to_cam);

/// times.txt: one timestamp in seconds per non-empty line.
[[nodiscard]] std::vector<double> read_kitti_times(const std::filesystem::path& path);
[[nodiscard]] std::vector<double> parse_kitti_times(std::string_view text, const std::string& source);

/// KITTI's velodyne-to-camera transform for sequences 00-02, a realistic default for writers.
[[nodiscard]] Eigen::Isometry3d kitti_velo_to_cam();

/// KITTI gives camera-0 poses; the lidar's is Tr^-1 * P * Tr (and back: Tr * L * Tr^-1).
[[nodiscard]] Eigen::Isometry3d lidar_pose_from_camera(const Eigen::Isometry3d& camera_pose,
                                                       const Eigen::Isometry3d& velo_to_cam);
[[nodiscard]] Eigen::Isometry3d camera_pose_from_lidar(const Eigen::Isometry3d& lidar_pose,
                                                       const Eigen::Isometry3d& velo_to_cam);

/// SemanticKITTI label ids (lower 16 bits of a label) that ECO's simulator writes.
namespace label {
inline constexpr std::uint32_t kUnlabeled = 0, kCar = 10, kRoad = 40, kSidewalk = 48,
                               kBuilding = 50, kVegetation = 70, kTrunk = 71, kPole = 80,
                               kMovingCar = 252;
/// SemanticKITTI marks moving objects with ids 252 and above.
[[nodiscard]] constexpr bool is_moving(std::uint32_t value) { return (value & 0xFFFFu) >= 252u; }
}  // namespace label

}  // namespace eco::io
