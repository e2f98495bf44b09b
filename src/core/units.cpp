#include "asperity/core/units.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>

#include "asperity/core/error.hpp"

namespace asperity::core {
namespace {

struct UnitDef {
  std::string_view symbol;
  double factor;  // SI value of one unit
  Dimension dimension;
  bool prefixable;
};

constexpr double kLbf = 4.4482216152605;
constexpr double kInch = 0.0254;

constexpr std::array<UnitDef, 16> kUnits{{
    {"m", 1.0, dim::length, true},
    {"g", 1e-3, dim::mass, true},
    {"s", 1.0, dim::time, true},
    {"N", 1.0, dim::force, true},
    {"Pa", 1.0, dim::pressure, true},
    {"J", 1.0, dim::energy, true},
    {"W", 1.0, Dimension{2, 1, -3}, true},
    {"Hz", 1.0, dim::frequency, true},
    {"in", kInch, dim::length, false},
    {"ft", 12.0 * kInch, dim::length, false},
    {"lbf", kLbf, dim::force, false},
    {"psi", kLbf / (kInch * kInch), dim::pressure, false},
    {"ksi", 1e3 * kLbf / (kInch * kInch), dim::pressure, false},
    {"min", 60.0, dim::time, false},
    {"h", 3600.0, dim::time, false},
    {"rad", 1.0, dim::dimensionless, false},
}};

struct Prefix {
  std::string_view symbol;
  double factor;
};
constexpr std::array<Prefix, 12> kPrefixes{{{"p", 1e-12},
                                            {"n", 1e-9},
                                            {"u", 1e-6},
                                            {"\xC2\xB5", 1e-6},  // µ (micro sign)
                                            {"\xCE\xBC", 1e-6},  // μ (Greek mu)
                                            {"m", 1e-3},
                                            {"c", 1e-2},
                                            {"d", 1e-1},
                                            {"k", 1e3},
                                            {"M", 1e6},
                                            {"G", 1e9},
                                            {"T", 1e12}}};

std::optional<Quantity> lookup_unit(std::string_view symbol) {
  for (const auto& u : kUnits) {
    if (u.symbol == symbol) return Quantity{u.factor, u.dimension};
  }
  for (const auto& p : kPrefixes) {
    if (symbol.size() <= p.symbol.size() || symbol.substr(0, p.symbol.size()) != p.symbol) {
      continue;
    }
    const auto rest = symbol.substr(p.symbol.size());
    for (const auto& u : kUnits) {
      if (u.prefixable && u.symbol == rest) return Quantity{p.factor * u.factor, u.dimension};
    }
  }
  return std::nullopt;
}

bool is_space(char c) {
  return c == ' ' || c == '\t';
}
bool is_symbol_char(unsigned char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c >= 0x80;
}

[[noreturn]] void fail(std::string_view field, std::string_view text, std::string_view why) {
  throw InvalidInput(fmt::format("{} = \"{}\" is not a valid quantity: {}", field, text, why));
}

}  // namespace

std::string dimension_name(Dimension d) {
  struct Named {
    Dimension d;
    std::string_view name;
  };
  static constexpr std::array<Named, 12> kNames{{{dim::dimensionless, "dimensionless"},
                                                 {dim::length, "length (e.g. um, mm, m, in)"},
                                                 {dim::area, "area (e.g. mm^2)"},
                                                 {dim::inverse_area, "1/area (e.g. um^-2)"},
                                                 {dim::time, "time (e.g. s, ms)"},
                                                 {dim::frequency, "frequency (e.g. Hz)"},
                                                 {dim::mass, "mass (e.g. kg, g)"},
                                                 {dim::force, "force (e.g. N, kN, lbf)"},
                                                 {dim::pressure, "pressure (e.g. Pa, MPa, GPa)"},
                                                 {dim::energy, "energy or torque (e.g. J, N*m)"},
                                                 {dim::stiffness, "stiffness (e.g. N/m, N/um)"},
                                                 {dim::velocity, "velocity (e.g. m/s)"}}};
  for (const auto& n : kNames) {
    if (n.d == d) return std::string(n.name);
  }
  std::string out;
  auto add = [&out](std::string_view sym, int e) {
    if (e == 0) return;
    if (!out.empty()) out += ' ';
    out += sym;
    if (e != 1) out += fmt::format("^{}", e);
  };
  add("m", d.m);
  add("kg", d.kg);
  add("s", d.s);
  return out;
}

Quantity parse_quantity(std::string_view text, std::string_view field) {
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n && is_space(text[i])) ++i;
  if (i == n) fail(field, text, "it is empty");

