// Elastic unloading and reloading of a rough flat from its plastic set (see
// RoughFlat::normal_load_after_set_star).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "detail/piecewise_quadrature.hpp"
#include "rough_flat_tolerances.hpp"

namespace asperity::surface {

namespace {}  // namespace

double RoughFlat::normal_load_after_set_star(double d_star, double d_set_star) const {
  core::require_finite("separation d*", d_star);
  core::require_finite("set separation d_set*", d_set_star);
  // Pressed past the set (d* < d_set*), asperities above d_set* reload elastically beyond
  // it from their set, those between d* and d_set* load along their virgin law.
  const double s_a = s_a_;
  const double wc = omega_c_star_;
  const double norm = 1.0 / (std::sqrt(2.0 * std::numbers::pi) * s_a);
  const SummitHeightTable* table = summit_heights();
  const auto phi = [&](double z) {  // Eq. 4.2, or the measured table
    if (table) return table->density(z);
    const double t = z / s_a;
    return norm * std::exp(-0.5 * t * t);
  };
  const double z0 = std::max(std::min(d_star, d_set_star), 0.0);
  const double z_max =
      table ? table->top() : std::sqrt(z0 * z0 + 2.0 * detail::kTailExponent * s_a * s_a);
  const std::vector<double> nodes =
      table ? table->nodes_between(-std::numeric_limits<double>::infinity(), table->top())
            : std::vector<double>{};
  const std::vector<double> law_breaks = laws_.break_points();
  // delta_u(w_m) = 3 P_m/(4 E* a_m) over omega_c: the elastic recovery of an asperity set at
  // w_m. In the laws' scales, (P_m/P_c)/(a_m/a_c) times 3 P_c/(4 E* a_c omega_c) = c_a/c_P,
  // where each law is Hertz's at small interference, P/P_c = c_P w^{3/2} and a/a_c =
  // c_a w^{1/2} (c = 1 for CEB and KE, whose scales are Hertz's at omega_c; not for BKE).
  constexpr double kSmall = 1e-8;
  const double hertz_ratio = (laws_.radius_star(kSmall) / std::sqrt(kSmall)) /
                             (laws_.load_star(kSmall) / std::pow(kSmall, 1.5));
  const auto recovery = [&](double w_m) {
    const double a = laws_.radius_star(w_m);
    return a > 0.0 ? hertz_ratio * laws_.load_star(w_m) / a : 0.0;
  };
  const auto set_asperity = [&](double z) {  // z > d_set*
    const double w_m = (z - d_set_star) / wc;
    const double w = (z - d_star) / wc;
    const double du = recovery(w_m);
    const double r = w - w_m + du;
    if (!(r > 0.0) || !(du > 0.0)) return 0.0;
    return laws_.load_star(w_m) * std::pow(r / du, 1.5) * phi(z);
  };
  const auto virgin_asperity = [&](double z) {
    return laws_.load_star((z - d_star) / wc) * phi(z);
  };
  const auto integrate = [&](auto g, std::vector<double> breaks) {
    std::sort(breaks.begin(), breaks.end());
    const auto tanh_sinh = [](const auto& f, double a, double b) {
      return core::integrate_tanh_sinh(f, a, b, detail::kQuadratureTol, "rough-flat unloading sum")
          .value;
    };
    return detail::integrate_between_nodes(g, tanh_sinh, breaks, nodes);
  };
  double total = 0.0;
  if (d_star < d_set_star && d_star < z_max) {
    std::vector<double> b{d_star, std::min(d_set_star, z_max)};
    for (double w : law_breaks) {
      const double z = d_star + w * wc;
      if (z > d_star && z < b[1]) b.push_back(z);
    }
    total += integrate(virgin_asperity, b);
  }
  if (d_set_star < z_max) {
    std::vector<double> b{d_set_star, z_max};
    for (double w : law_breaks) {
      const double z = d_set_star + w * wc;
      if (z > d_set_star && z < z_max) b.push_back(z);
    }
    if (d_star > d_set_star) {
      // Where an unloaded asperity loses contact, delta_u(w_m) = (d* - d_set*)/omega_c*:
      // the integrand ends there like a 3/2 power; split at each crossing.
      const double level = (d_star - d_set_star) / wc;
      const auto g = [&](double z) { return recovery((z - d_set_star) / wc) - level; };
      std::vector<double> edges = b;
      std::sort(edges.begin(), edges.end());
      constexpr int kSamples = 32;
      for (std::size_t s = 0; s + 1 < edges.size(); ++s) {
        const double lo = edges[s], hi = edges[s + 1];
        double z_prev = lo + (hi - lo) * 1e-12;
        double g_prev = g(z_prev);
        for (int i = 1; i <= kSamples; ++i) {
          const double t = static_cast<double>(i) / kSamples;
          const double zi = i == kSamples ? hi - (hi - lo) * 1e-12 : lo + (hi - lo) * t * t;
          const double gi = g(zi);
          if ((g_prev < 0.0) != (gi < 0.0)) {
            b.push_back(core::find_root(g, z_prev, zi, "asperity loss of contact", 52));
          }
          z_prev = zi;
          g_prev = gi;
        }
      }
    }
    total += integrate(set_asperity, b);
  }
  const double result = prefactor_ * total;
  if (!std::isfinite(result)) {
    throw NumericalError(fmt::format(
        "rough-flat unloading sum: non-finite load at d* = {}, d_set* = {}", d_star, d_set_star));
  }
  return result;
}

}  // namespace asperity::surface
