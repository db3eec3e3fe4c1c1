#pragma once
// A recording's messages as every container holds them (an MCAP file, a rosbag2 SQLite file, a
// ROS 1 bag): its topics listed, a topic's messages indexed in time order, then read one at a
// time, so that a recording of any length is streamed, never loaded.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace eco::io::detail {

enum class Encoding { Ros1, Cdr };

struct TopicInfo {
  std::string name;
  std::string type;  ///< "sensor_msgs/msg/PointCloud2" (ROS 2) or "sensor_msgs/PointCloud2" (ROS 1)
  std::size_t messages = 0;
};

/// Where one message is, and its log time.
struct StoredMessage {
  static constexpr std::uint64_t kInFile = std::uint64_t(-1);
  std::int64_t log_time_ns = 0;
  std::uint64_t container = kInFile;  ///< the file offset of the chunk holding it, or kInFile
  std::uint64_t offset = 0;           ///< its data's offset in the chunk or the file; a row id
  std::uint64_t size = 0;             ///< its data's bytes
  std::uint32_t part = 0;             ///< the file, in a recording split over several
};

class MessageStore {
 public:
  virtual ~MessageStore() = default;
  [[nodiscard]] virtual std::vector<TopicInfo> topics() const = 0;
  /// The messages on `topic`, in log-time order.
  [[nodiscard]] virtual std::vector<StoredMessage> index(const std::string& topic) const = 0;
  /// One message's serialised bytes, valid until the next read. Throws eco::io::Error naming the
  /// file and byte (or row) on damage.
  [[nodiscard]] virtual std::span<const std::uint8_t> read(const StoredMessage& message) = 0;
  /// How `topic`'s messages are serialised; throws eco::io::Error for an encoding not read here.
  [[nodiscard]] virtual Encoding encoding(const std::string& topic) const = 0;
  /// Why the recording ends early (a cut file: where), or empty.
  [[nodiscard]] virtual std::string damage() const { return {}; }
};

}  // namespace eco::io::detail
