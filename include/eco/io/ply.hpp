#pragma once
/// @file ply.hpp
/// PLY point files: read ascii and binary little-endian (vertex x, y, z of any scalar type, and an
/// `intensity`, `reflectance`, `scalar_intensity` or `remission` property if present; other
/// vertex properties and later elements are skipped); write float x, y, z [, intensity].

#include <eco/io/error.hpp>
#include <eco/io/point_cloud.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace eco::io {

enum class PlyFormat { Ascii, BinaryLittleEndian };

/// Throws eco::io::Error naming the file and the line (header, ascii) or byte offset (binary).
[[nodiscard]] PointCloud read_ply(const std::filesystem::path& path);
/// The same, from bytes in memory; `source` names them in errors.
[[nodiscard]] PointCloud parse_ply(std::string_view bytes, const std::string& source);

void write_ply(const std::filesystem::path& path, const PointCloud& cloud,
               PlyFormat format = PlyFormat::BinaryLittleEndian);
[[nodiscard]] std::string format_ply(const PointCloud& cloud, PlyFormat format);

}  // namespace eco::io
