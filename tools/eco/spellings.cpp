#include "spellings.hpp"

#include <algorithm>
#include <numeric>

namespace eco::cli {
namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), 0);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

/// The name nearest `typed`, if within a third of its length (at least 2 edits).
std::string nearest(const std::string& typed, const std::vector<std::string>& names) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, typed.size() / 3) + 1;
  for (const std::string& name : names) {
    const std::size_t d = edit_distance(typed, name);
    if (d < best_distance) {
      best = name;
      best_distance = d;
    }
  }
  return best;
}

std::vector<std::string> long_names(const CLI::App& cmd) {
  std::vector<std::string> names;
  for (const CLI::Option* option : cmd.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
  }
  return names;
}

}  // namespace

std::string both_spellings(const std::string& flag) {
  std::string other = flag.substr(2);
  const bool dashed = other.find('-') != std::string::npos;
  std::replace(other.begin(), other.end(), dashed ? '-' : '_', dashed ? '_' : '-');
  return other == flag.substr(2) ? flag : flag + ",--" + other;
}

std::string did_you_mean(CLI::App& app) {
  std::vector<std::string> commands;
  CLI::App* given = nullptr;
  for (CLI::App* sub : app.get_subcommands({})) {
    commands.push_back(sub->get_name());
    if (sub->parsed()) given = sub;
  }
  std::string out;
  const auto suggest = [&](const std::string& typed, const std::string& meant) {
    if (!meant.empty()) out += "eco: '" + typed + "' is not known: did you mean '" + meant + "'?\n";
  };
  if (!given) {
    for (const std::string& word : app.remaining()) {
      if (!word.starts_with("-")) suggest(word, nearest(word, commands));
    }
    return out;
  }
  const std::vector<std::string> options = long_names(*given);
  for (std::string word : given->remaining()) {
    if (!word.starts_with("--")) continue;
    word = word.substr(0, word.find('='));
    suggest(word, nearest(word, options));
  }
  return out;
}

}  // namespace eco::cli
