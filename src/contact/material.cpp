#include "asperity/contact/material.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::contact {

using core::require_in_half_open;
using core::require_non_negative;
using core::require_positive;

void Material::validate(std::string_view name) const {
  const std::string n(name);
  require_positive(n + ".E", E);
  require_in_half_open(n + ".nu", nu, 0.0, 0.5);
  require_non_negative(n + ".G (0 = derive from E and nu)", G);
  if (G > 0.0) require_shear_modulus_range(n + ".G", G, n + ".E", E);
  require_non_negative(n + ".H (0 = not given)", H);
}

void require_shear_modulus_range(std::string_view G_name, double G, std::string_view E_name,
                                 double E) {
  if (G >= E / 3.0 && G <= E / 2.0) return;
  throw InvalidInput(fmt::format(
      "{} = {} Pa is not allowed with {} = {} Pa: an isotropic material has G = E/(2(1 + nu)), "
      "so 0 <= nu <= 0.5 needs E/3 <= G <= E/2 ({} to {} Pa; G <= E/2 is nu >= 0, G >= E/3 is "
      "nu <= 0.5)",
      G_name, core::format_value(G), E_name, core::format_value(E), core::format_value(E / 3.0),
      core::format_value(E / 2.0)));
}

std::vector<std::string> hardness_warnings(double H, double E_star) {
  std::vector<std::string> w;
  const double ratio = H / E_star;
  if (ratio < 1e-3 || ratio > 0.2) {
    w.push_back(fmt::format(
        "hardness H = {} Pa is {:.3g} E*: outside 1e-3 to 0.2 E* (lead to diamond-like "
        "coatings), where the asperity laws were built; the critical interference omega_c = "
        "(pi K H/(2 E*))^2 R (Eq. 3.5) and everything normalized by it are far from any "
        "measured contact",
        core::format_value(H), ratio));
  }
  return w;
}

double Material::shear_modulus() const {
  return G > 0.0 ? G : E / (2.0 * (1.0 + nu));
}

double hardness_factor(double nu) {
  return 0.454 + 0.41 * nu;
}

ContactPair ContactPair::combine(const Material& body1, const Material& body2, double R1,
                                 double R2) {
  body1.validate("body1");
  body2.validate("body2");
  require_positive("R1", R1);
  if (!(R2 > 0.0)) {
    throw InvalidInput(fmt::format("R2 = {} is not allowed: it must be > 0 (infinity for a flat)",
                                   core::format_value(R2)));
  }
  if (body1.H <= 0.0 && body2.H <= 0.0) {
    throw InvalidInput(
        "hardness: neither body has a hardness H > 0; give the hardness of the softer material");
  }
  ContactPair p;
  p.E_star = 1.0 / ((1.0 - body1.nu * body1.nu) / body1.E + (1.0 - body2.nu * body2.nu) / body2.E);
  p.G_star =
      1.0 / ((2.0 - body1.nu) / body1.shear_modulus() + (2.0 - body2.nu) / body2.shear_modulus());
  p.R = std::isinf(R2) ? R1 : 1.0 / (1.0 / R1 + 1.0 / R2);
  const bool first_softer = body1.H > 0.0 && (body2.H <= 0.0 || body1.H <= body2.H);
  const Material& softer = first_softer ? body1 : body2;
  p.H = softer.H;
  p.nu = softer.nu;
  // The combined values can leave the double range for moduli of extreme magnitude.
  if (!std::isfinite(p.E_star) || !(p.E_star > 0.0)) {
    throw InvalidInput(fmt::format(
        "E* = 1/((1 - nu1^2)/E1 + (1 - nu2^2)/E2) = {} for E1 = {} Pa, E2 = {} Pa: it must be a "
        "finite number > 0",
        core::format_value(p.E_star), core::format_value(body1.E), core::format_value(body2.E)));
  }
  if (!std::isfinite(p.G_star) || !(p.G_star > 0.0)) {
    throw InvalidInput(fmt::format(
        "G* = 1/((2 - nu1)/G1 + (2 - nu2)/G2) = {} for G1 = {} Pa, G2 = {} Pa: it must be a "
        "finite number > 0",
        core::format_value(p.G_star), core::format_value(body1.shear_modulus()),
        core::format_value(body2.shear_modulus())));
  }
  p.validate();
  return p;
}

void ContactPair::validate() const {
  require_positive("E_star", E_star);
  require_positive("G_star", G_star);
  require_positive("R", R);
  require_positive("H", H);
  require_in_half_open("nu", nu, 0.0, 0.5);
}

CriticalValues ContactPair::critical() const {
  // Eq. 3.5 / B.9
  const double a_c = std::numbers::pi * K() * H * R / (2.0 * E_star);
  const double omega_c = a_c * a_c / R;
  const double P_c = 2.0 / 3.0 * K() * H * std::numbers::pi * a_c * a_c;
  return {omega_c, a_c, P_c};
}

}  // namespace asperity::contact
