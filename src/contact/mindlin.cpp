#include "asperity/contact/mindlin.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::contact {

namespace mindlin {
namespace {

void require_unit_force(double Q_tilde, const char* what) {
  if (!std::isfinite(Q_tilde) || Q_tilde < 0.0 || Q_tilde > 1.0) {
    throw InvalidInput(
        fmt::format("{} = {} is not allowed: it must lie in [0, 1] (beyond 1 the contact slides)",
                    what, core::format_value(Q_tilde)));
  }
}

// Binomial coefficient C(r, k) for real r.
double binomial(double r, int k) {
  double c = 1.0;
  for (int j = 0; j < k; ++j) c *= (r - j) / (j + 1);
  return c;
}

// B.19 as its Taylor series in x = Q~max: exact to round-off for x <= 0.25, where the
// closed form loses digits to cancellation (its terms are O(1), the result O(x^3)).
double energy_series(double x) {
  double sum = 0.0;
  double xk = x * x;  // x^2; the x and x^2 coefficients vanish
  for (int k = 3; k < 80; ++k) {
    xk *= x;
    const double sign_k = (k % 2 == 0) ? 1.0 : -1.0;
    const double a_k =
        -binomial(5.0 / 3.0, k) * sign_k + (5.0 / 6.0) * binomial(2.0 / 3.0, k - 1) * sign_k;
    const double term = a_k * xk;
    sum += term;
    if (std::abs(term) < 1e-18 * std::abs(sum)) break;
  }
  return sum;
}

}  // namespace

double stick_displacement_tilde(double Q_tilde) {
  require_unit_force(Q_tilde, "Q~ = Q/(mu P)");
  return 2.0 / 3.0 * Q_tilde;  // B.14
}

double loading_displacement_tilde(double Q_tilde) {
  require_unit_force(Q_tilde, "Q~ = Q/(mu P)");
  return -std::expm1(2.0 / 3.0 * std::log1p(-Q_tilde));  // B.15
}

double loading_force_tilde(double delta_tilde) {
  core::require_finite("delta~ = 16 G* a delta/(3 mu P)", delta_tilde);
  const double d = std::abs(delta_tilde);
  // B.15 inverted; expm1/log1p keep the relative accuracy for small delta~.
  const double q = d >= 1.0 ? 1.0 : -std::expm1(1.5 * std::log1p(-d));
  return std::copysign(q, delta_tilde);
}

double unloading_displacement_tilde(double Q_tilde, double Q_max_tilde) {
  require_unit_force(Q_max_tilde, "Q~max = Q_max/(mu P)");
  if (!(std::abs(Q_tilde) <= Q_max_tilde)) {
    throw InvalidInput(fmt::format("Q~ = {} must lie in [-Q~max, Q~max] = [-{}, {}]",
                                   core::format_value(Q_tilde), core::format_value(Q_max_tilde),
                                   core::format_value(Q_max_tilde)));
  }
  // B.16
  return 2.0 * std::pow(1.0 - (Q_max_tilde - Q_tilde) / 2.0, 2.0 / 3.0) -
         std::pow(1.0 - Q_max_tilde, 2.0 / 3.0) - 1.0;
}

double reloading_displacement_tilde(double Q_tilde, double Q_max_tilde) {
  return -unloading_displacement_tilde(-Q_tilde, Q_max_tilde);  // B.17
}

double unloading_force_tilde(double delta_tilde, double delta_max_tilde) {
  if (!std::isfinite(delta_max_tilde) || !(delta_max_tilde >= 0.0) ||
      !(std::abs(delta_tilde) <= delta_max_tilde)) {
    throw InvalidInput(
        fmt::format("delta~ = {} must lie in [-delta~max, delta~max] with delta~max finite and "
                    ">= 0; delta~max = {}",
                    core::format_value(delta_tilde), core::format_value(delta_max_tilde)));
  }
  // Masing: equals B.16 solved for Q~, and holds in gross slip too.
  return loading_force_tilde(delta_max_tilde) -
         2.0 * loading_force_tilde((delta_max_tilde - delta_tilde) / 2.0);
}

double reloading_force_tilde(double delta_tilde, double delta_max_tilde) {
  return -unloading_force_tilde(-delta_tilde, delta_max_tilde);
}

double energy_tilde(double Q_max_tilde) {
  require_unit_force(Q_max_tilde, "Q~max = Q_max/(mu P)");
  const double x = Q_max_tilde;
  if (x <= 0.25) return energy_series(x);
  const double r = std::pow(1.0 - x, 2.0 / 3.0);
  return 1.0 - std::pow(1.0 - x, 5.0 / 3.0) - 5.0 * x / 6.0 * (1.0 + r);  // B.19
}

double energy_tilde_small_amplitude(double Q_max_tilde) {
  require_unit_force(Q_max_tilde, "Q~max = Q_max/(mu P)");
  const double x = Q_max_tilde;
  return 5.0 * x * x * x / 162.0 * (1.0 + 2.0 * x / 3.0);  // B.20
}

double energy_tilde_for_displacement(double delta_max_tilde) {
  core::require_non_negative("delta~max", delta_max_tilde);
  if (delta_max_tilde <= 1.0) {
    const double Q = loading_force_tilde(delta_max_tilde);
    if (Q <= 0.25) return energy_tilde(Q);  // its series, exact for small amplitudes
    // B.19 in r = 1 - delta~ (1 - Q~ = r^{3/2}): no digits lost near gross slip.
    const double r = 1.0 - delta_max_tilde;
    return 1.0 - std::pow(r, 2.5) - 5.0 / 6.0 * (1.0 - r * std::sqrt(r)) * (1.0 + r);
  }
  // Gross slip: the partial-slip loop at onset (1/6) plus the rectangle 4 mu P (delta_max -
  // delta_slip), in tilde units 5/6 (delta~max - 1).
  return 1.0 / 6.0 + 5.0 / 6.0 * (delta_max_tilde - 1.0);
}

}  // namespace mindlin

