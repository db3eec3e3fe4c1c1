#include <eco/io/point_cloud2.hpp>

#include "io/ros/byte_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace eco::io {
namespace {

using detail::ByteReader;

/// The fields after the header, the same in both encodings but for alignment and strings.
PointCloud2 parse_body(ByteReader& in, PointCloud2 cloud) {
  cloud.height = in.read<std::uint32_t>("height");
  cloud.width = in.read<std::uint32_t>("width");
  const std::uint32_t count = in.read<std::uint32_t>("the field count");
  for (std::uint32_t i = 0; i < count; ++i) {
    PointField field;
    field.name = in.string("a field's name");
    field.offset = in.read<std::uint32_t>("a field's offset");
    const std::size_t type_at = in.offset();
    const std::uint8_t type = in.read<std::uint8_t>("a field's datatype");
    if (type < 1 || type > 8) in.fail_at(type_at, "field " + field.name + ": datatype " + std::to_string(type) + " is not 1-8");
    field.type = FieldType(type);
    field.count = in.read<std::uint32_t>("a field's count");
    cloud.fields.push_back(std::move(field));
  }
  cloud.is_bigendian = in.read<std::uint8_t>("is_bigendian") != 0;
  cloud.point_step = in.read<std::uint32_t>("point_step");
  cloud.row_step = in.read<std::uint32_t>("row_step");
  const std::uint32_t size = in.read<std::uint32_t>("the data's length");
  cloud.data = in.take(size, "data");
  cloud.is_dense = in.remaining() > 0 && in.read<std::uint8_t>("is_dense") != 0;
  return cloud;
}

std::size_t size_of(FieldType type) {
  switch (type) {
    case FieldType::Int8: case FieldType::UInt8: return 1;
    case FieldType::Int16: case FieldType::UInt16: return 2;
    case FieldType::Int32: case FieldType::UInt32: case FieldType::Float32: return 4;
    case FieldType::Float64: return 8;
  }
  return 0;
}

const char* type_name(FieldType type) {
  constexpr std::array<const char*, 9> names{"?", "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  return names[std::size_t(type)];
}

bool is_float(FieldType type) { return type == FieldType::Float32 || type == FieldType::Float64; }

template <class T>
double load(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return double(value);
}

/// A field's value in a point's bytes (the cloud is little-endian: checked before).
double value_of(FieldType type, const std::uint8_t* p) {
  switch (type) {
    case FieldType::Int8: return load<std::int8_t>(p);
    case FieldType::UInt8: return load<std::uint8_t>(p);
    case FieldType::Int16: return load<std::int16_t>(p);
    case FieldType::UInt16: return load<std::uint16_t>(p);
    case FieldType::Int32: return load<std::int32_t>(p);
    case FieldType::UInt32: return load<std::uint32_t>(p);
    case FieldType::Float32: return load<float>(p);
    case FieldType::Float64: return load<double>(p);
  }
  return 0.0;
}

const PointField* find(const PointCloud2& cloud, const std::string& name) {
  const auto it = std::ranges::find(cloud.fields, name, &PointField::name);
  return it == cloud.fields.end() ? nullptr : &*it;
}

const PointField* first_of(const PointCloud2& cloud, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    if (const PointField* f = find(cloud, name)) return f;
  }
  return nullptr;
}

double seconds_per(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::Milliseconds: return 1e-3;
    case TimeUnit::Microseconds: return 1e-6;
    case TimeUnit::Nanoseconds: return 1e-9;
    default: return 1.0;
  }
}

/// The middle point's time field in seconds, for telling offsets from clock readings.
double middle_time(const PointCloud2& cloud, const PointField& field, TimeUnit unit) {
  const std::size_t points = std::size_t(cloud.width) * cloud.height;
  const std::size_t middle = points / 2;
  const std::size_t row = middle / cloud.width, column = middle % cloud.width;
  const std::uint8_t* p = cloud.data.data() + row * cloud.row_step + column * cloud.point_step + field.offset;
  return value_of(field.type, p) * seconds_per(unit);
}

}  // namespace

PointCloud2 parse_ros1_point_cloud2(std::span<const std::uint8_t> message, const std::string& source) {
  ByteReader in(message, source);
  PointCloud2 cloud;
  (void)in.read<std::uint32_t>("the header's seq");
  const std::uint32_t sec = in.read<std::uint32_t>("the stamp");
  const std::uint32_t nsec = in.read<std::uint32_t>("the stamp");
  cloud.stamp_ns = std::int64_t(sec) * 1000000000 + nsec;
  cloud.frame_id = in.string("frame_id");
  return parse_body(in, std::move(cloud));
}

PointCloud2 parse_cdr_point_cloud2(std::span<const std::uint8_t> message, const std::string& source) {
  ByteReader head(message, source);
  (void)head.read<std::uint8_t>("the encapsulation");
  const std::uint8_t kind = head.read<std::uint8_t>("the encapsulation");
  if (kind > 1) head.fail_at(1, "encapsulation " + std::to_string(kind) + " is not plain CDR (0: big, 1: little endian)");
  (void)head.take(2, "the encapsulation's options");
  ByteReader in(message, source, 0, 4, kind == 0);
  in.seek(4);
  PointCloud2 cloud;
  const std::int32_t sec = in.read<std::int32_t>("the stamp");
  const std::uint32_t nsec = in.read<std::uint32_t>("the stamp");
  cloud.stamp_ns = std::int64_t(sec) * 1000000000 + nsec;
  cloud.frame_id = in.string("frame_id");
  return parse_body(in, std::move(cloud));
}

