#include "io/ros/sqlite_store.hpp"

#include <eco/io/error.hpp>

#include <sqlite3.h>

#include <algorithm>

namespace eco::io::detail {
namespace {

/// A prepared statement, finalised when it goes.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql) { sqlite3_prepare_v2(db, sql, -1, &statement_, nullptr); }
  ~Statement() { sqlite3_finalize(statement_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  [[nodiscard]] sqlite3_stmt* get() const { return statement_; }

 private:
  sqlite3_stmt* statement_ = nullptr;
};

std::string text_of(sqlite3_stmt* row, int column) {
  const unsigned char* text = sqlite3_column_text(row, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace

void SqliteStore::Close::operator()(sqlite3* db) const { sqlite3_close(db); }
void SqliteStore::Close::operator()(sqlite3_stmt* statement) const { sqlite3_finalize(statement); }

SqliteStore::SqliteStore(const std::filesystem::path& file) : name_(file.string()) {
  if (!std::filesystem::is_regular_file(file)) throw Error(name_, "", "no such file");
  sqlite3* db = nullptr;
  const int opened = sqlite3_open_v2(name_.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  db_.reset(db);  // a handle even when the open failed: closed with the store
  if (opened != SQLITE_OK) fail("cannot be opened");
  // a cloud spans hundreds of overflow pages: read through a mapping, not a pread a page
  sqlite3_exec(db_.get(), "PRAGMA mmap_size = 1099511627776", nullptr, nullptr, nullptr);
  const Statement listing(db_.get(),
                          "SELECT t.id, t.name, t.type, t.serialization_format, (SELECT COUNT(*) FROM messages m "
                          "WHERE m.topic_id = t.id) FROM topics t ORDER BY t.id");
  if (!listing.get()) fail("is not a rosbag2 database (no topics and messages tables)");
  int step = 0;
  while ((step = sqlite3_step(listing.get())) == SQLITE_ROW) {
    const std::string format = text_of(listing.get(), 3);
    if (format != "cdr") fail("topic " + text_of(listing.get(), 1) + " is serialised as '" + format + "', not cdr");
    topic_ids_.push_back(sqlite3_column_int64(listing.get(), 0));
    topics_.push_back({text_of(listing.get(), 1), text_of(listing.get(), 2), std::size_t(sqlite3_column_int64(listing.get(), 4))});
  }
  if (step != SQLITE_DONE) fail("its topics cannot be listed");
  sqlite3_stmt* fetch = nullptr;
  sqlite3_prepare_v2(db_.get(), "SELECT data FROM messages WHERE id = ?", -1, &fetch, nullptr);
  fetch_.reset(fetch);
  if (!fetch_) fail("its messages cannot be read");
}

void SqliteStore::fail(const std::string& what) const {
  const std::string reason = db_ ? std::string(" (sqlite: ") + sqlite3_errmsg(db_.get()) + ")" : "";
  throw Error(name_, "", what + reason);
}

std::vector<StoredMessage> SqliteStore::index(const std::string& topic) const {
  std::vector<StoredMessage> out;
  const auto it = std::ranges::find(topics_, topic, &TopicInfo::name);
  if (it == topics_.end()) return out;
  const Statement rows(db_.get(), "SELECT id, timestamp, length(data) FROM messages WHERE topic_id = ? ORDER BY timestamp, id");
  sqlite3_bind_int64(rows.get(), 1, topic_ids_[std::size_t(it - topics_.begin())]);
  int step = 0;
  while ((step = sqlite3_step(rows.get())) == SQLITE_ROW) {
    out.push_back({sqlite3_column_int64(rows.get(), 1), StoredMessage::kInFile, std::uint64_t(sqlite3_column_int64(rows.get(), 0)),
                   std::uint64_t(sqlite3_column_int64(rows.get(), 2)), 0});
  }
  if (step != SQLITE_DONE) fail("the messages of " + topic + " cannot be listed");
  return out;
}

std::span<const std::uint8_t> SqliteStore::read(const StoredMessage& message) {
  sqlite3_stmt* fetch = fetch_.get();
  sqlite3_reset(fetch);
  sqlite3_bind_int64(fetch, 1, std::int64_t(message.offset));
  if (sqlite3_step(fetch) != SQLITE_ROW) {
    throw Error(name_, "message row " + std::to_string(message.offset), "cannot be read");
  }
  // SQLite's own copy, valid until the statement is reset by the next read: not copied again
  const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(fetch, 0));
  return {data, std::size_t(sqlite3_column_bytes(fetch, 0))};
}

}  // namespace eco::io::detail
