#pragma once
// Quantities with units as text ("207 GPa", "2.91e-4 um^-2", "0.1525 N*m"), parsed
// into SI values with a dimension check. Used by the CLI and case files only: the
// library's APIs take SI doubles.
#include <string>
#include <string_view>

namespace asperity::core {

/// Exponents of metre, kilogram and second.
struct Dimension {
  int m = 0;
  int kg = 0;
  int s = 0;
  friend bool operator==(const Dimension&, const Dimension&) = default;
};

namespace dim {
inline constexpr Dimension dimensionless{0, 0, 0};
inline constexpr Dimension length{1, 0, 0};
inline constexpr Dimension area{2, 0, 0};
inline constexpr Dimension inverse_area{-2, 0, 0};
inline constexpr Dimension time{0, 0, 1};
inline constexpr Dimension frequency{0, 0, -1};
inline constexpr Dimension mass{0, 1, 0};
inline constexpr Dimension force{1, 1, -2};
inline constexpr Dimension pressure{-1, 1, -2};
inline constexpr Dimension energy{2, 1, -2};     ///< also torque (N*m)
inline constexpr Dimension stiffness{0, 1, -2};  ///< N/m
inline constexpr Dimension velocity{1, 0, -1};
}  // namespace dim

/// A value in SI base units and its dimension.
struct Quantity {
  double value = 0.0;
  Dimension dimension;
};

/// Human-readable name of a dimension ("length", "pressure", or "m^2 kg s^-2").
std::string dimension_name(Dimension d);

/// Parses "<number> [unit expression]". The unit expression is a product of unit
/// symbols with optional integer powers, joined by '*', '.', '·', '/' or a space:
/// "GPa", "um^-2", "mm^2", "N*m", "lbf*in", "N/um". SI prefixes p n u µ μ m c k M G
/// apply to m, g, s, N, Pa, J, W, Hz. Also: in, ft, lbf, psi, ksi, min, h.
/// Throws InvalidInput (naming `field`) on malformed text or an unknown unit.
Quantity parse_quantity(std::string_view text, std::string_view field = "quantity");

/// Parses and checks the dimension; returns the SI value. A bare number is accepted
/// only for dimensionless quantities.
double parse_quantity(std::string_view text, Dimension expected, std::string_view field);

}  // namespace asperity::core
