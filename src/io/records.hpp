#pragma once
// Point records as PLY and PCD describe them: a row of typed scalar fields per point. Both
// formats map their header onto a RecordLayout and share the decoding and encoding here.

#include <eco/io/point_cloud.hpp>

#include "io/text_cursor.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace eco::io::detail {

enum class Scalar { I8, U8, I16, U16, I32, U32, F32, F64 };

[[nodiscard]] std::size_t size_of(Scalar type);

struct Field {
  std::string name;
  Scalar type = Scalar::F32;
  std::size_t count = 1;   ///< values of this field per record (PCD COUNT)
  std::size_t offset = 0;  ///< byte offset within a binary record
  std::size_t first_value = 0;  ///< index of its first value within an ascii record
};

class RecordLayout {
 public:
  void add(std::string name, Scalar type, std::size_t count = 1);
  /// Finds x, y, z (required) and an intensity field (optional); fails through `header` if a
  /// coordinate is missing or repeated.
  void locate_fields(const TextCursor& header);

  [[nodiscard]] std::size_t stride() const { return stride_; }   ///< bytes per binary record
  [[nodiscard]] std::size_t values() const { return values_; }   ///< numbers per ascii record
  [[nodiscard]] bool has_intensity() const { return intensity_.has_value(); }
  [[nodiscard]] const std::vector<Field>& fields() const { return fields_; }

  /// Decodes `count` little-endian records starting at byte `offset` of `bytes`.
  void read_binary(std::string_view bytes, std::size_t offset, std::size_t count,
                   const std::string& source, PointCloud& cloud) const;
  /// Decodes `count` records, one per line, from the lines after the cursor's current one.
  void read_ascii(TextCursor& cursor, std::size_t count, PointCloud& cloud) const;

 private:
  std::vector<Field> fields_;
  std::size_t stride_ = 0;
  std::size_t values_ = 0;
  std::size_t x_ = 0, y_ = 0, z_ = 0;
  std::optional<std::size_t> intensity_;
};

/// Parses a scalar type name ("float", "uchar", "float32", ...); nullopt if unknown.
[[nodiscard]] std::optional<Scalar> ply_scalar(std::string_view name);
/// PCD's TYPE letter and SIZE bytes; nullopt if the pair is unknown.
[[nodiscard]] std::optional<Scalar> pcd_scalar(char type, std::size_t size);

/// Writers: x y z [intensity] as float32, one record per point.
void append_ascii_records(std::string& out, const PointCloud& cloud);
void append_binary_records(std::string& out, const PointCloud& cloud);
/// Throws unless the cloud has no intensities or exactly one per point.
void check_writable(const PointCloud& cloud, const std::string& destination);

}  // namespace eco::io::detail
