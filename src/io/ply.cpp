#include <eco/io/ply.hpp>

#include "io/files.hpp"
#include "io/records.hpp"

#include <optional>

namespace eco::io {

namespace {

using detail::RecordLayout;
using detail::TextCursor;

// One "element" of the header; only the vertex element's records are decoded.
struct Element {
  std::string name;
  std::size_t count = 0;
  RecordLayout layout;
  bool has_list = false;  // list properties make binary records variable-length
};

struct Header {
  bool binary = false;
  std::vector<Element> elements;
};

Header parse_header(TextCursor& cursor) {
  if (!cursor.next_line() || cursor.line() != "ply") cursor.fail("not a PLY file: the first line must be 'ply'");
  Header header;
  bool format_seen = false;
  while (true) {
    if (!cursor.next_line()) cursor.fail("the header has no 'end_header' line");
    const auto words = detail::split_words(cursor.line());
    if (words.empty()) continue;
    const std::string_view key = words[0];
    if (key == "end_header") break;
    if (key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      if (words.size() != 3) cursor.fail("expected 'format <type> 1.0'");
      if (words[1] == "ascii") header.binary = false;
      else if (words[1] == "binary_little_endian") header.binary = true;
      else cursor.fail("unsupported format '" + std::string(words[1]) + "' (ascii and binary_little_endian are)");
      format_seen = true;
    } else if (key == "element") {
      if (words.size() != 3) cursor.fail("expected 'element <name> <count>'");
      header.elements.push_back({std::string(words[1]), cursor.number<std::size_t>(words[2]), {}, false});
    } else if (key == "property") {
      if (header.elements.empty()) cursor.fail("a property before any element");
      Element& element = header.elements.back();
      if (words.size() >= 2 && words[1] == "list") {
        if (element.name == "vertex") cursor.fail("unsupported property: a list in the vertex element");
        element.has_list = true;
        continue;
      }
      if (words.size() != 3) cursor.fail("expected 'property <type> <name>'");
      const auto type = detail::ply_scalar(words[1]);
      if (!type) cursor.fail("unsupported property type '" + std::string(words[1]) + "'");
      element.layout.add(std::string(words[2]), *type);
    } else {
      cursor.fail("unknown header keyword '" + std::string(key) + "'");
    }
  }
  if (!format_seen) cursor.fail("the header has no 'format' line");
  return header;
}

// Moves past an element that comes before the vertices.
void skip_element(const Element& element, bool binary, std::string_view bytes, std::size_t& offset,
                  TextCursor& cursor) {
  if (binary) {
    if (element.has_list) {
      cursor.fail("cannot skip element '" + element.name + "' with a list property before the vertices");
    }
    const std::size_t available = bytes.size() - offset;
    const std::size_t stride = element.layout.stride();
    if (stride > 0 && element.count > available / stride) {
      throw Error(cursor.source(), at_byte(offset), "element '" + element.name + "' runs past the end of the file");
    }
    offset += element.count * stride;
    return;
  }
  for (std::size_t i = 0; i < element.count; ++i) {
    if (!cursor.next_line()) cursor.fail("the file ends inside element '" + element.name + "'");
  }
}

}  // namespace

PointCloud parse_ply(std::string_view bytes, const std::string& source) {
  TextCursor cursor(bytes, source);
  Header header = parse_header(cursor);
  std::size_t offset = cursor.offset();
  for (Element& element : header.elements) {
    if (element.name != "vertex") {
      skip_element(element, header.binary, bytes, offset, cursor);
      continue;
    }
    element.layout.locate_fields(cursor);
    PointCloud cloud;
    if (header.binary) element.layout.read_binary(bytes, offset, element.count, source, cloud);
    else element.layout.read_ascii(cursor, element.count, cloud);
    return cloud;
  }
  cursor.fail("the header declares no 'vertex' element");
}

PointCloud read_ply(const std::filesystem::path& path) {
  return parse_ply(detail::read_file(path), path.string());
}

std::string format_ply(const PointCloud& cloud, PlyFormat format) {
  detail::check_writable(cloud, "PLY output");
  std::string out = "ply\nformat ";
  out += format == PlyFormat::Ascii ? "ascii 1.0\n" : "binary_little_endian 1.0\n";
  out += "comment written by ECO\nelement vertex " + std::to_string(cloud.size()) + "\n";
  out += "property float x\nproperty float y\nproperty float z\n";
  if (cloud.has_intensity()) out += "property float intensity\n";
  out += "end_header\n";
  if (format == PlyFormat::Ascii) detail::append_ascii_records(out, cloud);
  else detail::append_binary_records(out, cloud);
  return out;
}

void write_ply(const std::filesystem::path& path, const PointCloud& cloud, PlyFormat format) {
  detail::check_writable(cloud, path.string());
  detail::write_file(path, format_ply(cloud, format));
}

}  // namespace eco::io