const char* to_string(SlipRegime r) {
  return r == SlipRegime::partial_slip ? "partial_slip" : "gross_slip";
}

MindlinContact::MindlinContact(double mu, double P, double G_star, double a)
    : mu_(mu), P_(P), G_star_(G_star), a_(a) {
  core::require_non_negative("mu", mu);
  core::require_non_negative("P", P);
  core::require_positive("G_star", G_star);
  core::require_non_negative("a", a);
  if (a == 0.0 && P > 0.0) {
    throw InvalidInput("contact radius a = 0 with a normal load P > 0 is not a contact");
  }
}

double MindlinContact::slip_displacement() const {
  if (Q_max() == 0.0) return 0.0;
  return 3.0 * mu_ * P_ / (16.0 * G_star_ * a_);
}

double MindlinContact::loading_force(double delta) const {
  core::require_finite("delta", delta);
  if (Q_max() == 0.0) return 0.0;
  return Q_max() * mindlin::loading_force_tilde(delta / slip_displacement());
}

double MindlinContact::loading_displacement(double Q) const {
  core::require_finite("Q", Q);
  if (std::abs(Q) > Q_max()) {
    throw InvalidInput(
        fmt::format("Q = {} N exceeds the static friction force mu P = {} N: the contact slides",
                    core::format_value(Q), core::format_value(Q_max())));
  }
  if (Q_max() == 0.0) return 0.0;
  return std::copysign(
      slip_displacement() * mindlin::loading_displacement_tilde(std::abs(Q) / Q_max()), Q);
}

