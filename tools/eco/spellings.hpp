#pragma once
// One spelling of a flag everywhere, both accepted: `--box-side` and `--box_side` name the same
// option on every command; and, for a mistyped command or option, the name meant.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace eco::cli {

/// "--box-side" -> "--box-side,--box_side" (CLI11's list of names), and the other way round.
[[nodiscard]] std::string both_spellings(const std::string& flag);

/// After a failed parse of `app`: "did you mean ...?" for each word it did not expect (a command
/// or an option of the command given), or "" when nothing is near enough.
[[nodiscard]] std::string did_you_mean(CLI::App& app);

}  // namespace eco::cli
