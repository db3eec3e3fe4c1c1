#include "io/records.hpp"

#include "io/number_text.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>

namespace eco::io::detail {

static_assert(std::endian::native == std::endian::little, "binary PLY and PCD records are little-endian");

namespace {

// Names a file format calls a point's intensity.
constexpr std::array<std::string_view, 4> kIntensityNames = {"intensity", "reflectance",
                                                             "scalar_intensity", "remission"};

template <typename T>
float load_as_float(const char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return static_cast<float>(value);
}

float load(Scalar type, const char* p) {
  switch (type) {
    case Scalar::I8: return load_as_float<std::int8_t>(p);
    case Scalar::U8: return load_as_float<std::uint8_t>(p);
    case Scalar::I16: return load_as_float<std::int16_t>(p);
    case Scalar::U16: return load_as_float<std::uint16_t>(p);
    case Scalar::I32: return load_as_float<std::int32_t>(p);
    case Scalar::U32: return load_as_float<std::uint32_t>(p);
    case Scalar::F32: return load_as_float<float>(p);
    case Scalar::F64: return load_as_float<double>(p);
  }
  return 0.0f;
}

void append_raw(std::string& out, float value) {
  char bytes[sizeof(float)];
  std::memcpy(bytes, &value, sizeof(float));
  out.append(bytes, sizeof(float));
}

}  // namespace

std::size_t size_of(Scalar type) {
  switch (type) {
    case Scalar::I8: case Scalar::U8: return 1;
    case Scalar::I16: case Scalar::U16: return 2;
    case Scalar::I32: case Scalar::U32: case Scalar::F32: return 4;
    case Scalar::F64: return 8;
  }
  return 0;
}

void RecordLayout::add(std::string name, Scalar type, std::size_t count) {
  fields_.push_back({std::move(name), type, count, stride_, values_});
  stride_ += size_of(type) * count;
  values_ += count;
}

void RecordLayout::locate_fields(const TextCursor& header) {
  std::optional<std::size_t> found[3];
  const char* axes[3] = {"x", "y", "z"};
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      if (fields_[i].name != axes[a]) continue;
      if (found[a]) header.fail(std::string("field '") + axes[a] + "' is declared twice");
      found[a] = i;
    }
    const bool is_intensity = std::find(kIntensityNames.begin(), kIntensityNames.end(),
                                        fields_[i].name) != kIntensityNames.end();
    if (is_intensity && !intensity_) intensity_ = i;
  }
  for (int a = 0; a < 3; ++a) {
    if (!found[a]) header.fail(std::string("no '") + axes[a] + "' field: points need x, y and z");
  }
  x_ = *found[0];
  y_ = *found[1];
  z_ = *found[2];
}

void RecordLayout::read_binary(std::string_view bytes, std::size_t offset, std::size_t count,
                               const std::string& source, PointCloud& cloud) const {
  const std::size_t available = bytes.size() - std::min(offset, bytes.size());
  if (stride_ == 0 || count > available / stride_) {
    throw Error(source, at_byte(offset),
                "header promises " + std::to_string(count) + " points of " +
                    std::to_string(stride_) + " bytes but only " + std::to_string(available) +
                    " bytes follow");
  }
  cloud.points.resize(count);
  if (intensity_) cloud.intensity.resize(count);
  const char* record = bytes.data() + offset;
  for (std::size_t i = 0; i < count; ++i, record += stride_) {
    cloud.points[i] = {load(fields_[x_].type, record + fields_[x_].offset),
                       load(fields_[y_].type, record + fields_[y_].offset),
                       load(fields_[z_].type, record + fields_[z_].offset)};
    if (intensity_) {
      cloud.intensity[i] = load(fields_[*intensity_].type, record + fields_[*intensity_].offset);
    }
  }
}

