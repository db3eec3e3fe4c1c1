#include "io/ros/mcap_store.hpp"

#include "bytes/checksum.hpp"
#include "io/ros/byte_reader.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <string_view>

namespace eco::io::detail {
namespace {

constexpr std::array<std::uint8_t, 8> kMagic{0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
enum Op : std::uint8_t { Header = 1, Footer = 2, Schema = 3, ChannelOp = 4, Message = 5, Chunk = 6, DataEnd = 0x0F };
constexpr std::uint64_t kMaxRecord = std::uint64_t(4) << 30;  // 4 GiB: past it a length is damage, not data
constexpr std::uint64_t kMaxChunk = std::uint64_t(1) << 30;   // writers make chunks of a few MB

void decompress_lz4(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out, const ByteReader& where) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) where.fail("no lz4 context");
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(raw, LZ4F_freeDecompressionContext);
  std::size_t read = 0, written = 0;
  while (read < in.size()) {
    std::size_t in_size = in.size() - read, out_size = out.size() - written;
    const std::size_t hint = LZ4F_decompress(context.get(), out.data() + written, &out_size, in.data() + read, &in_size, nullptr);
    if (LZ4F_isError(hint)) where.fail(std::string("lz4 chunk: ") + LZ4F_getErrorName(hint));
    read += in_size;
    written += out_size;
    if (hint == 0) break;
    if (in_size == 0 && out_size == 0) where.fail("lz4 chunk: larger than its uncompressed_size");
  }
  if (written != out.size()) {
    where.fail("lz4 chunk: " + std::to_string(written) + " bytes, not the " + std::to_string(out.size()) + " its header says");
  }
}

void decompress_zstd(ZSTD_DCtx* context, std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out,
                     const ByteReader& where) {
  const std::size_t written = ZSTD_decompressDCtx(context, out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(written)) where.fail(std::string("zstd chunk: ") + ZSTD_getErrorName(written));
  if (written != out.size()) {
    where.fail("zstd chunk: " + std::to_string(written) + " bytes, not the " + std::to_string(out.size()) + " its header says");
  }
}

}  // namespace

void McapStore::FreeZstd::operator()(ZSTD_DCtx* context) const { ZSTD_freeDCtx(context); }

McapStore::McapStore(const std::filesystem::path& file) : name_(file.string()), file_(file, std::ios::binary) {
  if (!file_) throw Error(name_, "", "cannot be opened");
  file_.seekg(0, std::ios::end);
  size_ = std::uint64_t(file_.tellg());
  scan();
}

void McapStore::read_at(std::uint64_t at, std::size_t n, std::vector<std::uint8_t>& out) {
  out.resize(n);
  file_.clear();
  file_.seekg(std::streamoff(at));
  file_.read(reinterpret_cast<char*>(out.data()), std::streamsize(n));
  if (!file_) throw Error(name_, at_byte(at), "cannot read " + std::to_string(n) + " bytes");
}

void McapStore::scan() {
  if (size_ < kMagic.size()) throw Error(name_, at_byte(0), "not an MCAP file (shorter than its magic)");
  read_at(0, kMagic.size(), buffer_);
  if (!std::equal(kMagic.begin(), kMagic.end(), buffer_.begin())) throw Error(name_, at_byte(0), "not an MCAP file (no MCAP0 magic)");
  std::uint64_t at = kMagic.size();
  for (;;) {
    const auto cut = [&](const std::string& where) {
      damage_ = name_ + ": " + at_byte(at) + ": the file ends " + where + " (cut short?): read up to there";
    };
    if (size_ - at < 9) return cut(at == size_ ? "without a footer" : "inside a record's header");
    read_at(at, 9, buffer_);
    const std::uint8_t op = buffer_[0];
    std::uint64_t length = 0;
    std::memcpy(&length, buffer_.data() + 1, 8);
    if (op == Footer || op == DataEnd) return;  // the summary repeats what the data section said
    if (length > size_ - at - 9) return cut("inside a record of " + std::to_string(length) + " bytes");
    if (op == Schema || op == ChannelOp) {
      read_at(at + 9, std::size_t(length), buffer_);
      define(op, buffer_, at);
    } else if (op == Message) {
      read_at(at + 9, std::size_t(std::min<std::uint64_t>(length, 22)), buffer_);
      add_message(buffer_, length, StoredMessage::kInFile, at + 9, at);
    } else if (op == Chunk) {
      const std::span<const std::uint8_t> records = chunk_records(at);
      ByteReader in(records, name_ + " (the chunk at " + at_byte(at) + ")");
      while (in.remaining() > 0) {
        const std::size_t start = in.offset();
        const std::uint8_t inner = in.read<std::uint8_t>("a record's opcode");
        const std::uint64_t inner_length = in.read<std::uint64_t>("a record's length");
        const std::span<const std::uint8_t> body = in.take(inner_length, "a record");
        if (inner == Schema || inner == ChannelOp) define(inner, body, at);
        if (inner == Message) add_message(body, inner_length, at, start + 9, at);
      }
    }
    at += 9 + length;
  }
}

void McapStore::define(std::uint8_t op, std::span<const std::uint8_t> body, std::uint64_t at) {
  ByteReader fields(body, name_, at + 9);
  if (op == Schema) {
    const std::uint16_t id = fields.read<std::uint16_t>("a schema's id");
    schemas_[id] = fields.string("a schema's name");
    return;
  }
  const std::uint16_t id = fields.read<std::uint16_t>("a channel's id");
  const std::uint16_t schema = fields.read<std::uint16_t>("a channel's schema_id");
  Channel& c = channels_[id];
  c.topic = fields.string("a channel's topic");
  c.encoding = fields.string("a channel's message_encoding");
  const auto s = schemas_.find(schema);
  c.type = s == schemas_.end() ? std::string() : s->second;
}

