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

  [[nodiscard]] std::vector<TopicInfo> topics() const override { return topics_; }
  [[nodiscard]] std::vector<StoredMessage> index(const std::string& topic) const override;
  [[nodiscard]] std::span<const std::uint8_t> read(const StoredMessage& message) override;
  [[nodiscard]] Encoding encoding(const std::string&) const override { return Encoding::Cdr; }

 private:
  [[noreturn]] void fail(const std::string& what) const;

  // closed however the constructor ends: a file refused half-way open leaks nothing
  struct Close {
    void operator()(sqlite3* db) const;
    void operator()(sqlite3_stmt* statement) const;
  };
  std::string name_;
  std::unique_ptr<sqlite3, Close> db_;
  std::unique_ptr<sqlite3_stmt, Close> fetch_;  // SELECT data FROM messages WHERE id = ?
  std::vector<TopicInfo> topics_;
  std::vector<std::int64_t> topic_ids_;
};

}  // namespace eco::io::detail
