#pragma once
/// @file kitti_sequence.hpp
/// A KITTI odometry folder read one frame at a time (only the scan asked for is in memory), and
/// written one frame at a time.
///
///   folder/velodyne/000000.bin ...   scans, numbered from 0 without gaps
///   folder/poses.txt                 one 3x4 pose per scan (more lines are allowed)
///   folder/calib.txt                 `Tr:` velodyne -> camera 0, when poses are camera-frame
///   folder/times.txt                 optional, seconds
///   folder/labels/000000.label ...   optional, SemanticKITTI labels (ECO's simulator writes them)

#include <eco/io/kitti.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace eco::io {

/// Which frame poses.txt is written in.
enum class PoseFrame {
  Auto,    ///< camera-0 frame if calib.txt exists (KITTI), else the lidar frame (e.g. BALM)
  Camera,  ///< camera-0 frame: lidar pose = Tr^-1 * P * Tr; calib.txt is required
  Lidar,   ///< already the lidar's pose (world_T_lidar); calib.txt is not read
};

struct KittiOptions {
  PoseFrame pose_frame = PoseFrame::Auto;
  std::string poses_file = "poses.txt";  ///< relative to the folder, or absolute
  /// False: a folder whose poses file does not exist is read all the same, without poses
  /// (has_poses() false, every frame's pose the identity); one that exists is still checked.
  bool require_poses = true;
};

struct KittiFrame {
  std::size_t index = 0;
  Eigen::Isometry3d world_T_lidar = Eigen::Isometry3d::Identity();
  PointCloud cloud;  ///< lidar frame, with reflectance
};

class KittiSequence {
 public:
  /// Reads the folder's listing, poses, calibration and times (not the scans). Throws
  /// eco::io::Error for a missing folder, missing or gapped scans, fewer poses than scans, or
  /// a missing `Tr:` when the poses are camera-frame.
  explicit KittiSequence(const std::filesystem::path& folder, const KittiOptions& options = {});

  [[nodiscard]] std::size_t size() const { return scan_count_; }
  [[nodiscard]] const std::filesystem::path& folder() const { return folder_; }
  /// world_T_lidar of every scan (empty without poses).
  [[nodiscard]] std::span<const Eigen::Isometry3d> poses() const { return poses_; }
  [[nodiscard]] bool has_poses() const { return has_poses_; }
  [[nodiscard]] bool poses_were_camera_frame() const { return velo_to_cam_.has_value(); }
  [[nodiscard]] const std::optional<Eigen::Isometry3d>& velo_to_cam() const { return velo_to_cam_; }
  /// Seconds from times.txt, or empty if there is none.
  [[nodiscard]] std::span<const double> times() const { return times_; }

  /// Loads scan `index` (throws std::out_of_range past the end, eco::io::Error for a bad file).
  [[nodiscard]] KittiFrame read(std::size_t index) const;
  [[nodiscard]] std::filesystem::path scan_path(std::size_t index) const;

  [[nodiscard]] bool has_labels() const;
  [[nodiscard]] std::filesystem::path label_path(std::size_t index) const;
  /// Labels of scan `index`; throws unless there is exactly one per point of the scan.
  [[nodiscard]] std::vector<std::uint32_t> read_labels(std::size_t index) const;

 private:
  void check_index(std::size_t index) const;
  void read_times(const std::filesystem::path& folder);

  std::filesystem::path folder_;
  std::size_t scan_count_ = 0;
  std::vector<Eigen::Isometry3d> poses_;
  bool has_poses_ = true;
  std::optional<Eigen::Isometry3d> velo_to_cam_;
  std::vector<double> times_;
};

/// Writes a sequence frame by frame in the same layout. With `velo_to_cam`, poses.txt holds
/// camera-frame poses and calib.txt is written (KITTI's convention); without, lidar poses.
class KittiWriter {
 public:
  explicit KittiWriter(const std::filesystem::path& folder,
                       std::optional<Eigen::Isometry3d> velo_to_cam = kitti_velo_to_cam());

  /// Appends frame size(): the scan, its pose, and optionally labels (one per point) and a time.
  void write(const Eigen::Isometry3d& world_T_lidar, const PointCloud& cloud,
             std::span<const std::uint32_t> labels = {}, std::optional<double> time = {});
  [[nodiscard]] std::size_t size() const { return frames_; }

 private:
  std::filesystem::path folder_;
  std::optional<Eigen::Isometry3d> velo_to_cam_;
  std::ofstream poses_;
  std::ofstream times_;
  std::size_t frames_ = 0;
};

}  // namespace eco::io
