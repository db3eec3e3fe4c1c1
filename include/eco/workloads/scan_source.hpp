#pragma once
/// @file scan_source.hpp
/// What `--data PATH` names, opened as a stream of frames, chosen by what the path holds:
///
///   a KITTI-layout folder        velodyne/*.bin, poses.txt (or --poses), calib.txt, times.txt
///   a rosbag2 folder             metadata.yaml beside .db3 or .mcap files (io::Recording)
///   an .mcap, .db3 or .bag file  (io::Recording); a folder of ROS 1 bags
///   a folder of point clouds     .pcd, .ply, .bin files in name order, poses from --poses
///
///   eco::workloads::OpenedSource in = eco::workloads::open_source("run.mcap", {});
///   for (std::size_t i = 0; i < in.frames->size(); ++i) {
///     const eco::workloads::WorkloadFrame f = in.frames->frame(i);   // pose (if any), points, times
///   }

#include <eco/io/recording.hpp>
#include <eco/workloads/workload.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace eco::workloads {

struct SourceOptions {
  /// A trajectory (KITTI or TUM, io/pose_file.hpp): KITTI's, one pose per scan or cloud in order;
  /// TUM's on a recording, interpolated at each cloud's stamp (clouds outside its span skipped).
  /// For a KITTI folder it replaces the folder's poses.txt.
  std::string poses;
  io::RecordingOptions recording;  ///< --topic, --time-field, --time-unit
  /// A recording's topic of poses (nav_msgs/Odometry, geometry_msgs/PoseStamped or
  /// TransformStamped), interpolated at each cloud's stamp as a TUM file would be, the recording's
  /// tf between the poses' frame and the clouds' applied when it has one; or "tf": the clouds'
  /// frame in `fixed_frame` through /tf and /tf_static.
  std::string pose_topic;
  std::string fixed_frame;  ///< with pose_topic "tf"; empty: the root of the clouds' frame's tree
  /// With timed poses and per-point times, each point placed by the pose at its own time (the
  /// sweep's smear taken out); off where the poses are only a reference, as for an odometry.
  bool place_points = true;
  std::size_t start = 0;  ///< the first frame taken (`--start`): the frames are numbered from it
};

struct OpenedSource {
  std::unique_ptr<Workload> frames;
  bool has_poses = false;  ///< false: every frame's pose is the identity (an odometry estimates them)
  std::optional<Eigen::Isometry3d> velo_to_cam;  ///< KITTI's camera-frame poses were turned into the LiDAR's
  std::string description;                        ///< one line: what was opened, and how it is read
  std::vector<std::string> warnings;              ///< what the user should know (a cut file, a guess)
  std::vector<std::string> pose_topics;           ///< a recording's topics of poses, for --pose-topic

  [[nodiscard]] std::size_t size() const { return frames ? frames->size() : 0; }
};

/// Opens `path`. Throws eco::io::Error naming the path and what it holds when it is none of the
/// above, or naming the file, byte or topic at fault.
[[nodiscard]] OpenedSource open_source(const std::filesystem::path& path, const SourceOptions& options);

}  // namespace eco::workloads
