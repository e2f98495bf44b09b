#include "asperity/contact/friction_law.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "asperity/contact/material.hpp"
#include "asperity/contact/normal_law.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::contact {

std::string_view to_string(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::cfc:
      return "cfc";
    case FrictionLaw::ceb:
      return "ceb";
    case FrictionLaw::ke:
      return "ke";
    case FrictionLaw::bke:
      return "bke";
  }
  return "?";
}

FrictionLaw parse_friction_law(std::string_view name) {
  for (auto law : {FrictionLaw::cfc, FrictionLaw::ceb, FrictionLaw::ke, FrictionLaw::bke}) {
    if (name == to_string(law)) return law;
  }
  throw InvalidInput(
      fmt::format("friction law \"{}\" is unknown: allowed are cfc, ceb, ke, bke", name));
}

void FrictionParameters::validate() const {
  core::require_positive("mu_cfc", mu_cfc);
  core::require_positive("zeta", zeta);
}

double cfc_coefficient(double shear_strength, double hardness) {
  core::require_positive("shear strength s", shear_strength);
  core::require_positive("hardness H", hardness);
  return shear_strength / hardness;  // B.10
}

namespace {

struct CebBranches {
  double surface;     // 0.2045/(K|c1|) (1/w - 1)^{1/2}
  double subsurface;  // (-c4 + sqrt(c4^2 - 4 c3 c5))/(2 c3)
};

CebBranches ceb_branches(double w, double nu, double zeta) {
  const double K = hardness_factor(nu);
  // B.11
  const double c1 =
      -1.0 + 1.5 * zeta * std::atan(1.0 / zeta) - zeta * zeta / (2.0 * (1.0 + zeta * zeta));
  const double c3 = 9.0 * M_PI * M_PI / 16.0 * (2.0 - nu / 2.0 + 7.0 / 8.0 * nu * nu);
  const double c4 = 9.0 * M_PI / 4.0 * (1.0 - 2.0 * nu) * (1.0 - nu / 2.0);
  const double c5 = 1.5 * (1.0 - 2.0 * nu) * (1.0 - 2.0 * nu) - 0.56 / (K * K * w);
  return {0.2045 / (K * std::abs(c1)) * std::sqrt(1.0 / w - 1.0),
          (-c4 + std::sqrt(c4 * c4 - 4.0 * c3 * c5)) / (2.0 * c3)};
}

double ceb_coefficient(double w, double nu, double zeta) {
  if (w >= 1.0) return 0.0;  // sliding inception = first yield: no friction once yielded
  const auto b = ceb_branches(w, nu, zeta);
  return std::min(b.surface, b.subsurface);
}

double ke_coefficient(double w) {
  // B.12
  if (w <= 1.0) return 0.536 / std::sqrt(w) - 0.0186 * std::sqrt(w);
  if (w <= 6.2) return ((-0.007 * w + 0.085) * w - 0.389) * w + 0.822;
  return 0.0;
}

double bke_coefficient(double w, double delta_c) {
  // B.13 (SEED_NOTES.md: this grouping of delta_c reproduces Table 3.2)
  return 0.26 / std::tanh(0.27 * std::pow(w / delta_c, 0.46));
}

}  // namespace

double friction_coefficient(FrictionLaw law, double w, double nu,
                            const FrictionParameters& params) {
  params.validate();
  core::require_in_half_open("nu", nu, 0.0, 0.5);
  if (law == FrictionLaw::cfc) {
    core::require_non_negative("interference w = omega/omega_c", w);
    return params.mu_cfc;
  }
  if (!(w > 0.0) || !std::isfinite(w)) {
    throw InvalidInput(fmt::format(
        "interference w = omega/omega_c = {} is not allowed for the {} friction law: it must be "
        "> 0 (mu diverges at w = 0)",
        core::format_value(w), to_string(law)));
  }
  const double delta_c = law == FrictionLaw::bke ? BkeConstants::for_poisson(nu).delta_c : 0.0;
  return detail::friction_coefficient(law, w, nu, delta_c, params);
}

namespace detail {

double friction_coefficient(FrictionLaw law, double w, double nu, double delta_c,
                            const FrictionParameters& params) {
  switch (law) {
    case FrictionLaw::ceb:
      return ceb_coefficient(w, nu, params.zeta);
    case FrictionLaw::ke:
      return ke_coefficient(w);
    case FrictionLaw::bke:
      return bke_coefficient(w, delta_c);
    case FrictionLaw::cfc:
      break;
  }
  return params.mu_cfc;
}

}  // namespace detail

std::optional<double> ceb_branch_crossing(double nu, double zeta) {
  auto diff = [&](double w) {
    const auto b = ceb_branches(w, nu, zeta);
    return b.surface - b.subsurface;
  };
  // Sample (0, 1) for a sign change; the surface branch vanishes at w = 1.
  double prev_w = 1e-6;
  double prev = diff(prev_w);
  for (int i = 1; i <= 200; ++i) {
    const double w = 1e-6 + (1.0 - 2e-6) * i / 200.0;
    const double cur = diff(w);
    if ((prev < 0.0) != (cur < 0.0)) {
      return core::find_root(diff, prev_w, w, "CEB branch crossing", 60);
    }
    prev_w = w;
    prev = cur;
  }
  return std::nullopt;
}

double static_friction_star(FrictionLaw law, double w, double nu, double normal_load_star,
                            const FrictionParameters& params) {
  if (w == 0.0) return 0.0;
  return friction_coefficient(law, w, nu, params) * normal_load_star;
}

}  // namespace asperity::contact
