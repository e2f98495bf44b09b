#include "asperity/hysteresis/table_backbone.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::hysteresis {

TableBackbone::TableBackbone(std::vector<double> x, std::vector<double> Q, std::string source)
    : x_(std::move(x)), Q_(std::move(Q)) {
  const std::size_t n = x_.size();
  if (n != Q_.size())
    throw InvalidInput(fmt::format("{}: {} displacements but {} forces", source, n, Q_.size()));
  if (n < 2)
    throw InvalidInput(
        fmt::format("{}: a backbone table needs at least 2 points, {} given", source, n));
  double Qmax = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x_[i]) || !std::isfinite(Q_[i])) {
      throw InvalidInput(fmt::format("{}: point {} (x = {}, Q = {}) is not finite", source, i + 1,
                                     core::format_value(x_[i]), core::format_value(Q_[i])));
    }
    Qmax = std::max(Qmax, std::abs(Q_[i]));
  }
  if (x_[0] != 0.0 || std::abs(Q_[0]) > 1e-9 * Qmax) {
    throw InvalidInput(fmt::format(
        "{}: a backbone starts at the origin: point 1 is (x = {} m, Q = {} N), it must be (0, 0)",
        source, core::format_value(x_[0]), core::format_value(Q_[0])));
  }
  Q_[0] = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    if (!(x_[i] > x_[i - 1])) {
      throw InvalidInput(
          fmt::format("{}: the displacement must increase: point {} has x = {} m after x = {} m",
                      source, i + 1, core::format_value(x_[i]), core::format_value(x_[i - 1])));
    }
    if (Q_[i] < Q_[i - 1]) {
      throw InvalidInput(fmt::format(
          "{}: a backbone is monotone: the force falls at point {} (Q = {} N after {} N)", source,
          i + 1, core::format_value(Q_[i]), core::format_value(Q_[i - 1])));
    }
  }
  if (!(Q_[1] > 0.0)) {
    throw InvalidInput(fmt::format(
        "{}: the force must rise over the first interval (a positive stiffness at rest); point 2 "
        "has Q = {} N",
        source, core::format_value(Q_[1])));
  }
  // Fritsch-Butland slopes: the weighted harmonic mean of the neighbouring secants, zero
  // where one of them is (a flat stretch stays flat, no overshoot).
  std::vector<double> h(n - 1), s(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x_[i + 1] - x_[i];
    s[i] = (Q_[i + 1] - Q_[i]) / h[i];
  }
  d_.assign(n, 0.0);
  d_[0] = s[0];
  for (std::size_t i = 1; i + 1 < n; ++i) {
    if (s[i - 1] > 0.0 && s[i] > 0.0) {
      const double w1 = 2.0 * h[i] + h[i - 1], w2 = h[i] + 2.0 * h[i - 1];
      d_[i] = (w1 + w2) / (w1 / s[i - 1] + w2 / s[i]);
    }
  }
  // The last point: zero slope, joining the constant force beyond it (the table ends at
  // the slip force). With the Fritsch-Butland slopes (at most 3 times either secant) every
  // piece keeps Fritsch and Carlson's monotonicity condition. Two points: a straight line.
  d_[n - 1] = n == 2 ? s[0] : 0.0;
  cumulative_.assign(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    cumulative_[i + 1] = cumulative_[i] + 0.5 * h[i] * (Q_[i] + Q_[i + 1]) +
                         h[i] * h[i] * (d_[i] - d_[i + 1]) / 12.0;
  }
}

std::size_t TableBackbone::interval(double x) const {
  const auto it = std::upper_bound(x_.begin(), x_.end(), x);
  const auto i = static_cast<std::size_t>(it - x_.begin());
  return std::min(i == 0 ? 0 : i - 1, x_.size() - 2);
}

double TableBackbone::force(double x) const {
  core::require_non_negative("x", x);
  if (x >= x_.back()) return Q_.back();
  const std::size_t i = interval(x);
  const double h = x_[i + 1] - x_[i], t = (x - x_[i]) / h;
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * Q_[i] + (t3 - 2 * t2 + t) * h * d_[i] +
         (-2 * t3 + 3 * t2) * Q_[i + 1] + (t3 - t2) * h * d_[i + 1];
}

double TableBackbone::stiffness(double x) const {
  core::require_non_negative("x", x);
  if (x >= x_.back()) return 0.0;
  const std::size_t i = interval(x);
  const double h = x_[i + 1] - x_[i], t = (x - x_[i]) / h;
  const double t2 = t * t;
  return ((6 * t2 - 6 * t) * Q_[i] + (-6 * t2 + 6 * t) * Q_[i + 1]) / h +
         (3 * t2 - 4 * t + 1) * d_[i] + (3 * t2 - 2 * t) * d_[i + 1];
}

double TableBackbone::integral(double x) const {
  core::require_non_negative("x", x);
  if (x >= x_.back()) return cumulative_.back() + Q_.back() * (x - x_.back());
  const std::size_t i = interval(x);
  const double h = x_[i + 1] - x_[i], t = (x - x_[i]) / h;
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
  // Integrals over [0, t] of the Hermite basis, times h.
  return cumulative_[i] +
         h * ((0.5 * t4 - t3 + t) * Q_[i] + (0.25 * t4 - 2.0 / 3.0 * t3 + 0.5 * t2) * h * d_[i] +
              (-0.5 * t4 + t3) * Q_[i + 1] + (0.25 * t4 - t3 / 3.0) * h * d_[i + 1]);
}

double TableBackbone::displacement(double Q) const {
  if (!(Q >= 0.0) || Q >= limit()) {
    throw InvalidInput(fmt::format(
        "tangential force {} N is outside [0, {}) of the backbone table: at its last force the "
        "contact slides",
        core::format_value(Q), core::format_value(limit())));
  }
  const auto it = std::upper_bound(Q_.begin(), Q_.end(), Q);
  std::size_t i = static_cast<std::size_t>(it - Q_.begin());
  i = i == 0 ? 0 : i - 1;
  double lo = x_[i], hi = x_[std::min(i + 1, x_.size() - 1)];
  for (int k = 0; k < 200 && hi - lo > 1e-14 * (x_[i + 1] - x_[i]); ++k) {
    const double mid = 0.5 * (lo + hi);
    (force(mid) < Q ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::pair<std::vector<double>, std::vector<double>> tabulate(const Backbone& backbone,
                                                             std::size_t points) {
  if (points < 3) throw InvalidInput(fmt::format("tabulate: {} points, at least 3", points));
  const double F = backbone.limit();
  // x_s by bisection on the (non-decreasing) force itself: the inverse's own root finder
  // can fail this close to the plateau, where force - target is of the order of round-off
  // at both ends of its bracket (seen on the steel_smooth joint at 200 N).
  const double target = (1.0 - 1e-9) * F;
  double lo = 0.0, hi = backbone.displacement(0.5 * F);
  for (int k = 0; k < 200 && backbone.force(hi) < target; ++k) {
    const double before = backbone.force(hi);
    lo = hi;
    hi *= 2.0;
    if (backbone.force(hi) <= before) break;  // the force stopped growing: its plateau
  }
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (backbone.force(mid) < target ? lo : hi) = mid;
  }
  const double xs = hi;
  std::vector<double> x, Q;
  for (std::size_t k = 0; k < points; ++k) {
    const double v = xs * static_cast<double>(k) / static_cast<double>(points - 1);
    x.push_back(v);
    Q.push_back(backbone.force(v));
  }
  x.push_back(1.25 * xs);
  Q.push_back(F);
  return {x, Q};
}

}  // namespace asperity::hysteresis
