#pragma once
// A ROS 1 bag (format 2.0: uncompressed, bz2 or lz4 chunks) as a MessageStore, through Debian's
// rosbag_storage: its connections listed, a topic's messages indexed by rosbag's own index, each
// message's ROS 1 bytes copied out when asked for.

#include "io/ros/message_store.hpp"

#include <filesystem>
#include <memory>
#include <vector>

namespace eco::io::detail {

class Ros1BagStore final : public MessageStore {
 public:
  /// Throws eco::io::Error naming the file for a bag rosbag cannot open (not a bag, cut short
  /// before its index was written, an unknown compression).
  explicit Ros1BagStore(const std::filesystem::path& file);
  ~Ros1BagStore() override;

  [[nodiscard]] std::vector<TopicInfo> topics() const override;
  [[nodiscard]] std::vector<StoredMessage> index(const std::string& topic) const override;
  [[nodiscard]] std::span<const std::uint8_t> read(const StoredMessage& message) override;
  [[nodiscard]] Encoding encoding(const std::string&) const override { return Encoding::Ros1; }

  /// Whether this build reads ROS 1 bags (Debian's librosbag-storage-dev was found).
  [[nodiscard]] static bool available();

 private:
  struct Bag;  // rosbag's, kept out of this header
  std::string name_;
  std::unique_ptr<Bag> bag_;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace eco::io::detail
