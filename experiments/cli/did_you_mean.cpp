#include "experiments/cli/did_you_mean.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <numeric>

namespace drape {

namespace {

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  return names;
}

// Every spelling of the options of `app` and of its parents (`--help` is everyone's).
std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* a = &app; a != nullptr; a = a->get_parent())
    for (const CLI::Option* opt : a->get_options()) {
      for (const std::string& l : opt->get_lnames()) names.push_back("--" + l);
      for (const std::string& s : opt->get_snames()) names.push_back("-" + s);
    }
  return names;
}

bool is_number(const std::string& text) {
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

}  // namespace

int edit_distance(const std::string& a, const std::string& b) {
  // One row of the dynamic programme: row[j] = distance(a[0..i), b[0..j)).
  std::vector<int> row(b.size() + 1);
  std::iota(row.begin(), row.end(), 0);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];
    row[0] = static_cast<int>(i);
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const int substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitute});
    }
  }
  return row[b.size()];
}

std::optional<std::string> nearest_name(const std::string& word,
                                        const std::vector<std::string>& candidates) {
  const int limit = std::max(2, static_cast<int>(word.size()) / 3);
  std::optional<std::string> best;
  int best_distance = limit + 1;
  for (const std::string& c : candidates) {
    const int d = edit_distance(word, c);
    if (d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  return best;
}

std::optional<std::string> did_you_mean(const CLI::App& app,
                                        const std::vector<std::string>& args) {
  const CLI::App* current = &app;
  std::string prefix = "drapelab";
  for (const std::string& arg : args) {
    if (arg == "--") break;
    if (current->get_allow_extras()) break;  // the rest belongs to another program (report)
    if (arg.size() > 1 && arg[0] == '-' && !is_number(arg)) {
      const std::string name = arg.substr(0, arg.find('='));
      const std::vector<std::string> names = option_names(*current);
      if (std::find(names.begin(), names.end(), name) != names.end()) continue;
      if (const auto near = nearest_name(name, names))
        return fmt::format("{}: unknown option '{}'; did you mean '{}'?", prefix, name, *near);
      continue;
    }
    const std::vector<std::string> subs = subcommand_names(*current);
    if (std::find(subs.begin(), subs.end(), arg) != subs.end()) {
      current = current->get_subcommand(arg);
      prefix += " " + arg;
      continue;
    }
    // A word where a subcommand is required and none was given yet: a mistyped subcommand.
    if (current == &app && !subs.empty())
      if (const auto near = nearest_name(arg, subs))
        return fmt::format("{}: unknown subcommand '{}'; did you mean '{}'?", prefix, arg, *near);
  }
  return std::nullopt;
}

}  // namespace drape
