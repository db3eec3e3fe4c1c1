#include <eco/io/pcd.hpp>

#include "io/files.hpp"
#include "io/records.hpp"

#include <lzf.h>

#include <cstdint>
#include <cstring>
#include <optional>

namespace eco::io {

namespace {

using detail::RecordLayout;
using detail::TextCursor;

struct Header {
  std::vector<std::string> names;
  std::vector<std::size_t> sizes;
  std::vector<char> types;
  std::vector<std::size_t> counts;
  std::optional<std::size_t> width, height, points;
  std::size_t points_line = 0;
  std::string data;
};

std::vector<std::size_t> numbers(const TextCursor& cursor, const std::vector<std::string_view>& words) {
  std::vector<std::size_t> values;
  for (std::size_t i = 1; i < words.size(); ++i) values.push_back(cursor.number<std::size_t>(words[i]));
  return values;
}

Header parse_header(TextCursor& cursor) {
  Header h;
  while (h.data.empty()) {
    if (!cursor.next_line()) cursor.fail("the header has no DATA line");
    const auto words = detail::split_words(cursor.line());
    if (words.empty() || words[0].front() == '#') continue;
    const std::string_view key = words[0];
    if (key == "VERSION" || key == "VIEWPOINT") continue;
    if (key == "FIELDS") {
      for (std::size_t i = 1; i < words.size(); ++i) h.names.emplace_back(words[i]);
    } else if (key == "SIZE") {
      h.sizes = numbers(cursor, words);
    } else if (key == "TYPE") {
      for (std::size_t i = 1; i < words.size(); ++i) {
        if (words[i].size() != 1) cursor.fail("TYPE must be I, U or F, not '" + std::string(words[i]) + "'");
        h.types.push_back(words[i][0]);
      }
    } else if (key == "COUNT") {
      h.counts = numbers(cursor, words);
    } else if (key == "WIDTH" || key == "HEIGHT" || key == "POINTS") {
      if (words.size() != 2) cursor.fail("expected '" + std::string(key) + " <count>'");
      const std::size_t value = cursor.number<std::size_t>(words[1]);
      (key == "WIDTH" ? h.width : key == "HEIGHT" ? h.height : h.points) = value;
      if (key == "POINTS") h.points_line = cursor.line_number();
    } else if (key == "DATA") {
      if (words.size() != 2) cursor.fail("expected 'DATA ascii|binary|binary_compressed'");
      h.data = std::string(words[1]);
    } else {
      cursor.fail("unknown header keyword '" + std::string(key) + "'");
    }
  }
  return h;
}

RecordLayout layout_of(Header& h, const TextCursor& cursor) {
  if (h.names.empty()) cursor.fail("the header has no FIELDS line");
  if (h.counts.empty()) h.counts.assign(h.names.size(), 1);
  if (h.sizes.size() != h.names.size() || h.types.size() != h.names.size() ||
      h.counts.size() != h.names.size()) {
    cursor.fail("FIELDS, SIZE, TYPE and COUNT name different numbers of fields");
  }
  RecordLayout layout;
  for (std::size_t i = 0; i < h.names.size(); ++i) {
    const auto type = detail::pcd_scalar(h.types[i], h.sizes[i]);
    if (!type) {
      cursor.fail("unsupported field '" + h.names[i] + "': TYPE " + h.types[i] + " SIZE " +
                  std::to_string(h.sizes[i]));
    }
    if (h.counts[i] == 0 || h.counts[i] > 4096) cursor.fail("field '" + h.names[i] + "' has COUNT " + std::to_string(h.counts[i]));
    layout.add(h.names[i], *type, h.counts[i]);
  }
  layout.locate_fields(cursor);
  return layout;
}

std::size_t point_count(const Header& h, const TextCursor& cursor) {
  if (!h.width) cursor.fail("the header has no WIDTH line");
  const std::size_t height = h.height.value_or(1);
  if (height != 0 && *h.width > SIZE_MAX / height) cursor.fail("WIDTH x HEIGHT overflows");
  const std::size_t n = *h.width * height;
  if (h.points && *h.points != n) {
    throw Error(cursor.source(), at_line(h.points_line),
                "POINTS " + std::to_string(*h.points) + " differs from WIDTH x HEIGHT = " + std::to_string(n));
  }
  return n;
}

std::uint32_t load_u32(std::string_view bytes, std::size_t offset) {
  std::uint32_t value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

// binary_compressed: two uint32 sizes, then LZF data that unpacks to one array per field
// (all x, then all y, ...). Re-packed here into records so one decoder serves every variant.
std::string unpack_compressed(std::string_view bytes, std::size_t offset, std::size_t n,
                              const RecordLayout& layout, const std::string& source) {
  if (bytes.size() - offset < 8) throw Error(source, at_byte(offset), "binary_compressed data has no size words");
  const std::uint32_t packed = load_u32(bytes, offset);
  const std::uint32_t unpacked = load_u32(bytes, offset + 4);
  if (packed > bytes.size() - offset - 8) {
    throw Error(source, at_byte(offset), "compressed size " + std::to_string(packed) + " runs past the end of the file");
  }
  if (layout.stride() == 0 || n > SIZE_MAX / layout.stride() || unpacked != n * layout.stride()) {
    throw Error(source, at_byte(offset + 4), "uncompressed size " + std::to_string(unpacked) + " does not match " +
                                                 std::to_string(n) + " points of " + std::to_string(layout.stride()) + " bytes");
  }
  if (unpacked / 88 > packed) {  // an LZF back-reference expands 3 bytes into at most 264
    throw Error(source, at_byte(offset), "compressed size " + std::to_string(packed) + " cannot hold " +
                                             std::to_string(unpacked) + " bytes");
  }
  std::string fields(unpacked, '\0');
  if (unpacked > 0 &&
      lzf_decompress(bytes.data() + offset + 8, packed, fields.data(), unpacked) != unpacked) {
    throw Error(source, at_byte(offset + 8), "corrupt LZF data");
  }
  std::string records(unpacked, '\0');
  std::size_t field_start = 0;
  for (const auto& field : layout.fields()) {
    const std::size_t width = detail::size_of(field.type) * field.count;
    for (std::size_t i = 0; i < n; ++i) {
      std::memcpy(records.data() + i * layout.stride() + field.offset, fields.data() + field_start + i * width, width);
    }
    field_start += n * width;
  }
  return records;
}

std::string pack_compressed(const PointCloud& cloud) {
  const std::size_t per_point = cloud.has_intensity() ? 4 : 3;
  std::string fields(cloud.size() * per_point * sizeof(float), '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (std::size_t f = 0; f < per_point; ++f) {
      const float value = f < 3 ? cloud.points[i][static_cast<Eigen::Index>(f)] : cloud.intensity[i];
      std::memcpy(fields.data() + (f * cloud.size() + i) * sizeof(float), &value, sizeof(float));
    }
  }
  std::string packed(fields.size() + fields.size() / 16 + 64, '\0');
  const unsigned int size = fields.empty() ? 0 : lzf_compress(fields.data(), static_cast<unsigned>(fields.size()),
                                                              packed.data(), static_cast<unsigned>(packed.size()));
  if (size == 0 && !fields.empty()) throw Error("PCD output", "", "LZF compression failed");
  std::string out(8, '\0');
  const auto sizes = std::array<std::uint32_t, 2>{size, static_cast<std::uint32_t>(fields.size())};
  std::memcpy(out.data(), sizes.data(), 8);
  out.append(packed.data(), size);
  return out;
}

}  // namespace

PointCloud parse_pcd(std::string_view bytes, const std::string& source) {
  TextCursor cursor(bytes, source);
  Header header = parse_header(cursor);
  const RecordLayout layout = layout_of(header, cursor);
  const std::size_t n = point_count(header, cursor);
  PointCloud cloud;
  if (header.data == "ascii") {
    layout.read_ascii(cursor, n, cloud);
  } else if (header.data == "binary") {
    layout.read_binary(bytes, cursor.offset(), n, source, cloud);
  } else if (header.data == "binary_compressed") {
    const std::string records = unpack_compressed(bytes, cursor.offset(), n, layout, source);
    layout.read_binary(records, 0, n, source, cloud);
  } else {
    cursor.fail("unsupported DATA '" + header.data + "' (ascii, binary and binary_compressed are)");
  }
  return cloud;
}

PointCloud read_pcd(const std::filesystem::path& path) {
  return parse_pcd(detail::read_file(path), path.string());
}

std::string format_pcd(const PointCloud& cloud, PcdFormat format) {
  detail::check_writable(cloud, "PCD output");
  const bool intensity = cloud.has_intensity();
  const std::string n = std::to_string(cloud.size());
  std::string out = "# .PCD v0.7 - Point Cloud Data file format (written by ECO)\nVERSION 0.7\n";
  out += intensity ? "FIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                   : "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
  out += "WIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA ";
  switch (format) {
    case PcdFormat::Ascii:
      out += "ascii\n";
      detail::append_ascii_records(out, cloud);
      break;
    case PcdFormat::Binary:
      out += "binary\n";
      detail::append_binary_records(out, cloud);
      break;
    case PcdFormat::BinaryCompressed:
      out += "binary_compressed\n";
      out += pack_compressed(cloud);
      break;
  }
  return out;
}

void write_pcd(const std::filesystem::path& path, const PointCloud& cloud, PcdFormat format) {
  detail::check_writable(cloud, path.string());
  detail::write_file(path, format_pcd(cloud, format));
}

}  // namespace eco::io
