#include <eco/io/recording.hpp>

#include "io/ros/mcap_store.hpp"
#include "io/ros/pose_messages.hpp"
#include "io/ros/ros1_bag_store.hpp"
#include "io/ros/sqlite_store.hpp"

#include <eco/io/error.hpp>

#include <algorithm>
#include <cstdio>

namespace eco::io {
namespace {

namespace fs = std::filesystem;

bool is_cloud_type(const std::string& type) {
  return type == "sensor_msgs/msg/PointCloud2" || type == "sensor_msgs/PointCloud2";
}

/// A folder's files with one of `extensions`, in name order: a split recording's parts in turn.
std::vector<fs::path> files_in(const fs::path& folder, std::initializer_list<const char*> extensions) {
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && std::ranges::find(extensions, ext) != extensions.end()) files.push_back(entry.path());
  }
  std::ranges::sort(files);
  return files;
}

/// A folder of ROS 1 bags only (a split recording: name_0.bag, name_1.bag, ...).
bool holds_ros1_bags(const fs::path& folder) {
  return fs::is_directory(folder) && !files_in(folder, {".bag"}).empty() &&
         files_in(folder, {".bag"}).size() == files_in(folder, {".bag", ".mcap", ".db3", ".bin", ".pcd", ".ply"}).size();
}

std::unique_ptr<detail::MessageStore> open_store(const fs::path& file) {
  if (file.extension() == ".db3") return std::make_unique<detail::SqliteStore>(file);
  if (file.extension() == ".bag") return std::make_unique<detail::Ros1BagStore>(file);
  return std::make_unique<detail::McapStore>(file);
}

}  // namespace

std::string list_topics(const std::vector<RecordedTopic>& topics) {
  std::string text;
  for (const RecordedTopic& t : topics) {
    char line[512];
    std::snprintf(line, sizeof line, "  %-30s %-32s %zu messages\n", t.name.c_str(), t.type.c_str(), t.messages);
    text += line;
  }
  return text.empty() ? "  (no topics)\n" : text;
}

bool Recording::is_recording(const fs::path& path) {
  const std::string ext = path.extension().string();
  if (fs::is_directory(path)) return fs::is_regular_file(path / "metadata.yaml") || holds_ros1_bags(path);
  return ext == ".mcap" || ext == ".db3" || ext == ".bag";
}

Recording::Recording(const fs::path& path, const RecordingOptions& options) : name_(path.string()), decoder_(options.time) {
  std::vector<fs::path> files;
  if (fs::is_directory(path) && holds_ros1_bags(path)) {
    files = files_in(path, {".bag"});
    kind_ = "ROS 1 bags, " + std::to_string(files.size()) + " file" + (files.size() > 1 ? "s" : "");
  } else if (fs::is_directory(path)) {
    if (!fs::is_regular_file(path / "metadata.yaml")) throw Error(name_, "", "is not a rosbag2 folder (no metadata.yaml)");
    files = files_in(path, {".mcap", ".db3"});
    if (files.empty()) throw Error(name_, "", "has metadata.yaml but no .mcap or .db3 file");
    kind_ = "rosbag2 folder, " + std::to_string(files.size()) + " file" + (files.size() > 1 ? "s" : "");
  } else {
    if (!fs::exists(path)) throw Error(name_, "", "no such file or folder");
    files = {path};
    kind_ = path.extension() == ".db3" ? "rosbag2 SQLite" : path.extension() == ".bag" ? "ROS 1 bag" : "MCAP";
  }
  for (const fs::path& file : files) {
    parts_.push_back(open_store(file));
    for (const detail::TopicInfo& t : parts_.back()->topics()) {
      const auto same = std::ranges::find(topics_, t.name, &RecordedTopic::name);
      if (same != topics_.end()) {
        same->messages += t.messages;
      } else {
        topics_.push_back({t.name, t.type, t.messages});
      }
    }
    if (damage_.empty()) damage_ = parts_.back()->damage();
  }

  if (options.topic.empty()) {
    std::vector<const RecordedTopic*> clouds;
    for (const RecordedTopic& t : topics_) {
      if (is_cloud_type(t.type)) clouds.push_back(&t);
    }
    if (clouds.size() != 1) {
      throw Error(name_, "", (clouds.empty() ? std::string("has no sensor_msgs/PointCloud2 topic")
                                             : std::string("has several PointCloud2 topics: pick one with --topic")) +
                                 "; its topics:\n" + list_topics(topics_));
    }
    topic_ = clouds.front()->name;
  } else {
    const auto it = std::ranges::find(topics_, options.topic, &RecordedTopic::name);
    if (it == topics_.end()) throw Error(name_, "", "has no topic " + options.topic + "; its topics:\n" + list_topics(topics_));
    if (!is_cloud_type(it->type)) {
      throw Error(name_, "", "topic " + options.topic + " holds " + it->type + ", not sensor_msgs/PointCloud2");
    }
    topic_ = options.topic;
  }
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    for (detail::StoredMessage m : parts_[p]->index(topic_)) {
      m.part = std::uint32_t(p);
      clouds_.push_back(m);
    }
  }
  std::ranges::stable_sort(clouds_, {}, &detail::StoredMessage::log_time_ns);
  for (const auto& part : parts_) encodings_.push_back(int(part->encoding(topic_)));
}

