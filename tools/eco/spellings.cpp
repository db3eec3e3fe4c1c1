#include "spellings.hpp"

#include "text/nearest_name.hpp"

#include <algorithm>

namespace eco::cli {
namespace {

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
      if (!word.starts_with("-")) suggest(word, text::nearest_name(word, commands));
    }
    return out;
  }
  const std::vector<std::string> options = long_names(*given);
  for (std::string word : given->remaining()) {
    if (!word.starts_with("--")) continue;
    word = word.substr(0, word.find('='));
    suggest(word, text::nearest_name(word, options));
  }
  return out;
}

}  // namespace eco::cli
