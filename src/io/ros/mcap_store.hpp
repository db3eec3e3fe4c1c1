#pragma once
// An MCAP file (the published MCAP specification, major version 0) as a MessageStore: records read
// in one pass for the schemas, channels and where each message lies (inside chunks: uncompressed,
// lz4 or zstd, each checked against its CRC-32), then messages read on demand, one chunk kept.
// A file cut short is read up to its last whole record, and says where it ends.

#include "io/ros/message_store.hpp"

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <vector>

struct ZSTD_DCtx_s;
using ZSTD_DCtx = ZSTD_DCtx_s;

namespace eco::io::detail {

class McapStore final : public MessageStore {
 public:
  /// Throws eco::io::Error naming the file and byte for a file that is not MCAP or is damaged
  /// before its first message.
  explicit McapStore(const std::filesystem::path& file);

  [[nodiscard]] std::vector<TopicInfo> topics() const override;
  [[nodiscard]] std::vector<StoredMessage> index(const std::string& topic) const override;
  [[nodiscard]] std::span<const std::uint8_t> read(const StoredMessage& message) override;
  [[nodiscard]] Encoding encoding(const std::string& topic) const override;
  [[nodiscard]] std::string damage() const override { return damage_; }

 private:
  struct Channel {
    std::string topic, type, encoding;
    std::vector<StoredMessage> messages;
  };
  void scan();
  /// Keeps the schema or channel a record at `at` of the file (`body`: its content) defines.
  void define(std::uint8_t op, std::span<const std::uint8_t> body, std::uint64_t at);
  /// Indexes the message whose 22-byte header starts `body`, found at `offset` in `container`.
  void add_message(std::span<const std::uint8_t> body, std::uint64_t length, std::uint64_t container,
                   std::uint64_t offset, std::uint64_t at);
  /// The records of the chunk at file offset `chunk`, decompressed and checked against their CRC.
  [[nodiscard]] std::span<const std::uint8_t> chunk_records(std::uint64_t chunk);
  /// `n` bytes at file offset `at` into `out`.
  void read_at(std::uint64_t at, std::size_t n, std::vector<std::uint8_t>& out);

  std::string name_;
  std::ifstream file_;
  std::uint64_t size_ = 0;
  std::map<std::uint16_t, std::string> schemas_;  // id -> name
  std::map<std::uint16_t, Channel> channels_;
  std::string damage_;
  // the chunk last decompressed, and a message read outside any chunk
  std::uint64_t cached_chunk_ = std::uint64_t(-1);
  std::vector<std::uint8_t> chunk_;
  std::vector<std::uint8_t> buffer_;
  struct FreeZstd {
    void operator()(ZSTD_DCtx* context) const;
  };
  std::unique_ptr<ZSTD_DCtx, FreeZstd> zstd_;  // kept: a context's tables are not remade a chunk
};

}  // namespace eco::io::detail
