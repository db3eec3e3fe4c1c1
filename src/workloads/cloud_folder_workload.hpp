#pragma once
// A folder of point-cloud files (.pcd, .ply, KITTI's .bin) taken in name order, a scan a file,
// read when asked for; poses from a trajectory file when one is given.

#include <eco/io/pose_file.hpp>
#include <eco/workloads/workload.hpp>

#include <filesystem>
#include <optional>
#include <vector>

namespace eco::workloads {

class CloudFolderWorkload final : public Workload {
 public:
  /// Throws eco::io::Error when the folder holds no such file, or `track` has fewer poses.
  CloudFolderWorkload(const std::filesystem::path& folder, std::optional<io::PoseTrack> track);

  /// Whether `folder` holds at least one .pcd, .ply or .bin file.
  [[nodiscard]] static bool holds_clouds(const std::filesystem::path& folder);

  [[nodiscard]] std::size_t size() const override { return files_.size(); }
  [[nodiscard]] WorkloadFrame frame(std::size_t index) const override;
  [[nodiscard]] Eigen::Isometry3d pose(std::size_t index) const override;
  [[nodiscard]] std::string name() const override { return "dynamic"; }

 private:
  std::vector<std::filesystem::path> files_;
  std::optional<io::PoseTrack> track_;
};

}  // namespace eco::workloads