std::optional<TimeUnit> time_unit_named(const std::string& name) {
  for (TimeUnit unit : {TimeUnit::Auto, TimeUnit::Seconds, TimeUnit::Milliseconds, TimeUnit::Microseconds, TimeUnit::Nanoseconds}) {
    if (name == name_of(unit)) return unit;
  }
  return std::nullopt;
}

const char* name_of(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::Seconds: return "s";
    case TimeUnit::Milliseconds: return "ms";
    case TimeUnit::Microseconds: return "us";
    case TimeUnit::Nanoseconds: return "ns";
    default: return "auto";
  }
}

std::string CloudLayout::describe() const {
  std::string text = time_field.empty() ? "no per-point time" :
      "time: field " + time_field + " in " + name_of(time_unit) + (absolute_times ? ", absolute" : " after the header stamp");
  return text + "; intensity: " + (intensity_field.empty() ? "none" : intensity_field);
}

DecodedCloud CloudDecoder::decode(const PointCloud2& cloud, const std::string& source) {
  const auto refuse = [&](const std::string& what) { throw Error(source, "", "PointCloud2 " + what); };
  if (cloud.is_bigendian) refuse("is big-endian: only little-endian clouds are read");
  const PointField* xyz[3] = {find(cloud, "x"), find(cloud, "y"), find(cloud, "z")};
  if (!xyz[0] || !xyz[1] || !xyz[2]) refuse("has no x, y and z fields");
  for (const PointField& f : cloud.fields) {
    if (std::uint64_t(f.offset) + size_of(f.type) > cloud.point_step) {
      refuse("field " + f.name + " (" + type_name(f.type) + " at " + std::to_string(f.offset) + ") ends past point_step " +
             std::to_string(cloud.point_step));
    }
  }
  const std::uint64_t points = std::uint64_t(cloud.width) * cloud.height;
  if (points > 0 && std::uint64_t(cloud.width) * cloud.point_step > cloud.row_step) {
    refuse("row_step " + std::to_string(cloud.row_step) + " is shorter than width " + std::to_string(cloud.width) +
           " × point_step " + std::to_string(cloud.point_step));
  }
  if (points > 0 && std::uint64_t(cloud.height) * cloud.row_step > cloud.data.size()) {
    refuse("data holds " + std::to_string(cloud.data.size()) + " bytes, less than height " + std::to_string(cloud.height) +
           " × row_step " + std::to_string(cloud.row_step));
  }

  if (!layout_) {
    CloudLayout layout;
    if (const PointField* f = first_of(cloud, {"intensity", "reflectivity", "i"})) layout.intensity_field = f->name;
    const PointField* time = options_.field.empty()
                                 ? first_of(cloud, {"t", "time", "timestamp", "timestamps", "offset_time", "stamps"})
                                 : find(cloud, options_.field);
    if (!options_.field.empty() && !time) refuse("has no time field " + options_.field);
    if (time) {
      layout.time_field = time->name;
      layout.time_unit = options_.unit != TimeUnit::Auto ? options_.unit
                                                         : (is_float(time->type) ? TimeUnit::Seconds : TimeUnit::Nanoseconds);
      // clock readings lie nearer the stamp than zero; offsets from it, nearer zero
      if (points > 0) {
        const double t = middle_time(cloud, *time, layout.time_unit);
        layout.absolute_times = std::abs(t - double(cloud.stamp_ns) * 1e-9) < std::abs(t);
      }
    }
    layout_ = layout;
  }
  const PointField* intensity = layout_->intensity_field.empty() ? nullptr : find(cloud, layout_->intensity_field);
  const PointField* time = layout_->time_field.empty() ? nullptr : find(cloud, layout_->time_field);
  if (!layout_->time_field.empty() && !time) refuse("has no field " + layout_->time_field + ", which the first cloud timed its points by");

  DecodedCloud out;
  out.points.reserve(std::size_t(points));
  if (intensity) out.intensities.reserve(std::size_t(points));
  if (time) out.times.reserve(std::size_t(points));
  const double unit = time ? seconds_per(layout_->time_unit) : 0.0;
  const double stamp = double(cloud.stamp_ns) * 1e-9;
  // float32 coordinates, as most drivers write them, read without going through double
  const bool floats = xyz[0]->type == FieldType::Float32 && xyz[1]->type == FieldType::Float32 &&
                      xyz[2]->type == FieldType::Float32;
  const std::uint32_t rows = points > 0 ? cloud.height : 0;  // a cloud 0 wide and 4 billion high holds nothing to walk
  for (std::uint32_t row = 0; row < rows; ++row) {
    const std::uint8_t* p = cloud.data.data() + std::size_t(row) * cloud.row_step;
    for (std::uint32_t column = 0; column < cloud.width; ++column, p += cloud.point_step) {
      Eigen::Vector3f v;
      if (floats) {
        std::memcpy(&v.x(), p + xyz[0]->offset, 4);
        std::memcpy(&v.y(), p + xyz[1]->offset, 4);
        std::memcpy(&v.z(), p + xyz[2]->offset, 4);
      } else {
        v = Eigen::Vector3d(value_of(xyz[0]->type, p + xyz[0]->offset), value_of(xyz[1]->type, p + xyz[1]->offset),
                            value_of(xyz[2]->type, p + xyz[2]->offset))
                .cast<float>();
      }
      if (!v.allFinite()) {
        ++out.skipped_not_finite;
        continue;
      }
      if (v.x() == 0.0f && v.y() == 0.0f && v.z() == 0.0f) {
        ++out.skipped_zero;
        continue;
      }
      out.points.push_back(v);
      if (intensity) out.intensities.push_back(float(value_of(intensity->type, p + intensity->offset)));
      if (time) {
        const double t = value_of(time->type, p + time->offset) * unit;
        out.times.push_back(layout_->absolute_times ? t - stamp : t);
      }
    }
  }
  return out;
}

}  // namespace eco::io
