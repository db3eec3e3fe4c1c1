#pragma once
// Line-by-line reading of a text (or a text header) that knows where it is, so every parse
// error can name the line.

#include <eco/io/error.hpp>

#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace eco::io::detail {

/// Splits a line into words at spaces and tabs.
[[nodiscard]] std::vector<std::string_view> split_words(std::string_view line);

class TextCursor {
 public:
  TextCursor(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  /// Moves to the next line (without its "\n" or "\r\n"); false at the end of the text.
  bool next_line();
  [[nodiscard]] std::string_view line() const { return line_; }
  [[nodiscard]] std::size_t line_number() const { return line_number_; }
  /// Byte offset just past the current line: where binary data after a header begins.
  [[nodiscard]] std::size_t offset() const { return next_; }
  [[nodiscard]] const std::string& source() const { return source_; }

  [[noreturn]] void fail(const std::string& message) const {
    throw Error(source_, at_line(line_number_), message);
  }

  /// Parses a whole word as a number of type T, or fails naming the word and the line.
  template <typename T>
  [[nodiscard]] T number(std::string_view word) const {
    std::string_view digits = word;
    if (digits.size() > 1 && digits.front() == '+') digits.remove_prefix(1);  // from_chars refuses '+'
    T value{};
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec == std::errc::result_out_of_range) fail("number out of range: '" + std::string(word) + "'");
    if (ec != std::errc() || end != digits.data() + digits.size()) {
      fail("malformed number '" + std::string(word) + "'");
    }
    return value;
  }

 private:
  std::string_view text_;
  std::string source_;
  std::string_view line_;
  std::size_t next_ = 0;
  std::size_t line_number_ = 0;
};

}  // namespace eco::io::detail
