#include "asperity/contact/normal_law.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "asperity/contact/material.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::contact {

std::string_view to_string(NormalLaw law) {
  switch (law) {
    case NormalLaw::hertz:
      return "hertz";
    case NormalLaw::ceb:
      return "ceb";
    case NormalLaw::ke:
      return "ke";
    case NormalLaw::bke:
      return "bke";
  }
  return "?";
}

NormalLaw parse_normal_law(std::string_view name) {
  for (auto law : {NormalLaw::hertz, NormalLaw::ceb, NormalLaw::ke, NormalLaw::bke}) {
    if (name == to_string(law)) return law;
  }
  throw InvalidInput(
      fmt::format("normal law \"{}\" is unknown: allowed are hertz, ceb, ke, bke", name));
}

BkeConstants BkeConstants::for_poisson(double nu) {
  core::require_in_half_open("nu", nu, 0.0, 0.5);
  BkeConstants c;
  c.l_c = 8.88 * nu - 10.13 * (nu * nu + 0.089);
  c.delta_c = 6.82 * nu - 7.83 * (nu * nu + 0.0586);
  c.alpha = 0.174 + 0.08 * nu;
  c.gamma = 0.25 + 0.125 * nu;
  if (!(c.l_c > 0.0) || !(c.delta_c > 0.0)) {
    throw InvalidInput(fmt::format(
        "nu = {} is outside the range of the BKE fits: l_c = {:.4g} and delta_c = {:.4g} must "
        "be > 0, which needs nu in about (0.118, 0.5)",
        core::format_value(nu), c.l_c, c.delta_c));
  }
  c.load_scale = c.l_c / (c.delta_c * std::sqrt(c.delta_c));
  c.delta_c_alpha = std::pow(c.delta_c, c.alpha);
  c.delta_c_gamma = std::pow(c.delta_c, c.gamma);
  return c;
}

namespace {

void check_interference(double w) {
  core::require_non_negative("interference w = omega/omega_c", w);
}

// Beyond this interference w^1.5 may overflow while P/P_c (which grows only like
// w^(1.5 - alpha)) is still a double: B.4 is then evaluated in logarithms.
constexpr double kBkeLogForm = 1e150;

double bke_load(const BkeConstants& c, double w) {
  // B.4
  const double elastic = c.load_scale * w * std::sqrt(w);
  if (w <= c.delta_c) return elastic;
  const double gap = std::pow(w, c.alpha) - c.delta_c_alpha;
  // Just above delta_c the rounded gap can be 0: the factor is then exactly 1 (B.4's limit).
  if (!(gap > 0.0)) return elastic;
  // 1 - exp(-x) as -expm1(-x): exact also where x = da/gap is below the round-off of 1.
  const double factor = -std::expm1(-c.delta_c_alpha / gap);
  if (w > kBkeLogForm)
    return std::exp(std::log(c.load_scale) + 1.5 * std::log(w) + std::log(factor));
  return elastic * factor;
}

}  // namespace

namespace detail {

double normal_load_star(NormalLaw law, double w, double K, const BkeConstants& bke) {
  switch (law) {
    case NormalLaw::hertz:  // B.1
      return w * std::sqrt(w);
    case NormalLaw::ceb:  // B.2
      return w <= 1.0 ? w * std::sqrt(w) : 3.0 * (w - 0.5);
    case NormalLaw::ke:  // B.3
      if (w <= 1.0) return w * std::sqrt(w);
      if (w <= 6.0) return 1.03 * std::pow(w, 1.425);
      if (w <= 110.0) return 1.4 * std::pow(w, 1.263);
      return 3.0 / K * w;
    case NormalLaw::bke:
      return bke_load(bke, w);
  }
  return 0.0;
}

double contact_radius_star(NormalLaw law, double w, const BkeConstants& c) {
  switch (law) {
    case NormalLaw::hertz:  // B.5
      return std::sqrt(w);
    case NormalLaw::ceb:  // B.6
      return w <= 1.0 ? std::sqrt(w) : std::sqrt(2.0 * w - 1.0);
    case NormalLaw::ke:  // B.7
      if (w <= 1.0) return std::sqrt(w);
      if (w <= 6.0) return 0.96 * std::pow(w, 0.57);
      if (w <= 110.0) return 0.97 * std::pow(w, 0.57);
      return 1.41 * std::sqrt(w);
    case NormalLaw::bke: {  // B.8
      const double scale = 1.0 / std::sqrt(c.delta_c);
      if (w <= c.delta_c) return scale * std::sqrt(w);
      const double gap = std::pow(w, c.gamma) - c.delta_c_gamma;
      if (!(gap > 0.0)) return scale * std::sqrt(w);  // B.8's limit at delta_c
      return scale * std::sqrt(w) * std::sqrt(1.0 + std::exp(-c.delta_c_gamma / gap));
    }
  }
  return 0.0;
}

}  // namespace detail

