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

/// The poses --pose-topic gives: a topic's, taken to the clouds' frame through tf when the
/// recording links them, or tf's own chain from the fixed frame to the clouds' frame.
struct TopicPoses {
  PoseAtTime at_time;
  std::string said;  // what places the clouds, for the user
  std::string warning;
};

TopicPoses poses_from_tf(io::Recording& recording, const std::string& cloud_frame, const SourceOptions& options) {
  auto tree = std::make_shared<io::TransformTree>(recording.transform_tree());
  const std::string fixed = options.fixed_frame.empty() ? tree->root_of(cloud_frame) : options.fixed_frame;
  (void)tree->lookup(fixed, cloud_frame, 0.0);  // throws, naming the frames, when no chain joins them
  return {[tree, fixed, cloud_frame](double t) { return tree->lookup(fixed, cloud_frame, t); },
          "tf: " + tree->chain(fixed, cloud_frame), {}};
}

TopicPoses poses_from_topic(io::Recording& recording, const std::string& cloud_frame, const SourceOptions& options) {
  auto stream = std::make_shared<io::PoseStream>(recording.pose_track(options.pose_topic));
  const std::string child = stream->child_frame_id.empty() ? "the pose" : stream->child_frame_id;
  const std::string placed = options.pose_topic + " (" + child + " in " + stream->frame_id + ")";
  std::shared_ptr<io::TransformTree> tree;
  if (!stream->child_frame_id.empty() && stream->child_frame_id != cloud_frame && recording.has_tf()) {
    tree = std::make_shared<io::TransformTree>(recording.transform_tree());
    if (!tree->has_frame(stream->child_frame_id) || !tree->has_frame(cloud_frame) ||
        tree->root_of(stream->child_frame_id) != tree->root_of(cloud_frame)) {
      tree.reset();
    }
  }
  if (!tree) {
    const bool same_frame = stream->child_frame_id == cloud_frame;
    return {[stream](double t) { return io::pose_at(stream->track, t); }, placed,
            same_frame ? std::string()
                       : "the poses of " + placed + " are taken as the LiDAR's (" + cloud_frame +
                             "): no tf in the recording links them"};
  }
  const std::string child_frame = stream->child_frame_id;
  return {[stream, tree, child_frame, cloud_frame](double t) -> std::optional<Eigen::Isometry3d> {
            const std::optional<Eigen::Isometry3d> pose = io::pose_at(stream->track, t);
            const std::optional<Eigen::Isometry3d> extrinsic = tree->lookup(child_frame, cloud_frame, t);
            if (!pose || !extrinsic) return std::nullopt;
            return *pose * *extrinsic;
          },
          placed + ", then tf: " + tree->chain(child_frame, cloud_frame), {}};
}

OpenedSource open_recording(const fs::path& path, const SourceOptions& options) {
  io::Recording recording(path, options.recording);
  if (!options.poses.empty() && !options.pose_topic.empty()) {
    throw io::Error(path.string(), "", "--poses and --pose-topic both give poses: give one");
  }
  if (!options.fixed_frame.empty() && options.pose_topic != "tf") {
    throw io::Error(path.string(), "", "--fixed-frame " + options.fixed_frame + " is for --pose-topic tf");
  }
  OpenedSource out;
  const std::string cloud_frame = recording.size() > 0 ? recording.read(0).frame_id : std::string();  // also fixes the layout
  out.description = recording.describe() + (recording.layout() ? "; " + recording.layout()->describe() : "");
  if (!recording.damage().empty()) out.warnings.push_back(recording.damage());
  std::optional<CloudPoses> poses;
  if (!options.poses.empty()) {
    const io::PoseTrack track = io::read_pose_file(options.poses);
    poses = track.timed() ? CloudPoses{{}, [track](double t) { return io::pose_at(track, t); }, options.place_points}
                          : CloudPoses{track.poses, {}, false};
  } else if (!options.pose_topic.empty()) {
    const TopicPoses given = options.pose_topic == "tf" ? poses_from_tf(recording, cloud_frame, options)
                                                       : poses_from_topic(recording, cloud_frame, options);
    poses = CloudPoses{{}, given.at_time, options.place_points};
    out.description += "; poses: " + given.said;
    if (!given.warning.empty()) out.warnings.push_back(given.warning);
  }
  out.has_poses = poses.has_value();
  for (const io::RecordedTopic& t : recording.pose_topics()) out.pose_topics.push_back(t.name + " (" + t.type + ")");
  static const std::string kTf = "tf (/tf and /tf_static, from --fixed-frame to the clouds' frame)";
  if (recording.has_tf()) out.pose_topics.push_back(kTf);  // (a named string: GCC 12 warns falsely of a literal's)
  auto frames = std::make_unique<RecordingWorkload>(std::move(recording), std::move(poses));
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
