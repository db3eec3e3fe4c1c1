#pragma once
/// @file recording.hpp
/// A robot's recording read as a stream of LiDAR scans: an MCAP file, a rosbag2 folder
/// (metadata.yaml beside its .db3 or .mcap files) or a single .db3 file. The clouds of one
/// sensor_msgs/PointCloud2 topic are indexed when it opens and decoded one at a time when asked
/// for, so that a recording of any length is streamed, not loaded.
///
///   eco::io::Recording bag("run.mcap", {.topic = "/ouster/points"});
///   for (std::size_t i = 0; i < bag.size(); ++i) {
///     const eco::io::RecordedScan scan = bag.read(i);   // points in the cloud's frame, times
///   }

#include <eco/io/point_cloud2.hpp>
#include <eco/io/pose_file.hpp>
#include <eco/io/transform_tree.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace eco::io {

namespace detail {
class MessageStore;
struct StoredMessage;
}  // namespace detail

struct RecordingOptions {
  std::string topic;  ///< empty: the only sensor_msgs/PointCloud2 topic
  TimeOptions time;
};

struct RecordedTopic {
  std::string name, type;
  std::size_t messages = 0;
};

struct RecordedScan {
  std::size_t index = 0;
  std::int64_t stamp_ns = 0;  ///< the cloud's header stamp
  std::string frame_id;
  DecodedCloud cloud;
};

/// A topic's poses: where `child_frame_id` was in `frame_id` (PoseStamped names no child).
struct PoseStream {
  PoseTrack track;
  std::string frame_id, child_frame_id;
};

class Recording {
 public:
  /// Opens `path` and indexes its cloud topic. Throws eco::io::Error naming the file (and byte)
  /// for a damaged or unknown container, and naming every topic with its type and count when the
  /// topic is missing or several clouds topics leave the choice open.
  Recording(const std::filesystem::path& path, const RecordingOptions& options);
  ~Recording();
  Recording(Recording&&) noexcept;
  Recording& operator=(Recording&&) noexcept;

  /// Whether `path` looks like a recording this class reads (by name: .mcap, .db3, or a folder
  /// with metadata.yaml).
  [[nodiscard]] static bool is_recording(const std::filesystem::path& path);

  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] const std::string& topic() const { return topic_; }
  [[nodiscard]] const std::vector<RecordedTopic>& topics() const { return topics_; }
  /// Cloud `index` (< size()), decoded; the first read fixes the layout (CloudDecoder).
  [[nodiscard]] RecordedScan read(std::size_t index);
  /// Cloud `index`'s header stamp, read without decoding its points.
  [[nodiscard]] std::int64_t stamp_ns(std::size_t index);
  /// The cloud's log time, without reading it.
  [[nodiscard]] std::int64_t log_time_ns(std::size_t index) const;
  [[nodiscard]] const std::optional<CloudLayout>& layout() const { return decoder_.layout(); }
  /// Why the recording ends early (a cut file and where), or empty.
  [[nodiscard]] const std::string& damage() const { return damage_; }
  /// "path (MCAP), topic /points: 120 clouds"
  [[nodiscard]] std::string describe() const;

  /// The topics whose messages hold poses (nav_msgs/Odometry, geometry_msgs/PoseStamped,
  /// geometry_msgs/TransformStamped).
  [[nodiscard]] std::vector<RecordedTopic> pose_topics() const;
  /// Every pose on `topic`, in stamp order, as a timed trajectory (at the messages' header
  /// stamps) with the frames it places. Throws eco::io::Error naming the topic when it is missing,
  /// holds no pose type, or is empty.
  [[nodiscard]] PoseStream pose_track(const std::string& topic);
  /// Whether the recording has tf's topics (/tf, /tf_static).
  [[nodiscard]] bool has_tf() const;
  /// The frames /tf and /tf_static give (tf2_msgs/TFMessage), every transform of the recording.
  /// Throws eco::io::Error naming the topic and message of a transform that breaks the tree, and
  /// naming the topics when there is no tf topic.
  [[nodiscard]] TransformTree transform_tree();

 private:
  [[nodiscard]] PointCloud2 parsed(std::size_t index, const std::string& source);
  [[nodiscard]] std::vector<const RecordedTopic*> tf_topics() const;

  std::string name_;
  std::string kind_;
  std::vector<std::unique_ptr<detail::MessageStore>> parts_;
  std::vector<detail::StoredMessage> clouds_;
  std::vector<int> encodings_;  // detail::Encoding of the topic, a part each
  std::vector<RecordedTopic> topics_;
  std::string topic_;
  std::string damage_;
  CloudDecoder decoder_;
};

/// The topics as an error lists them: "  /points  sensor_msgs/msg/PointCloud2  120 messages", a line each.
[[nodiscard]] std::string list_topics(const std::vector<RecordedTopic>& topics);

}  // namespace eco::io
