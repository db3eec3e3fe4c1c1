#include <eco/io/kitti_sequence.hpp>

#include "io/files.hpp"
#include "io/number_text.hpp"

#include <cstdio>
#include <set>
#include <stdexcept>

namespace eco::io {

namespace fs = std::filesystem;

namespace {

std::string numbered(std::size_t index, const char* extension) {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu%s", index, extension);
  return name;
}

// The scan count: files NNNNNN.bin in velodyne/, numbered 0..n-1 without a gap.
std::size_t count_scans(const fs::path& velodyne) {
  detail::require_directory(velodyne);
  std::set<std::size_t> indices;
  for (const auto& entry : fs::directory_iterator(velodyne)) {
    const std::string name = entry.path().filename().string();
    if (name.size() != 10 || name.substr(6) != ".bin") continue;
    if (name.find_first_not_of("0123456789") != 6) continue;
    indices.insert(std::stoul(name.substr(0, 6)));
  }
  if (indices.empty()) throw Error(velodyne.string(), "", "holds no scans (NNNNNN.bin)");
  std::size_t expected = 0;
  for (const std::size_t index : indices) {
    if (index != expected) {
      throw Error((velodyne / numbered(expected, ".bin")).string(), "",
                  "is missing: scans must be numbered from 000000 without gaps");
    }
    ++expected;
  }
  return expected;
}

fs::path resolve(const fs::path& folder, const std::string& file) {
  const fs::path path(file);
  return path.is_absolute() ? path : folder / path;
}

}  // namespace

KittiSequence::KittiSequence(const fs::path& folder, const KittiOptions& options) : folder_(folder) {
  detail::require_directory(folder);
  scan_count_ = count_scans(folder / "velodyne");

  const fs::path poses_path = resolve(folder, options.poses_file);
  if (!options.require_poses && !fs::exists(poses_path)) {  // scans alone: frames read without poses
    has_poses_ = false;
    read_times(folder);
    return;
  }
  poses_ = read_kitti_poses(poses_path);
  if (poses_.size() < scan_count_) {
    throw Error(poses_path.string(), "", "has " + std::to_string(poses_.size()) + " poses for " +
                                             std::to_string(scan_count_) + " scans in velodyne/");
  }
  poses_.resize(scan_count_);

  const fs::path calib_path = folder / "calib.txt";
  const bool camera = options.pose_frame == PoseFrame::Camera ||
                      (options.pose_frame == PoseFrame::Auto && fs::exists(calib_path));
  if (camera) {
    velo_to_cam_ = read_kitti_calib(calib_path);
    for (auto& pose : poses_) pose = lidar_pose_from_camera(pose, *velo_to_cam_);
  }
  read_times(folder);
}

void KittiSequence::read_times(const fs::path& folder) {
  const fs::path times_path = folder / "times.txt";
  if (fs::exists(times_path)) {
    times_ = read_kitti_times(times_path);
    if (times_.size() < scan_count_) {
      throw Error(times_path.string(), "", "has " + std::to_string(times_.size()) + " times for " +
                                               std::to_string(scan_count_) + " scans");
    }
    times_.resize(scan_count_);
  }
}

void KittiSequence::check_index(std::size_t index) const {
  if (index >= scan_count_) {
    throw std::out_of_range("eco::io::KittiSequence: frame " + std::to_string(index) + " of " +
                            std::to_string(scan_count_));
  }
}

fs::path KittiSequence::scan_path(std::size_t index) const {
  return folder_ / "velodyne" / numbered(index, ".bin");
}

KittiFrame KittiSequence::read(std::size_t index) const {
  check_index(index);
  return {index, has_poses() ? poses_[index] : Eigen::Isometry3d::Identity(), read_kitti_scan(scan_path(index))};
}

bool KittiSequence::has_labels() const { return fs::is_directory(folder_ / "labels"); }

fs::path KittiSequence::label_path(std::size_t index) const {
  return folder_ / "labels" / numbered(index, ".label");
}

std::vector<std::uint32_t> KittiSequence::read_labels(std::size_t index) const {
  check_index(index);
  auto labels = read_kitti_labels(label_path(index));
  const std::size_t points = fs::file_size(scan_path(index)) / 16;
  if (labels.size() != points) {
    throw Error(label_path(index).string(), "", "has " + std::to_string(labels.size()) +
                                                     " labels for the " + std::to_string(points) +
                                                     " points of " + scan_path(index).string());
  }
  return labels;
}

KittiWriter::KittiWriter(const fs::path& folder, std::optional<Eigen::Isometry3d> velo_to_cam)
    : folder_(folder), velo_to_cam_(std::move(velo_to_cam)) {
  std::error_code ec;
  fs::create_directories(folder / "velodyne", ec);
  if (ec) throw Error((folder / "velodyne").string(), "", "cannot create: " + ec.message());
  if (velo_to_cam_) write_kitti_calib(folder / "calib.txt", *velo_to_cam_);
  poses_.open(folder / "poses.txt", std::ios::trunc);
  times_.open(folder / "times.txt", std::ios::trunc);
  if (!poses_ || !times_) throw Error(folder.string(), "", "cannot create poses.txt and times.txt");
}

void KittiWriter::write(const Eigen::Isometry3d& world_T_lidar, const PointCloud& cloud,
                        std::span<const std::uint32_t> labels, std::optional<double> time) {
  if (!labels.empty() && labels.size() != cloud.size()) {
    throw std::invalid_argument("eco::io::KittiWriter: " + std::to_string(labels.size()) +
                                " labels for " + std::to_string(cloud.size()) + " points");
  }
  write_kitti_scan(folder_ / "velodyne" / numbered(frames_, ".bin"), cloud);
  if (!labels.empty()) {
    fs::create_directories(folder_ / "labels");
    write_kitti_labels(folder_ / "labels" / numbered(frames_, ".label"), labels);
  }
  const Eigen::Isometry3d pose = velo_to_cam_ ? camera_pose_from_lidar(world_T_lidar, *velo_to_cam_) : world_T_lidar;
  poses_ << format_kitti_pose(pose) << '\n';
  times_ << detail::number_text(time.value_or(0.1 * static_cast<double>(frames_))) << '\n';
  poses_.flush();
  times_.flush();
  if (!poses_ || !times_) throw Error(folder_.string(), "", "writing poses.txt or times.txt failed");
  ++frames_;
}

}  // namespace eco::io