Recording::~Recording() = default;
Recording::Recording(Recording&&) noexcept = default;
Recording& Recording::operator=(Recording&&) noexcept = default;

std::size_t Recording::size() const { return clouds_.size(); }

std::int64_t Recording::log_time_ns(std::size_t index) const { return clouds_.at(index).log_time_ns; }

PointCloud2 Recording::parsed(std::size_t index, const std::string& source) {
  const detail::StoredMessage& where = clouds_.at(index);
  const std::span<const std::uint8_t> bytes = parts_[where.part]->read(where);
  return detail::Encoding(encodings_[where.part]) == detail::Encoding::Cdr ? parse_cdr_point_cloud2(bytes, source)
                                                                           : parse_ros1_point_cloud2(bytes, source);
}

RecordedScan Recording::read(std::size_t index) {
  const std::string source = name_ + ", " + topic_ + " message " + std::to_string(index);
  const PointCloud2 cloud = parsed(index, source);
  return {index, cloud.stamp_ns, cloud.frame_id, decoder_.decode(cloud, source)};
}

std::int64_t Recording::stamp_ns(std::size_t index) {
  return parsed(index, name_ + ", " + topic_ + " message " + std::to_string(index)).stamp_ns;
}

std::string Recording::describe() const {
  return name_ + " (" + kind_ + "), topic " + topic_ + ": " + std::to_string(clouds_.size()) + " clouds";
}

std::vector<RecordedTopic> Recording::pose_topics() const {
  std::vector<RecordedTopic> out;
  for (const RecordedTopic& t : topics_) {
    if (detail::is_pose_type(t.type)) out.push_back(t);
  }
  return out;
}

PoseStream Recording::pose_track(const std::string& topic) {
  const auto it = std::ranges::find(topics_, topic, &RecordedTopic::name);
  if (it == topics_.end()) throw Error(name_, "", "has no topic " + topic + "; its topics:\n" + list_topics(topics_));
  if (!detail::is_pose_type(it->type)) {
    throw Error(name_, "", "topic " + topic + " holds " + it->type +
                               ", not nav_msgs/Odometry, geometry_msgs/PoseStamped or geometry_msgs/TransformStamped");
  }
  std::vector<detail::StampedPose> poses;
  for (const auto& part : parts_) {
    const detail::Encoding encoding = part->encoding(topic);
    std::size_t n = 0;
    for (const detail::StoredMessage& m : part->index(topic)) {
      const std::string source = name_ + ", " + topic + " message " + std::to_string(n++);
      poses.push_back(detail::parse_pose_message(part->read(m), encoding, it->type, source));
    }
  }
  if (poses.empty()) throw Error(name_, "", "topic " + topic + " holds no message");
  std::ranges::stable_sort(poses, {}, &detail::StampedPose::stamp_ns);
  PoseStream stream{{}, poses.front().frame_id, poses.front().child_frame_id};
  for (const detail::StampedPose& p : poses) {
    stream.track.times.push_back(double(p.stamp_ns) * 1e-9);
    stream.track.poses.push_back(p.pose);
  }
  return stream;
}

std::vector<const RecordedTopic*> Recording::tf_topics() const {
  std::vector<const RecordedTopic*> out;
  for (const RecordedTopic& t : topics_) {
    const bool named_tf = t.name == "/tf" || t.name == "/tf_static" || t.name == "tf" || t.name == "tf_static";
    if (named_tf && detail::is_tf_type(t.type)) out.push_back(&t);
  }
  return out;
}

bool Recording::has_tf() const { return !tf_topics().empty(); }

TransformTree Recording::transform_tree() {
  const std::vector<const RecordedTopic*> topics = tf_topics();
  if (topics.empty()) throw Error(name_, "", "has no /tf or /tf_static topic of tf2_msgs/TFMessage; its topics:\n" + list_topics(topics_));
  TransformTree tree;
  for (const RecordedTopic* topic : topics) {
    const bool is_static = topic->name.ends_with("tf_static");
    for (const auto& part : parts_) {
      const detail::Encoding encoding = part->encoding(topic->name);
      std::size_t n = 0;
      for (const detail::StoredMessage& m : part->index(topic->name)) {
        const std::string source = name_ + ", " + topic->name + " message " + std::to_string(n++);
        for (const detail::StampedPose& t : detail::parse_tf_message(part->read(m), encoding, source)) {
          tree.add({double(t.stamp_ns) * 1e-9, t.frame_id, t.child_frame_id, t.pose}, is_static, source);
        }
      }
    }
  }
  return tree;
}

}  // namespace eco::io