void RecordLayout::read_ascii(TextCursor& cursor, std::size_t count, PointCloud& cloud) const {
  cloud.points.reserve(std::min<std::size_t>(count, 1u << 20));
  if (intensity_) cloud.intensity.reserve(cloud.points.capacity());
  // What each number of a record is for: 0..2 x, y, z, 3 intensity, -1 checked and skipped.
  std::vector<int> role(values_, -1);
  role[fields_[x_].first_value] = 0;
  role[fields_[y_].first_value] = 1;
  role[fields_[z_].first_value] = 2;
  if (intensity_) role[fields_[*intensity_].first_value] = 3;
  float kept[4] = {};
  for (std::size_t i = 0; i < count; ++i) {
    if (!cursor.next_line()) {
      cursor.fail("the file ends after " + std::to_string(i) + " of " + std::to_string(count) +
                  " points");
    }
    const auto words = split_words(cursor.line());
    if (words.size() != values_) {
      cursor.fail("expected " + std::to_string(values_) + " numbers, found " +
                  std::to_string(words.size()));
    }
    for (std::size_t k = 0; k < words.size(); ++k) {  // each number parsed once, all well formed
      if (role[k] < 0) (void)cursor.number<double>(words[k]);
      else kept[role[k]] = cursor.number<float>(words[k]);
    }
    cloud.points.emplace_back(kept[0], kept[1], kept[2]);
    if (intensity_) cloud.intensity.push_back(kept[3]);
  }
}

std::optional<Scalar> ply_scalar(std::string_view name) {
  static constexpr std::pair<std::string_view, Scalar> kNames[] = {
      {"char", Scalar::I8},    {"int8", Scalar::I8},     {"uchar", Scalar::U8},
      {"uint8", Scalar::U8},   {"short", Scalar::I16},   {"int16", Scalar::I16},
      {"ushort", Scalar::U16}, {"uint16", Scalar::U16},  {"int", Scalar::I32},
      {"int32", Scalar::I32},  {"uint", Scalar::U32},    {"uint32", Scalar::U32},
      {"float", Scalar::F32},  {"float32", Scalar::F32}, {"double", Scalar::F64},
      {"float64", Scalar::F64}};
  for (const auto& [text, type] : kNames) {
    if (text == name) return type;
  }
  return std::nullopt;
}

std::optional<Scalar> pcd_scalar(char type, std::size_t size) {
  switch (type) {
    case 'I':
      if (size == 1) return Scalar::I8;
      if (size == 2) return Scalar::I16;
      if (size == 4) return Scalar::I32;
      return std::nullopt;
    case 'U':
      if (size == 1) return Scalar::U8;
      if (size == 2) return Scalar::U16;
      if (size == 4) return Scalar::U32;
      return std::nullopt;
    case 'F':
      if (size == 4) return Scalar::F32;
      if (size == 8) return Scalar::F64;
      return std::nullopt;
    default: return std::nullopt;
  }
}

void append_ascii_records(std::string& out, const PointCloud& cloud) {
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    append_number(out, p.x());
    out += ' ';
    append_number(out, p.y());
    out += ' ';
    append_number(out, p.z());
    if (cloud.has_intensity()) {
      out += ' ';
      append_number(out, cloud.intensity[i]);
    }
    out += '\n';
  }
}

void append_binary_records(std::string& out, const PointCloud& cloud) {
  out.reserve(out.size() + cloud.size() * (cloud.has_intensity() ? 16 : 12));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int a = 0; a < 3; ++a) append_raw(out, cloud.points[i][a]);
    if (cloud.has_intensity()) append_raw(out, cloud.intensity[i]);
  }
}

void check_writable(const PointCloud& cloud, const std::string& destination) {
  if (cloud.has_intensity() && cloud.intensity.size() != cloud.size()) {
    throw Error(destination, "",
                "cannot write " + std::to_string(cloud.size()) + " points with " +
                    std::to_string(cloud.intensity.size()) + " intensities");
  }
}

}  // namespace eco::io::detail
