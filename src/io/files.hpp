#pragma once
// Whole-file reads and writes that fail with an eco::io::Error naming the path.

#include <filesystem>
#include <string>
#include <string_view>

namespace eco::io::detail {

[[nodiscard]] std::string read_file(const std::filesystem::path& path);
void write_file(const std::filesystem::path& path, std::string_view bytes);
/// Throws unless `path` is an existing directory.
void require_directory(const std::filesystem::path& path);

}  // namespace eco::io::detail
