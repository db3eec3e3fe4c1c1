#pragma once
// A map file on disk: read whole, and written so that a failed write leaves any earlier file at
// the path as it was.

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

namespace eco::detail {

/// A file's bytes, read into memory that was not cleared first (a map file is read once, whole).
struct FileBytes {
  std::unique_ptr<char[]> data;
  std::size_t size = 0;
  [[nodiscard]] std::string_view view() const { return {data.get(), size}; }
};

/// The bytes of the file at `path`. Throws std::runtime_error naming the path and the reason.
FileBytes read_whole_file(const std::string& path);

/// Writes `bytes` to a temporary file beside `path`, flushes it to the disk, then renames it over
/// `path`. Throws std::runtime_error naming the path and the reason; the temporary file is then
/// removed and whatever was at `path` stays.
void write_replacing(const std::string& path, std::string_view bytes);

}  // namespace eco::detail
