#pragma once
// A map file on disk: read whole, and written so that a failed write leaves any earlier file at
// the path as it was.

#include <string>
#include <string_view>

namespace eco::detail {

/// The bytes of the file at `path`. Throws std::runtime_error naming the path and the reason.
std::string read_whole_file(const std::string& path);

/// Writes `bytes` to a temporary file beside `path`, flushes it to the disk, then renames it over
/// `path`. Throws std::runtime_error naming the path and the reason; the temporary file is then
/// removed and whatever was at `path` stays.
void write_replacing(const std::string& path, std::string_view bytes);

}  // namespace eco::detail
