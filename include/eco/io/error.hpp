#pragma once
/// @file error.hpp
/// The one exception every ECO reader and writer throws: it names the file and, when the fault
/// is inside the file, the line (text) or byte offset (binary) where it was found.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace eco::io {

class Error : public std::runtime_error {
 public:
  /// `source`: the file (or buffer name); `where`: "line 7", "byte 1024", or empty.
  Error(const std::string& source, const std::string& where, const std::string& message)
      : std::runtime_error(source + ": " + (where.empty() ? "" : where + ": ") + message),
        source_(source) {}

  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  std::string source_;
};

[[nodiscard]] inline std::string at_line(std::size_t line) { return "line " + std::to_string(line); }
[[nodiscard]] inline std::string at_byte(std::size_t offset) {
  return "byte " + std::to_string(offset);
}

}  // namespace eco::io