namespace {
BkeConstants constants_for(NormalLaw law, double nu) {
  return law == NormalLaw::bke ? BkeConstants::for_poisson(nu) : BkeConstants{};
}
}  // namespace

double normal_load_star(NormalLaw law, double w, double nu) {
  check_interference(w);
  core::require_in_half_open("nu", nu, 0.0, 0.5);
  return detail::normal_load_star(law, w, hardness_factor(nu), constants_for(law, nu));
}

double contact_radius_star(NormalLaw law, double w, double nu) {
  check_interference(w);
  core::require_in_half_open("nu", nu, 0.0, 0.5);
  return detail::contact_radius_star(law, w, constants_for(law, nu));
}

double interference_star(NormalLaw law, double P_star, double nu) {
  core::require_non_negative("normal load P/P_c", P_star);
  switch (law) {
    case NormalLaw::hertz:
      return std::pow(P_star, 2.0 / 3.0);
    case NormalLaw::ceb:
      if (P_star <= 1.0) return std::pow(P_star, 2.0 / 3.0);
      if (P_star <= 1.5) return 1.0;  // inside the jump at w = 1
      return P_star / 3.0 + 0.5;
    case NormalLaw::ke: {
      if (P_star <= 1.0) return std::pow(P_star, 2.0 / 3.0);
      const double p6 = 1.03 * std::pow(6.0, 1.425);
      if (P_star <= 1.03) return 1.0;
      if (P_star <= p6) return std::pow(P_star / 1.03, 1.0 / 1.425);
      const double p6_next = 1.4 * std::pow(6.0, 1.263);
      if (P_star <= p6_next) return 6.0;
      const double p110 = 1.4 * std::pow(110.0, 1.263);
      if (P_star <= p110) return std::pow(P_star / 1.4, 1.0 / 1.263);
      const double p110_next = 3.0 / hardness_factor(nu) * 110.0;
      if (P_star <= p110_next) return 110.0;
      return P_star * hardness_factor(nu) / 3.0;
    }
    case NormalLaw::bke: {
      const auto c = BkeConstants::for_poisson(nu);
      const double scale = c.l_c / std::pow(c.delta_c, 1.5);
      if (P_star <= scale * std::pow(c.delta_c, 1.5)) return std::pow(P_star / scale, 2.0 / 3.0);
      // Plastic branch, monotone in w. The factor 1 - exp(-x) of B.4 lies between
      // x/(1 + x) and 1 (x = delta_c^alpha/(w^alpha - delta_c^alpha)), so
      //   scale delta_c^alpha w^(1.5 - alpha) <= P/P_c <= scale w^1.5,
      // which brackets the root in closed form for any finite P/P_c (in logarithms:
      // w reaches ~1e236 at the largest double).
      const double log_lo = 2.0 / 3.0 * (std::log(P_star) - std::log(scale));
      const double log_hi =
          (std::log(P_star) - std::log(scale) - c.alpha * std::log(c.delta_c)) / (1.5 - c.alpha);
      // Widened by 1e-9 against round-off at the bounds (the log form of B.4 is good to
      // ~1e-13); f(delta_c) < 0 since P/P_c is above the elastic branch's end.
      const double lo = std::max(c.delta_c, std::exp(log_lo) * (1.0 - 1e-9));
      const double hi = std::max(lo, std::exp(log_hi)) * (1.0 + 1e-9);
      if (!std::isfinite(hi)) {
        throw NumericalError(
            fmt::format("BKE inverse: P/P_c = {} needs an interference beyond "
                        "the double range",
                        core::format_value(P_star)));
      }
      if (hi > 16.0 * lo) {
        // A bracket over decades (very large P/P_c): in logarithms, where the load is
        // nearly linear (slope 1.5 - alpha to 1.5), TOMS 748 converges in a few steps.
        const double log_P = std::log(P_star);
        const double u = core::find_root(
            [&](double x) { return std::log(bke_load(c, std::exp(x))) - log_P; }, std::log(lo),
            std::log(hi), "BKE interference for a load (logarithmic)", 62);
        return std::exp(u);
      }
      return core::find_root([&](double w) { return bke_load(c, w) - P_star; }, lo, hi,
                             "BKE interference for a load", 62);
    }
  }
  return 0.0;
}

}  // namespace asperity::contact
