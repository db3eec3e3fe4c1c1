#pragma once
// A map file on disk: read whole, and written so that a failed write leaves any earlier file at
// the path as it was.

#include <cstddef>
#include <string>
#include <string_view>

namespace eco::detail {

/// A file's bytes, mapped read-only: the system's cached pages of the file itself, neither copied
/// nor faulted in one at a time. A map file is only ever replaced whole (write_replacing), so the
/// bytes stay those of the file opened; one cut short in place by another program while mapped
/// would end the process with SIGBUS.
class FileBytes {
 public:
  FileBytes() = default;
  FileBytes(const void* data, std::size_t size) : data_(data), size_(size) {}
  FileBytes(FileBytes&& other) noexcept;
  FileBytes& operator=(FileBytes&& other) noexcept;
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  ~FileBytes();
  [[nodiscard]] std::string_view view() const { return {static_cast<const char*>(data_), size_}; }

 private:
  const void* data_ = nullptr;
  std::size_t size_ = 0;
};

/// The bytes of the file at `path`. Throws std::runtime_error naming the path and the reason.
FileBytes read_whole_file(const std::string& path);

/// Writes `bytes` to a temporary file beside `path`, flushes it to the disk, then renames it over
/// `path`. Throws std::runtime_error naming the path and the reason; the temporary file is then
/// removed and whatever was at `path` stays.
void write_replacing(const std::string& path, std::string_view bytes);

}  // namespace eco::detail
