#pragma once
// Internal to the reader of joint case files (asperity/joint/case.hpp): case_parse.cpp
// reads the file, case_interface.cpp its [interface] table; both through Reader, whose
// errors name the file, the line, the key and what is allowed. toml++ is a private
// dependency: no public header includes it.
#include <fmt/format.h>

#include <toml++/toml.h>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/units.hpp"
#include "asperity/joint/case.hpp"

namespace asperity::joint::detail {

namespace dim = core::dim;

// Error context: the file and the line of a node.
class Reader {
 public:
  Reader(std::string source, std::string base_dir)
      : source_(std::move(source)), base_(std::move(base_dir)) {}

  [[noreturn]] void fail(const toml::node* n, const std::string& key,
                         const std::string& what) const {
    const auto line = n ? n->source().begin.line : 0U;
    if (line > 0) throw InvalidInput(fmt::format("{}:{}: {}: {}", source_, line, key, what));
    throw InvalidInput(fmt::format("{}: {}: {}", source_, key, what));
  }

  // "FILE:LINE: key" of a node.
  [[nodiscard]] std::string origin(const toml::node* n, const std::string& key) const {
    const auto line = n ? n->source().begin.line : 0U;
    if (line > 0) return fmt::format("{}:{}: {}", source_, line, key);
    return fmt::format("{}: {}", source_, key);
  }

  // The value as the user wrote it: "\"-1.2 lbf*in\"" or "0.24".
  static std::string text_of(const toml::node* n) {
    if (!n) return "";
    if (const auto s = n->value<std::string>()) return fmt::format("\"{}\"", *s);
    if (n->is_boolean()) return *n->value<bool>() ? "true" : "false";
    if (const auto v = n->value<double>()) return fmt::format("{}", *v);
    return "(a table or array)";
  }

  // "FILE:LINE: key = TEXT: what".
  [[noreturn]] void fail_value(const toml::node* n, const std::string& key,
                               const std::string& what) const {
    throw InvalidInput(fmt::format("{} = {}: {}", origin(n, key), text_of(n), what));
  }

  void check_keys(const toml::table& t, const std::string& where,
                  const std::set<std::string>& allowed) const {
    for (const auto& [k, v] : t) {
      const std::string key(k.str());
      if (!allowed.count(key)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        const std::string full = where.empty() ? key : where + "." + key;
        // The key's own position is the best line to report.
        const auto line = k.source().begin.line > 0 ? k.source().begin.line : v.source().begin.line;
        throw InvalidInput(fmt::format("{}:{}: {}: unknown key (allowed in [{}]: {})", source_,
                                       line, full, where.empty() ? "top level" : where, list));
      }
    }
  }

  const toml::table& table(const toml::table& parent, const std::string& key,
                           const std::string& where) const {
    const auto* n = parent.get(key);
    const std::string full = where.empty() ? key : where + "." + key;
    if (!n) fail(&parent, full, "missing (required table)");
    const auto* t = n->as_table();
    if (!t) fail(n, full, "must be a table");
    return *t;
  }

  // What to write instead of a string for a dimensionless key: the number it starts
  // with, if any, without quotes and without the unit.
  static std::string dimensionless_advice(const std::string& name, const std::string& text) {
    const auto first = text.find_first_not_of(" \t");
    const char* begin = text.data() + (first == std::string::npos ? text.size() : first);
    const char* end = text.data() + text.size();
    double x = 0.0;
    const auto [ptr, ec] = std::from_chars(begin, end, x);
    if (ec != std::errc() || !std::isfinite(x)) {
      return fmt::format(
          "{} is dimensionless: write a bare number without quotes or unit, e.g. {} = 0.3", name,
          name);
    }
    const std::string rest(ptr, end);
    if (rest.find_first_not_of(" \t") == std::string::npos) {
      return fmt::format("a dimensionless value is a bare number, not a string: write {} = {}",
                         name, std::string(begin, ptr));
    }
    return fmt::format(
        "{} is dimensionless and takes no unit: write {} = {} (no quotes, no \"{}\")", name, name,
        std::string(begin, ptr), rest.substr(rest.find_first_not_of(" \t")));
  }