double MindlinContact::unloading_force(double delta, double delta_max) const {
  core::require_non_negative("delta_max", delta_max);
  if (Q_max() == 0.0) return 0.0;
  const double s = slip_displacement();
  // Masing's rule, exact for Cattaneo-Mindlin (B.16 solved for Q).
  if (!(std::abs(delta) <= delta_max)) {
    throw InvalidInput(
        fmt::format("delta = {} m must lie in [-delta_max, delta_max], delta_max = {} m",
                    core::format_value(delta), core::format_value(delta_max)));
  }
  return Q_max() * (mindlin::loading_force_tilde(delta_max / s) -
                    2.0 * mindlin::loading_force_tilde((delta_max - delta) / (2.0 * s)));
}

double MindlinContact::reloading_force(double delta, double delta_max) const {
  return -unloading_force(-delta, delta_max);  // B.17 by symmetry
}

double MindlinContact::unloading_displacement(double Q, double Q_max_reversal) const {
  if (Q_max() == 0.0) {
    throw InvalidInput("the contact carries no friction force (mu P = 0): no unloading branch");
  }
  return slip_displacement() *
         mindlin::unloading_displacement_tilde(Q / Q_max(), Q_max_reversal / Q_max());
}

double MindlinContact::reloading_displacement(double Q, double Q_max_reversal) const {
  return -unloading_displacement(-Q, Q_max_reversal);
}

SlipRegime MindlinContact::regime_for_displacement(double delta_max) const {
  core::require_non_negative("delta_max", delta_max);
  return delta_max < slip_displacement() ? SlipRegime::partial_slip : SlipRegime::gross_slip;
}

double MindlinContact::energy_per_cycle(double delta_max) const {
  core::require_non_negative("delta_max", delta_max);
  if (Q_max() == 0.0) return 0.0;
  const double scale = 9.0 * Q_max() * Q_max() / (10.0 * G_star_ * a_);  // B.19 scaling
  return scale * mindlin::energy_tilde_for_displacement(delta_max / slip_displacement());
}

double MindlinContact::energy_per_cycle_for_force(double Q_max_reversal) const {
  core::require_non_negative("Q_max", Q_max_reversal);
  if (Q_max_reversal > Q_max()) {
    throw InvalidInput(fmt::format(
        "force amplitude Q_max = {} N exceeds mu P = {} N: gross slip, the displacement and the "
        "energy per cycle are unbounded under force control",
        core::format_value(Q_max_reversal), core::format_value(Q_max())));
  }
  if (Q_max() == 0.0) return 0.0;
  const double scale = 9.0 * Q_max() * Q_max() / (10.0 * G_star_ * a_);
  return scale * mindlin::energy_tilde(Q_max_reversal / Q_max());
}

FrettingLoop MindlinContact::loop(double delta_max, std::size_t points) const {
  core::require_non_negative("delta_max", delta_max);
  if (points < 2) throw InvalidInput("loop points per branch must be >= 2");
  FrettingLoop out;
  out.delta.reserve(3 * points);
  out.Q.reserve(3 * points);
  out.branch.reserve(3 * points);
  const double n = static_cast<double>(points - 1);
  for (std::size_t i = 0; i < points; ++i) {
    const double d = delta_max * static_cast<double>(i) / n;
    out.delta.push_back(d);
    out.Q.push_back(loading_force(d));
    out.branch.push_back(0);
  }
  for (std::size_t i = 0; i < points; ++i) {
    const double d = delta_max * (1.0 - 2.0 * static_cast<double>(i) / n);
    out.delta.push_back(d);
    out.Q.push_back(unloading_force(std::clamp(d, -delta_max, delta_max), delta_max));
    out.branch.push_back(1);
  }
  for (std::size_t i = 0; i < points; ++i) {
    const double d = -delta_max * (1.0 - 2.0 * static_cast<double>(i) / n);
    out.delta.push_back(d);
    out.Q.push_back(reloading_force(std::clamp(d, -delta_max, delta_max), delta_max));
    out.branch.push_back(2);
  }
  return out;
}

}  // namespace asperity::contact
