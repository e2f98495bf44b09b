#include "asperity/hysteresis/odfalk_vingsbo.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::hysteresis {

void OdfalkVingsboParameters::validate() const {
  core::require_positive("fretting_yield_point (Q_ty) [N]", fretting_yield_point);
  core::require_finite("fretting_yield_point (Q_ty) [N]", fretting_yield_point);
  core::require_positive("hardening_coefficient (k_p) [N/m]", hardening_coefficient);
  core::require_finite("hardening_coefficient (k_p) [N/m]", hardening_coefficient);
}

double odfalk_vingsbo_plastic_slip(const OdfalkVingsboParameters& p, double Q, double Q_m,
                                   bool unloading) {
  const double Q_ty = p.fretting_yield_point, k_p = p.hardening_coefficient;
  if (!(Q_m > Q_ty)) return 0.0;  // beta = 0
  // Eq. 3.10 on the unloading branch (dQ/dt < 0: gamma = 1 for Q < -Q_ty); the reloading
  // branch is its mirror image, delta_p(Q) = -delta_p_unloading(-Q).
  const auto unload = [&](double q) {
    const double gamma = q < -Q_ty ? 1.0 : 0.0;
    return gamma * (q + Q_ty) / k_p + (Q_m - Q_ty) / (2.0 * k_p);
  };
  return unloading ? unload(Q) : -unload(-Q);
}

double odfalk_vingsbo_plastic_energy(const OdfalkVingsboParameters& p, double Q_m) {
  const double Q_ty = p.fretting_yield_point;
  if (!(Q_m > Q_ty)) return 0.0;
  // Parallelogram: vertical sides of height Q_m + Q_ty, (Q_m - Q_ty)/k_p apart.
  return (Q_m - Q_ty) * (Q_m + Q_ty) / p.hardening_coefficient;
}

OdfalkVingsboCycle odfalk_vingsbo_cycle(const Backbone& elastic, const OdfalkVingsboParameters& p,
                                        double x_m) {
  p.validate();
  core::require_non_negative("displacement amplitude [m]", x_m);
  core::require_finite("displacement amplitude [m]", x_m);
  OdfalkVingsboCycle c;
  if (x_m == 0.0) return c;
  const auto plastic = [&](double Q) {
    return std::max(0.0, Q - p.fretting_yield_point) / (2.0 * p.hardening_coefficient);
  };
  // The virgin curve x = x_l(Q) + delta_p(Q), solved for the elastic amplitude x_e in
  // [0, x_m] (strictly rising in x_e).
  const auto g = [&](double xe) { return xe + plastic(elastic.force(xe)) - x_m; };
  const double xe = g(x_m) <= 0.0 ? x_m : core::find_root(g, 0.0, x_m, "Odfalk-Vingsbo amplitude");
  c.elastic_amplitude = xe;
  c.Q_m = elastic.force(xe);
  c.plastic_amplitude = plastic(c.Q_m);
  c.energy = energy_per_cycle(elastic, xe) + odfalk_vingsbo_plastic_energy(p, c.Q_m);
  return c;
}

OdfalkVingsboSlip::OdfalkVingsboSlip(const OdfalkVingsboParameters& p) : p_(p) {
  p_.validate();
}

double OdfalkVingsboSlip::peek(double Q) const {
  // Outward flow over [q0, q1] (q1 > q0, on the side of positive force): at 1/k_p beyond
  // Q_ty, at 1/(2 k_p) beyond the envelope (the virgin curve).
  const auto outward = [&](double q0, double q1) {
    const double a = std::max(q0, p_.fretting_yield_point);
    if (!(q1 > a)) return 0.0;
    const double e = std::clamp(Q_envelope_, a, q1);
    return (e - a) / p_.hardening_coefficient + (q1 - e) / (2.0 * p_.hardening_coefficient);
  };
  if (Q > Q_) return delta_p_ + outward(Q_, Q);
  if (Q < Q_) return delta_p_ - outward(-Q_, -Q);
  return delta_p_;
}

double OdfalkVingsboSlip::update(double Q) {
  delta_p_ = peek(Q);
  Q_ = Q;
  Q_envelope_ = std::max(Q_envelope_, std::abs(Q));
  return delta_p_;
}

OdfalkVingsboHysteresis::OdfalkVingsboHysteresis(std::shared_ptr<const Backbone> elastic,
                                                 const OdfalkVingsboParameters& p)
    : elastic_(std::move(elastic)), plastic_(p) {}

double OdfalkVingsboHysteresis::update(double x) {
  if (!std::isfinite(x)) {
    throw InvalidInput(
        fmt::format("displacement = {} is not allowed: a history value must be finite", x));
  }
  if (x == x_) return elastic_.Q();
  // Along a monotone step the elastic and plastic parts move with the total: the elastic
  // displacement lies between its current value and that plus the whole step.
  const double xe0 = elastic_.x();
  const double xe1 = xe0 + (x - x_);
  // The root's rounding from earlier steps (x_ against x_e + delta_p) is carried, so that
  // g(xe0) = x_ - x exactly and g(xe1) is the plastic increment, of the step's sign.
  const double carried = x_ - (xe0 + plastic_.slip());
  const auto g = [&](double xe) { return xe + plastic_.peek(elastic_.peek(xe)) + carried - x; };
  double xe = xe1;
  const double g1 = g(xe1);
  const bool up = xe1 > xe0;
  // No plastic increment (g1 zero, or of the wrong sign by rounding): the whole step is elastic.
  if (up ? g1 > 0.0 : g1 < 0.0) {
    const double g0 = g(xe0);
    const double scale = std::max({std::abs(xe0), std::abs(xe1), std::abs(x)});
    const double tol = 4.0 * std::numeric_limits<double>::epsilon() * scale;
    std::uintmax_t iters = 200;
    const auto [a, b] = boost::math::tools::toms748_solve(
        g, up ? xe0 : xe1, up ? xe1 : xe0, up ? g0 : g1, up ? g1 : g0,
        [tol](double l, double r) { return std::abs(r - l) <= tol; }, iters);
    if (iters >= 200) {
      throw NumericalError(fmt::format(
          "Odfalk-Vingsbo step to x = {:.6g} m: TOMS 748 on the elastic displacement in [{:.6g}, "
          "{:.6g}] m did not converge in 200 iterations",
          x, xe0, xe1));
    }
    xe = 0.5 * (a + b);
  }
  const double Q = elastic_.update(xe);
  plastic_.update(Q);
  x_ = x;
  return Q;
}

double OdfalkVingsboHysteresis::update_force(double Q) {
  const double xe = elastic_.update_force(Q);
  x_ = xe + plastic_.update(Q);
  return x_;
}

std::vector<double> OdfalkVingsboHysteresis::forces(std::span<const double> x_history) const {
  OdfalkVingsboHysteresis h(*this);
  std::vector<double> Q;
  Q.reserve(x_history.size());
  for (double x : x_history) Q.push_back(h.update(x));
  return Q;
}

}  // namespace asperity::hysteresis
