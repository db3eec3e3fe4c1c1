#include "cloud_folder_workload.hpp"

#include <eco/io/error.hpp>
#include <eco/io/kitti.hpp>
#include <eco/io/pcd.hpp>
#include <eco/io/ply.hpp>

#include <algorithm>

namespace eco::workloads {
namespace {

namespace fs = std::filesystem;

bool is_cloud_file(const fs::path& path) {
  const std::string ext = path.extension().string();
  return ext == ".pcd" || ext == ".ply" || ext == ".bin";
}

std::vector<fs::path> cloud_files(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.is_regular_file() && is_cloud_file(entry.path())) files.push_back(entry.path());
  }
  std::ranges::sort(files);
  return files;
}

}  // namespace

bool CloudFolderWorkload::holds_clouds(const fs::path& folder) {
  return fs::is_directory(folder) && !cloud_files(folder).empty();
}

CloudFolderWorkload::CloudFolderWorkload(const fs::path& folder, std::optional<io::PoseTrack> track)
    : files_(cloud_files(folder)), track_(std::move(track)) {
  if (files_.empty()) throw io::Error(folder.string(), "", "holds no .pcd, .ply or .bin file");
  if (track_ && track_->poses.size() < files_.size()) {
    throw io::Error(folder.string(), "", std::to_string(track_->poses.size()) + " poses for " + std::to_string(files_.size()) +
                                             " point-cloud files: one pose a file, in name order");
  }
}

WorkloadFrame CloudFolderWorkload::frame(std::size_t index) const {
  const fs::path& file = files_.at(index);
  const std::string ext = file.extension().string();
  io::PointCloud cloud = ext == ".pcd" ? io::read_pcd(file) : ext == ".ply" ? io::read_ply(file) : io::read_kitti_scan(file);
  WorkloadFrame out;
  out.index = index;
  out.world_T_sensor = pose(index);
  out.points = std::move(cloud.points);
  out.intensities = std::move(cloud.intensity);
  out.time = track_ && track_->timed() ? track_->times[index] : double(index) / 10.0;
  return out;
}

Eigen::Isometry3d CloudFolderWorkload::pose(std::size_t index) const {
  if (index >= files_.size()) throw std::out_of_range("frame " + std::to_string(index) + " of " + std::to_string(files_.size()));
  return track_ ? track_->poses[index] : Eigen::Isometry3d::Identity();
}

}  // namespace eco::workloads