  // A quantity: a string with units, or a bare number for dimensionless ones.
  double quantity(const toml::node& n, core::Dimension d, const std::string& key) const {
    if (const auto s = n.value<std::string>(); s && d == dim::dimensionless) {
      // One spelling for dimensionless values: a bare number (nu = 0.24), without a unit.
      fail_value(&n, key, dimensionless_advice(key.substr(key.rfind('.') + 1), *s));
    }
    try {
      if (n.is_floating_point() || n.is_integer()) {
        const double x = *n.value<double>();
        if (d == dim::dimensionless) return x;
        return core::parse_quantity(fmt::format("{}", x), d, key);  // names the missing unit
      }
      if (const auto s = n.value<std::string>()) return core::parse_quantity(*s, d, key);
    } catch (const InvalidInput& e) {
      // parse_quantity's message names the key already.
      const std::string msg = e.what();
      if (msg.starts_with(key))
        throw InvalidInput(fmt::format("{}:{}: {}", source_, n.source().begin.line, msg));
      fail(&n, key, msg);
    }
    fail(&n, key,
         d == dim::dimensionless ? "must be a number"
                                 : fmt::format("must be a quantity string with units of {}, e.g. "
                                               "\"{}\"",
                                               core::dimension_name(d), example(d)));
  }

  std::optional<double> optional_quantity(const toml::table& t, const std::string& key,
                                          core::Dimension d, const std::string& where) const {
    const auto* n = t.get(key);
    if (!n) return std::nullopt;
    return quantity(*n, d, where + "." + key);
  }

  double required(const toml::table& t, const std::string& key, core::Dimension d,
                  const std::string& where) const {
    const auto v = optional_quantity(t, key, d, where);
    if (!v) fail(&t, where + "." + key, "missing");
    return *v;
  }

  double positive(const toml::table& t, const std::string& key, core::Dimension d,
                  const std::string& where) const {
    const double v = required(t, key, d, where);
    if (!(v > 0.0) || !std::isfinite(v)) fail_value(t.get(key), where + "." + key, "must be > 0");
    return v;
  }

  std::vector<double> quantity_list(const toml::node& n, core::Dimension d, const std::string& key,
                                    bool must_be_positive) const {
    const auto* a = n.as_array();
    if (!a) fail(&n, key, "must be an array, e.g. [\"1 um\", \"2 um\"]");
    if (a->empty()) fail(&n, key, "must not be empty");
    std::vector<double> out;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string k = fmt::format("{}[{}]", key, i + 1);
      const double v = quantity(*a->get(i), d, k);
      if (must_be_positive && (!(v > 0.0) || !std::isfinite(v))) {
        fail_value(a->get(i), k, "must be > 0");
      }
      out.push_back(v);
    }
    return out;
  }

  std::string string(const toml::table& t, const std::string& key, const std::string& where,
                     const std::string& dflt) const {
    const auto* n = t.get(key);
    if (!n) return dflt;
    if (const auto s = n->value<std::string>()) return *s;
    fail(n, where + "." + key, "must be a string");
  }

  [[nodiscard]] std::string resolve(const std::string& p) const {
    const std::filesystem::path path(p);
    return path.is_absolute() ? p
                              : (std::filesystem::path(base_) / path).lexically_normal().string();
  }

  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  static const char* example(core::Dimension d) {
    if (d == dim::length) return "2.9 mm";
    if (d == dim::area) return "170 mm^2";
    if (d == dim::pressure) return "200 GPa";
    if (d == dim::force) return "526 N";
    if (d == dim::energy) return "0.305 N*m";
    if (d == dim::stiffness) return "38 N/um";
    if (d == dim::inverse_area) return "3.34e-4 um^-2";
    return "1";
  }
  std::string source_;
  std::string base_;
};

/// Reads the [interface] table `node` into c.interface (case_interface.cpp).
void parse_interface(const Reader& r, const toml::node& node, JointCase& c);

}  // namespace asperity::joint::detail
