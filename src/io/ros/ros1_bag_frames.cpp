#include "io/ros/ros1_bag_frames.hpp"

#include "io/ros/byte_reader.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace eco::io::detail {
namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::uint64_t kMagicSize = sizeof kMagic - 1;
constexpr std::uint32_t kLargestHeader = 16u << 20;  // connection headers hold message definitions: kilobytes
constexpr std::uint32_t kLargestChunk = 1u << 30;    // rosbag writes ~768 KB chunks

enum Op : std::uint8_t { kMessage = 0x02, kBagHeader = 0x03, kIndex = 0x04, kChunk = 0x05, kChunkInfo = 0x06, kConnection = 0x07 };

class BagFile {
 public:
  explicit BagFile(const std::filesystem::path& file) : name_(file.string()), in_(file, std::ios::binary) {
    if (!in_) throw Error(name_, "", "cannot be opened");
    size_ = std::filesystem::file_size(file);
  }
  [[nodiscard]] std::uint64_t size() const { return size_; }
  [[nodiscard]] const std::string& name() const { return name_; }

  std::vector<std::uint8_t> bytes(std::uint64_t at, std::uint64_t n) {
    std::vector<std::uint8_t> out(n);
    in_.seekg(std::streamoff(at));
    in_.read(reinterpret_cast<char*>(out.data()), std::streamsize(n));
    if (!in_) throw Error(name_, at_byte(at), "cannot be read");
    return out;
  }
  std::uint32_t u32(std::uint64_t at) {
    const std::vector<std::uint8_t> raw = bytes(at, 4);
    std::uint32_t v;
    std::memcpy(&v, raw.data(), 4);
    return v;
  }
  [[noreturn]] void fail(std::uint64_t at, const std::string& message) const { throw Error(name_, at_byte(at), message); }
  [[noreturn]] void cut(std::uint64_t at, const char* part, std::uint64_t declared, std::uint64_t remain) const {
    fail(at, std::string("a record's ") + part + " declares " + std::to_string(declared) + " bytes, " +
                 std::to_string(remain) + " remain: the bag is cut short (rosbag reindex mends that) or damaged");
  }

 private:
  std::string name_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

/// A record header's fields, name=value, each uint32-length-prefixed.
std::map<std::string, std::vector<std::uint8_t>> fields_of(const std::vector<std::uint8_t>& header, std::uint64_t at,
                                                           const std::string& source) {
  std::map<std::string, std::vector<std::uint8_t>> fields;
  ByteReader in(header, source, at);
  while (in.remaining() > 0) {
    const std::size_t start = in.offset();
    const std::span<const std::uint8_t> field = in.take(in.read<std::uint32_t>("a header field's length"), "a header field");
    const auto equals = std::find(field.begin(), field.end(), std::uint8_t('='));
    if (equals == field.end()) in.fail_at(start, "a header field without '='");
    fields[std::string(field.begin(), equals)] = std::vector<std::uint8_t>(equals + 1, field.end());
  }
  return fields;
}

std::uint64_t number(const std::map<std::string, std::vector<std::uint8_t>>& fields, const char* name, std::uint64_t at,
                     BagFile& bag) {
  const auto it = fields.find(name);
  if (it == fields.end() || (it->second.size() != 4 && it->second.size() != 8)) {
    bag.fail(at, std::string("a record without its field ") + name);
  }
  std::uint64_t v = 0;
  std::memcpy(&v, it->second.data(), it->second.size());  // little-endian, as the format is
  return v;
}

}  // namespace

void check_ros1_bag_frames(const std::filesystem::path& file) {
  BagFile bag(file);
  if (bag.size() < kMagicSize || std::memcmp(bag.bytes(0, kMagicSize).data(), kMagic, kMagicSize) != 0) {
    bag.fail(0, "is not a ROS 1 bag of format 2.0 (it does not begin with #ROSBAG V2.0)");
  }
  for (std::uint64_t at = kMagicSize; at < bag.size();) {
    const std::uint64_t remaining = bag.size() - at;
    if (remaining < 8) bag.fail(at, "a record cut short: the bag ends " + std::to_string(remaining) + " bytes into it");
    const std::uint32_t header_length = bag.u32(at);
    if (header_length > remaining - 8 || header_length > kLargestHeader) bag.cut(at, "header", header_length, remaining - 8);
    const auto fields = fields_of(bag.bytes(at + 4, header_length), at + 4, bag.name());
    const std::uint64_t data_at = at + 4 + header_length + 4;
    const std::uint32_t data_length = bag.u32(at + 4 + header_length);
    if (data_length > bag.size() - data_at) bag.cut(at, "data", data_length, bag.size() - data_at);
    const auto op = fields.find("op");
    if (op == fields.end() || op->second.size() != 1) bag.fail(at, "a record without its op");
    switch (op->second[0]) {
      case kBagHeader:
        if (const std::uint64_t index = number(fields, "index_pos", at, bag); index > bag.size()) {
          bag.fail(at, "the bag header's index lies at byte " + std::to_string(index) + ", past the end (" +
                           std::to_string(bag.size()) + " bytes): the bag is cut short (rosbag reindex mends that)");
        }
        break;
      case kChunk:
        if (number(fields, "size", at, bag) > kLargestChunk) bag.fail(at, "a chunk declares more than 1 GiB once uncompressed");
        break;
      case kIndex:
        if (number(fields, "count", at, bag) * 12 > data_length) bag.fail(at, "an index declares more entries than it holds");
        break;
      case kChunkInfo:
        if (number(fields, "count", at, bag) * 8 > data_length) bag.fail(at, "a chunk's summary declares more entries than it holds");
        break;
      case kMessage:
      case kConnection:
        break;
      default:
        bag.fail(at, "a record of unknown op " + std::to_string(int(op->second[0])));
    }
    at = data_at + data_length;
  }
}

}  // namespace eco::io::detail
