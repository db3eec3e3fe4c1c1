#pragma once
/// @file pcd.hpp
/// PCD point files (PCL's format, v0.7 and earlier headers): read DATA ascii, binary and
/// binary_compressed (fields x, y, z of any type, and an intensity field if present; other
/// fields are skipped; VIEWPOINT is ignored); write float x, y, z [, intensity].

#include <eco/io/error.hpp>
#include <eco/io/point_cloud.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace eco::io {

enum class PcdFormat { Ascii, Binary, BinaryCompressed };

/// Throws eco::io::Error naming the file and the line (header, ascii) or byte offset (binary).
[[nodiscard]] PointCloud read_pcd(const std::filesystem::path& path);
/// The same, from bytes in memory; `source` names them in errors.
[[nodiscard]] PointCloud parse_pcd(std::string_view bytes, const std::string& source);

void write_pcd(const std::filesystem::path& path, const PointCloud& cloud,
               PcdFormat format = PcdFormat::Binary);
[[nodiscard]] std::string format_pcd(const PointCloud& cloud, PcdFormat format);

}  // namespace eco::io