void McapStore::add_message(std::span<const std::uint8_t> body, std::uint64_t length, std::uint64_t container,
                            std::uint64_t offset, std::uint64_t at) {
  ByteReader in(body, name_, at + 9);
  if (length < 22) in.fail("a message record of " + std::to_string(length) + " bytes, fewer than its 22-byte header");
  const std::uint16_t channel = in.read<std::uint16_t>("a message's channel_id");
  (void)in.read<std::uint32_t>("a message's sequence");
  const auto log_time = std::int64_t(in.read<std::uint64_t>("a message's log_time"));
  const auto it = channels_.find(channel);
  if (it == channels_.end()) in.fail("a message on channel " + std::to_string(channel) + ", which no Channel record defined");
  it->second.messages.push_back({log_time, container, offset + 22, length - 22, 0});
}

std::span<const std::uint8_t> McapStore::chunk_records(std::uint64_t chunk) {
  if (cached_chunk_ == chunk) return chunk_;
  cached_chunk_ = StoredMessage::kInFile;
  read_at(chunk + 1, 8, buffer_);
  std::uint64_t length = 0;
  std::memcpy(&length, buffer_.data(), 8);
  if (length > kMaxRecord) throw Error(name_, at_byte(chunk + 1), "a chunk of " + std::to_string(length) + " bytes is not believable");
  read_at(chunk + 9, std::size_t(length), buffer_);
  ByteReader in(buffer_, name_, chunk + 9);
  (void)in.read<std::uint64_t>("the chunk's message_start_time");
  (void)in.read<std::uint64_t>("the chunk's message_end_time");
  const std::uint64_t uncompressed = in.read<std::uint64_t>("the chunk's uncompressed_size");
  const std::uint32_t crc = in.read<std::uint32_t>("the chunk's uncompressed_crc");
  const std::size_t compression_at = in.offset();
  const std::string compression = in.string("the chunk's compression");
  const std::uint64_t size = in.read<std::uint64_t>("the chunk's records length");
  const std::span<const std::uint8_t> records = in.take(size, "the chunk's records");
  // what the records could decompress to at most: lz4 makes at most 255 bytes of one, a zstd block
  // (3 bytes, RLE) at most 128 KiB; a chunk is allocated at its declared size, so a size past
  // that is refused before the allocation, not after it
  const std::uint64_t most = compression.empty()   ? records.size()
                              : compression == "lz4" ? 255 * std::uint64_t(records.size()) + 64
                                                     : 43691 * std::uint64_t(records.size()) + 64;
  if (uncompressed > kMaxChunk || uncompressed > most) {
    in.fail_at(compression_at, "uncompressed_size " + std::to_string(uncompressed) + " is not believable for " +
                                   std::to_string(records.size()) + " bytes of records");
  }
  chunk_.resize(std::size_t(uncompressed));
  if (compression.empty()) {
    if (records.size() != uncompressed) in.fail_at(compression_at, "an uncompressed chunk whose length is not its uncompressed_size");
    std::copy(records.begin(), records.end(), chunk_.begin());
  } else if (compression == "lz4") {
    decompress_lz4(records, chunk_, in);
  } else if (compression == "zstd") {
    if (!zstd_) zstd_.reset(ZSTD_createDCtx());
    decompress_zstd(zstd_.get(), records, chunk_, in);
  } else {
    in.fail_at(compression_at, "compression '" + compression + "' is not one of lz4, zstd or none");
  }
  const std::string_view decompressed(reinterpret_cast<const char*>(chunk_.data()), chunk_.size());
  // MCAP's CRC-32 is zlib's, the one the library closes its own files with
  if (crc != 0 && eco::detail::checksum(decompressed) != crc) in.fail_at(compression_at, "the chunk's records fail their CRC-32");
  cached_chunk_ = chunk;
  return chunk_;
}

std::vector<TopicInfo> McapStore::topics() const {
  std::vector<TopicInfo> out;
  for (const auto& [id, c] : channels_) {
    const auto same = std::ranges::find(out, c.topic, &TopicInfo::name);
    if (same != out.end()) {
      same->messages += c.messages.size();
    } else {
      out.push_back({c.topic, c.type, c.messages.size()});
    }
  }
  return out;
}

std::vector<StoredMessage> McapStore::index(const std::string& topic) const {
  std::vector<StoredMessage> out;
  for (const auto& [id, c] : channels_) {
    if (c.topic == topic) out.insert(out.end(), c.messages.begin(), c.messages.end());
  }
  std::ranges::stable_sort(out, {}, &StoredMessage::log_time_ns);
  return out;
}

Encoding McapStore::encoding(const std::string& topic) const {
  for (const auto& [id, c] : channels_) {
    if (c.topic != topic) continue;
    if (c.encoding == "cdr") return Encoding::Cdr;
    if (c.encoding == "ros1") return Encoding::Ros1;
    throw Error(name_, "", "topic " + topic + " is encoded as '" + c.encoding + "', not cdr or ros1");
  }
  return Encoding::Cdr;
}

std::span<const std::uint8_t> McapStore::read(const StoredMessage& message) {
  if (message.container == StoredMessage::kInFile) {
    read_at(message.offset, std::size_t(message.size), buffer_);
    return buffer_;
  }
  const std::span<const std::uint8_t> records = chunk_records(message.container);
  if (message.offset + message.size > records.size()) throw Error(name_, at_byte(message.container), "a message past its chunk's end");
  return records.subspan(std::size_t(message.offset), std::size_t(message.size));
}

}  // namespace eco::io::detail
