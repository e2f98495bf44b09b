#pragma once
// Messages for command-line parse errors: the nearest command or option to a mistyped one.
#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace asperity::cli {

/// Levenshtein distance between `a` and `b` (insertions, deletions, substitutions),
/// ignoring ASCII letter case.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate nearest to `word` by edit_distance, or "" when none is within
/// max(2, |word|/3) edits (too far to be a typo of it).
std::string nearest(std::string_view word, const std::vector<std::string>& candidates);

/// The message (without the "asperity: error: " prefix) for a CLI11 parse error of
/// `app`: an unknown command or option names its nearest valid one ("did you mean"),
/// and every message ends by pointing at --help.
std::string parse_error_message(CLI::App& app, const CLI::ParseError& e, int argc, char** argv);

}  // namespace asperity::cli
