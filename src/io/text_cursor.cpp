#include "io/text_cursor.hpp"

namespace eco::io::detail {

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t begin = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > begin) words.push_back(line.substr(begin, i - begin));
  }
  return words;
}

bool TextCursor::next_line() {
  if (next_ >= text_.size()) return false;
  const std::size_t end = text_.find('\n', next_);
  const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
  line_ = text_.substr(next_, stop - next_);
  if (!line_.empty() && line_.back() == '\r') line_.remove_suffix(1);
  next_ = end == std::string_view::npos ? text_.size() : end + 1;
  ++line_number_;
  return true;
}

}  // namespace eco::io::detail
