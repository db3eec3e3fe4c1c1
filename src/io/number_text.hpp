#pragma once
// Numbers written in their shortest form that reads back to the same value.

#include <array>
#include <charconv>
#include <string>

namespace eco::io::detail {

template <typename T>
void append_number(std::string& out, T value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out.append(buffer.data(), result.ptr);
}

template <typename T>
[[nodiscard]] std::string number_text(T value) {
  std::string out;
  append_number(out, value);
  return out;
}

}  // namespace eco::io::detail
