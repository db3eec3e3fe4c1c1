#pragma once
// A rosbag2 SQLite file (.db3) as a MessageStore, through Debian's libsqlite3: rosbag2's schema,
// `topics(id, name, type, serialization_format, ...)` and `messages(id, topic_id, timestamp,
// data)`, read-only; a message is fetched by its row when asked for.

#include "io/ros/message_store.hpp"

#include <filesystem>
#include <memory>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace eco::io::detail {

class SqliteStore final : public MessageStore {
 public:
  /// Throws eco::io::Error naming the file when it is not a rosbag2 database.
  explicit SqliteStore(const std::filesystem::path& file);
  ~SqliteStore() override;

  [[nodiscard]] std::vector<TopicInfo> topics() const override { return topics_; }
  [[nodiscard]] std::vector<StoredMessage> index(const std::string& topic) const override;
  [[nodiscard]] std::span<const std::uint8_t> read(const StoredMessage& message) override;
  [[nodiscard]] Encoding encoding(const std::string&) const override { return Encoding::Cdr; }

 private:
  [[noreturn]] void fail(const std::string& what) const;

  std::string name_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* fetch_ = nullptr;  // SELECT data FROM messages WHERE id = ?
  std::vector<TopicInfo> topics_;
  std::vector<std::int64_t> topic_ids_;
};

}  // namespace eco::io::detail