  double number = 0.0;
  const char* first = text.data() + i;
  // std::from_chars does not accept a leading '+'.
  if (text[i] == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, text.data() + n, number);
  if (ec == std::errc::result_out_of_range) {
    // from_chars says so for a magnitude beyond the double range in either direction.
    const std::string digits(first, static_cast<std::size_t>(ptr - first));
    const bool tiny = !std::isinf(std::strtod(digits.c_str(), nullptr));
    fail(field, text,
         tiny ? fmt::format("the number {} underflows: its magnitude is below the smallest "
                            "double ({:.3g}); write it with a unit prefix or as 0",
                            digits, std::numeric_limits<double>::denorm_min())
              : fmt::format("the number {} overflows: its magnitude is above the largest "
                            "double ({:.3g})",
                            digits, std::numeric_limits<double>::max()));
  }
  if (ec != std::errc() || ptr == first) fail(field, text, "it does not start with a number");
  if (!std::isfinite(number)) fail(field, text, "the number is not finite");
  i = static_cast<std::size_t>(ptr - text.data());

  Quantity q{number, dim::dimensionless};
  bool divide = false;
  bool expect_unit = false;
  bool any_unit = false;
  while (true) {
    while (i < n && is_space(text[i])) ++i;
    if (i == n) break;
    const char c = text[i];
    if (c == '*' || c == '.' || c == '/') {
      if (!any_unit || expect_unit) fail(field, text, fmt::format("unexpected '{}'", c));
      divide = (c == '/');
      expect_unit = true;
      ++i;
      continue;
    }
    if (text.substr(i, 2) == "\xC2\xB7") {  // middle dot
      if (!any_unit || expect_unit) fail(field, text, "unexpected '\xC2\xB7'");
      divide = false;
      expect_unit = true;
      i += 2;
      continue;
    }
    if (!is_symbol_char(static_cast<unsigned char>(c))) {
      fail(field, text, fmt::format("unexpected character '{}'", c));
    }
    const std::size_t start = i;
    // A symbol ends at a middle dot (U+00B7, bytes C2 B7), whose bytes are >= 0x80
    // like those of the micro sign: "N" U+00B7 "m" is N times m, not one symbol.
    while (i < n && is_symbol_char(static_cast<unsigned char>(text[i])) &&
           text.substr(i, 2) != "\xC2\xB7") {
      ++i;
    }
    const auto symbol = text.substr(start, i - start);
    const auto unit = lookup_unit(symbol);
    if (!unit) fail(field, text, fmt::format("unknown unit \"{}\"", symbol));
    int power = 1;
    if (i < n && text[i] == '^') {
      ++i;
      const auto [p, pec] = std::from_chars(text.data() + i, text.data() + n, power);
      if (pec != std::errc() || p == text.data() + i) fail(field, text, "'^' needs an integer");
      i = static_cast<std::size_t>(p - text.data());
      if (power == 0 || power < -6 || power > 6) fail(field, text, "unit power out of range");
    }
    if (divide) power = -power;
    q.value *= std::pow(unit->value, power);
    q.dimension.m += unit->dimension.m * power;
    q.dimension.kg += unit->dimension.kg * power;
    q.dimension.s += unit->dimension.s * power;
    any_unit = true;
    expect_unit = false;
    divide = false;
  }
  if (expect_unit) fail(field, text, "it ends with an operator");
  if (!std::isfinite(q.value)) {
    fail(field, text,
         "the value in SI units overflows (its magnitude is above the largest double)");
  }
  if (q.value == 0.0 && number != 0.0) {
    fail(field, text,
         "the value in SI units underflows to 0 (its magnitude is below the smallest double)");
  }
  return q;
}

double parse_quantity(std::string_view text, Dimension expected, std::string_view field) {
  const Quantity q = parse_quantity(text, field);
  if (q.dimension != expected) {
    throw InvalidInput(fmt::format("{} = \"{}\" has the units of {}, but {} is expected", field,
                                   text, dimension_name(q.dimension), dimension_name(expected)));
  }
  return q.value;
}

}  // namespace asperity::core
