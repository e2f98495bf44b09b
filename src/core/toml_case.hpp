#pragma once
// Case-file helpers shared by the TOML readers of the library (dynamics and vibration
// case files): unknown keys named with their line, typed look-ups with messages that name
// the key, and the lines a subtree occupies. Internal to src/ (toml++ is a private
// dependency: no public header includes it).
#include <fmt/format.h>

#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "asperity/core/error.hpp"

namespace asperity::core::toml_case {

/// The document of a case file; a syntax error is InvalidInput "PATH: what (line N)".
inline toml::table parse(std::string_view text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InvalidInput(
        fmt::format("{}: {} (line {})", path, e.description(), e.source().begin.line));
  }
}

inline std::uint32_t line_of(const toml::node& n) {
  return n.source().begin.line;
}

/// " (line N)" when the node has a source line, else "".
inline std::string at_line(const toml::node& n) {
  return line_of(n) > 0 ? fmt::format(" (line {})", line_of(n)) : std::string();
}

/// t[key], a name read by `parse` (which throws InvalidInput listing the allowed names), or
/// `dflt` when absent. A wrong name or type is InvalidInput "FILE:LINE: WHERE.KEY = VALUE: "
/// followed by `parse`'s message.
template <class Parse>
auto named_choice(const toml::table& t, const std::string& key, const std::string& where,
                  const std::string& dflt, Parse parse) {
  const auto* n = t.get(key);
  if (!n) return parse(dflt);
  const auto& src = n->source();
  const std::string place =
      src.path ? fmt::format("{}:{}: ", *src.path, line_of(*n)) : std::string();
  const auto name = n->value<std::string>();
  if (!name) throw InvalidInput(fmt::format("{}{}.{} must be a string", place, where, key));
  try {
    return parse(*name);
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}{}.{} = \"{}\": {}", place, where, key, *name, e.what()));
  }
}

/// Throws InvalidInput naming the first key of `t` not in `allowed`, its line, and the
/// allowed keys.
inline void check_keys(const toml::table& t, const std::string& where,
                       const std::set<std::string>& allowed) {
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (!allowed.count(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      const auto line = k.source().begin.line > 0 ? k.source().begin.line : v.source().begin.line;
      const std::string at = line > 0 ? fmt::format(" at line {}", line) : std::string();
      throw InvalidInput(fmt::format("{}: unknown key \"{}\"{} (allowed: {})",
                                     where.empty() ? std::string("top level") : where, key, at,
                                     list));
    }
  }
}

/// t[key] as a table (nullptr when absent); InvalidInput when it is something else.
inline const toml::table* subtable(const toml::table& t, const std::string& key,
                                   const std::string& where) {
  const auto* n = t.get(key);
  if (!n) return nullptr;
  const auto* tt = n->as_table();
  if (!tt) throw InvalidInput(fmt::format("{}.{} must be a table{}", where, key, at_line(*n)));
  return tt;
}

/// t[key] as a finite number (`dflt` when absent); InvalidInput naming the key otherwise.
inline double number(const toml::table& t, const std::string& key, const std::string& where,
                     double dflt) {
  const auto* n = t.get(key);
  if (!n) return dflt;
  if (auto x = n->value<double>(); x && (n->is_floating_point() || n->is_integer())) {
    if (!std::isfinite(*x)) {
      throw InvalidInput(fmt::format("{}.{} = {} must be finite{}", where, key, *x, at_line(*n)));
    }
    return *x;
  }
  throw InvalidInput(fmt::format("{}.{} must be a number{}", where, key, at_line(*n)));
}

/// Every source line the node occupies: a [header] table only its header line (its
/// region may span other tables), [[header]] arrays only their tables' headers.
inline void collect_lines(const toml::node& n, std::set<std::uint32_t>& lines) {
  auto add = [&lines](const toml::source_region& r) {
    if (r.begin.line == 0) return;
    for (auto l = r.begin.line; l <= std::max(r.begin.line, r.end.line); ++l) lines.insert(l);
  };
  if (const auto* t = n.as_table()) {
    if (t->is_inline()) {
      add(t->source());
    } else if (t->source().begin.line > 0) {
      lines.insert(t->source().begin.line);
    }
    for (const auto& [k, v] : *t) {
      add(k.source());
      collect_lines(v, lines);
    }
    return;
  }
  if (const auto* a = n.as_array()) {
    const bool headers =
        a->is_array_of_tables() && !a->empty() && !a->get(0)->as_table()->is_inline();
    if (!headers) add(a->source());
    for (const auto& e : *a) collect_lines(e, lines);
    return;
  }
  add(n.source());
}

/// `text` with the given (1-based) lines blanked, the others at their line numbers: what
/// a reader of the rest of a case file sees, so that its errors point into the user's file.
inline std::string without_lines(const std::string& text, const std::set<std::uint32_t>& lines) {
  std::string out;
  out.reserve(text.size());
  std::uint32_t line = 1;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    if (!lines.count(line)) out.append(text, begin, end - begin);
    if (end == text.size()) break;
    out += '\n';
    begin = end + 1;
    ++line;
  }
  return out;
}

}  // namespace asperity::core::toml_case
