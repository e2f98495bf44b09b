#include "suggest.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <numeric>

namespace asperity::cli {

namespace {

char lower(char c) {
  return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

bool is_option_token(const std::string& t) {
  // "-" (standard output) and negative numbers ("-1N", "-.5") are values, not options.
  if (t.size() < 2 || t[0] != '-') return false;
  const char c = t[1] == '-' ? (t.size() > 2 ? t[2] : '\0') : t[1];
  return std::isalpha(static_cast<unsigned char>(c)) != 0;
}

std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const auto& l : o->get_lnames()) names.push_back("--" + l);
    for (const auto& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + cost});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string nearest(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

std::string parse_error_message(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::vector<std::string> commands;
  std::vector<CLI::App*> subs = app.get_subcommands([](CLI::App*) { return true; });
  for (const CLI::App* s : subs) commands.push_back(s->get_name());
  // The command given: the first argument naming one.
  CLI::App* sub = nullptr;
  std::size_t sub_at = args.size();
  for (std::size_t i = 0; i < args.size() && !sub; ++i) {
    if (args[i] == "--") break;
    for (CLI::App* s : subs) {
      if (s->get_name() == args[i]) {
        sub = s;
        sub_at = i;
      }
    }
  }
  if (!sub) {
    // No command, or a mistyped one: the first argument that is not an option.
    for (const auto& a : args) {
      if (is_option_token(a)) {
        if (app.get_option_no_throw(a.substr(0, a.find('='))) != nullptr) continue;
        const auto near = nearest(a, option_names(app));
        return fmt::format(
            "unknown option {} of asperity{}; give a command first: {} (asperity "
            "--help)",
            a, near.empty() ? "" : fmt::format(" (did you mean {}?)", near), join(commands));
      }
      const auto near = nearest(a, commands);
      return fmt::format("unknown command \"{}\"{}: the commands are {} (asperity --help)", a,
                         near.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", near),
                         join(commands));
    }
    return fmt::format("a command is required: {} (asperity --help)", join(commands));
  }
  const std::string help = fmt::format("asperity {} --help", sub->get_name());
  const auto names = option_names(*sub);
  for (std::size_t i = sub_at + 1; i < args.size(); ++i) {
    const auto& a = args[i];
    if (a == "--") break;
    if (!is_option_token(a)) continue;
    const std::string name = a.substr(0, a.find('='));
    if (sub->get_option_no_throw(name) != nullptr) continue;
    const auto near = nearest(name, names);
    return fmt::format("unknown option {} of asperity {}{}: {} lists the options", name,
                       sub->get_name(),
                       near.empty() ? "" : fmt::format(" (did you mean {}?)", near), help);
  }
  return fmt::format("{} ({} lists the options)", e.what(), help);
}

}  // namespace asperity::cli
