#include <eco/workloads/scan_source.hpp>

#include "cloud_folder_workload.hpp"
#include "recording_workload.hpp"

#include <eco/io/error.hpp>
#include <eco/io/kitti_sequence.hpp>
#include <eco/io/pose_file.hpp>
#include <eco/workloads/dynamic_workload.hpp>
#include <eco/workloads/frame_window.hpp>

namespace eco::workloads {
namespace {

namespace fs = std::filesystem;

std::optional<io::PoseTrack> track_of(const SourceOptions& options) {
  if (options.poses.empty()) return std::nullopt;
  return io::read_pose_file(options.poses);
}

OpenedSource open_kitti(const fs::path& folder, const SourceOptions& options) {
  io::KittiOptions read;
  read.require_poses = false;  // scans alone run: an odometry estimates their poses
  if (!options.poses.empty()) {
    read.poses_file = fs::absolute(options.poses).string();
    if (!fs::is_regular_file(read.poses_file)) throw io::Error(options.poses, "", "no such poses file");
  }
  io::KittiSequence sequence(folder, read);
  OpenedSource out;
  out.has_poses = sequence.has_poses();
  out.velo_to_cam = sequence.velo_to_cam();
  out.description = folder.string() + " (KITTI layout): " + std::to_string(sequence.size()) + " scans";
  if (out.has_poses && !out.velo_to_cam) {
    out.warnings.push_back("the poses are taken as the LiDAR's: there is no calib.txt beside them (KITTI's own poses are "
                           "camera 0's: put the sequence's calib.txt in " + folder.string() + ")");
  }
  out.frames = std::make_unique<DynamicWorkload>(std::move(sequence));
  return out;
}

OpenedSource open_recording(const fs::path& path, const SourceOptions& options) {
  io::Recording recording(path, options.recording);
  if (!options.poses.empty() && !options.pose_topic.empty()) {
    throw io::Error(path.string(), "", "--poses and --pose-topic both give poses: give one");
  }
  std::optional<io::PoseTrack> track = track_of(options);
  std::string placed;
  if (!options.pose_topic.empty()) track = recording.pose_track(options.pose_topic, &placed);
  OpenedSource out;
  out.has_poses = track.has_value();
  if (recording.size() > 0) (void)recording.read(0);  // the first cloud fixes how its points are read
  out.description = recording.describe() + (recording.layout() ? "; " + recording.layout()->describe() : "");
  if (!recording.damage().empty()) out.warnings.push_back(recording.damage());
  if (!placed.empty()) {
    out.warnings.push_back("the poses of " + placed + " on " + options.pose_topic +
                           " are taken as the LiDAR's: no extrinsic (TF) between them is applied");
  }
  for (const io::RecordedTopic& t : recording.pose_topics()) out.pose_topics.push_back(t.name + " (" + t.type + ")");
  auto frames = std::make_unique<RecordingWorkload>(std::move(recording), std::move(track));
  if (frames->outside_poses() > 0) {
    out.warnings.push_back(std::to_string(frames->outside_poses()) + " clouds lie outside the span of " +
                           (options.poses.empty() ? options.pose_topic : options.poses) + " and are left out");
  }
  out.frames = std::move(frames);
  return out;
}

}  // namespace

namespace {

/// What `path` holds, every frame of it.
OpenedSource open_by_kind(const fs::path& path, const SourceOptions& options) {
  if (!fs::exists(path)) throw io::Error(path.string(), "", "no such file or folder");
  if (io::Recording::is_recording(path)) return open_recording(path, options);
  if (fs::is_directory(path / "velodyne")) return open_kitti(path, options);
  if (CloudFolderWorkload::holds_clouds(path)) {
    OpenedSource out;
    auto frames = std::make_unique<CloudFolderWorkload>(path, track_of(options));
    out.has_poses = !options.poses.empty();
    out.description = path.string() + " (point-cloud files): " + std::to_string(frames->size()) + " scans in name order";
    out.frames = std::move(frames);
    return out;
  }
  throw io::Error(path.string(), "", "is none of what --data reads: a KITTI-layout folder (velodyne/), a folder of .pcd, "
                                     ".ply or .bin files, an .mcap, .db3 or .bag file, a rosbag2 folder (metadata.yaml) "
                                     "or a folder of ROS 1 bags");
}

}  // namespace

OpenedSource open_source(const fs::path& path, const SourceOptions& options) {
  OpenedSource opened = open_by_kind(path, options);
  opened.frames = frame_window(std::move(opened.frames), options.start);
  return opened;
}

}  // namespace eco::workloads
