#pragma once
// "Did you mean" for mistyped subcommands and options of drapelab: `drapelab rnu` names `run`,
// `drapelab run s.json --outt d` names `--out` (docs/model.md section 9, the command line).
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace drape {

/// Levenshtein distance: insertions, deletions and substitutions of one character each.
int edit_distance(const std::string& a, const std::string& b);
/// The candidate nearest `word`, if it is near enough to be a typo (at most 2 edits, and at
/// most a third of the word's length for longer words); ties go to the first candidate.
std::optional<std::string> nearest_name(const std::string& word,
                                        const std::vector<std::string>& candidates);
/// After a parse error: the message naming the first argument of `args` (argv without the
/// program) that is an unknown subcommand or option of `app` and its nearest name, e.g.
/// "unknown subcommand 'rnu'; did you mean 'run'?"; nothing when no such argument has a near name.
std::optional<std::string> did_you_mean(const CLI::App& app, const std::vector<std::string>& args);

}  // namespace drape
