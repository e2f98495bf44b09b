// The tabulated backbone of a rough flat (see RoughFlatBackbone in rough_flat.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "gw_fast_sum.hpp"

namespace asperity::surface {

namespace {

constexpr std::size_t kInitialIntervals = 16;  // over the whole range; per segment pro rata
constexpr std::size_t kMaxIntervals = 1u << 12;
// Beyond the table's end, Q_max - Q_l < kSaturation * Q_max.
constexpr double kSaturation = 1e-12;

// Quintic Hermite on t in [0, 1] from end values y, first derivatives m and second
// derivatives a (already scaled to t), as polynomial coefficients c0..c5.
std::array<double, 6> quintic(double y0, double m0, double a0, double y1, double m1, double a1) {
  // p = y0 H0 + m0 H1 + a0 H2 + y1 H3 + m1 H4 + a1 H5 with the standard basis:
  // H0 = 1 - 10t^3 + 15t^4 - 6t^5,  H1 = t - 6t^3 + 8t^4 - 3t^5,
  // H2 = (t^2 - 3t^3 + 3t^4 - t^5)/2, H3 = 10t^3 - 15t^4 + 6t^5,
  // H4 = -4t^3 + 7t^4 - 3t^5,         H5 = (t^3 - 2t^4 + t^5)/2.
  return {y0,
          m0,
          0.5 * a0,
          -10 * y0 - 6 * m0 - 1.5 * a0 + 10 * y1 - 4 * m1 + 0.5 * a1,
          15 * y0 + 8 * m0 + 1.5 * a0 - 15 * y1 + 7 * m1 - a1,
          -6 * y0 - 3 * m0 - 0.5 * a0 + 6 * y1 - 3 * m1 + 0.5 * a1};
}

// Estrin's scheme: shorter dependency chain than Horner for the hot force() path.
double horner(const double* c, double t) {
  const double t2 = t * t;
  return (c[0] + c[1] * t) + t2 * ((c[2] + c[3] * t) + t2 * (c[4] + c[5] * t));
}

struct NodeData {
  double G, Gs, Gss;  // G(s) = Q_l(s^2)/s^2 and its s-derivatives
};

}  // namespace

RoughFlatBackbone::RoughFlatBackbone(const RoughFlat& flat, double d_star, double rel_tol)
    : d_star_(d_star) {
  core::require_finite("separation d*", d_star);
  if (!(rel_tol >= 1e-12 && rel_tol <= 1e-3)) {
    throw InvalidInput(
        fmt::format("table tolerance {} is not allowed: it must lie in [1e-12, 1e-3]",
                    core::format_value(rel_tol)));
  }
  const detail::FastLoadingSum sum(flat, d_star);
  Q_max_ = sum.static_friction();
  const auto origin = sum.at(0.0);
  k0_ = origin.dQ;
  if (!(Q_max_ > 0.0) || !(k0_ > 0.0)) {
    throw InvalidInput(fmt::format(
        "the rough flat carries no friction force at d* = {} (Q*_max = {}): with the {} model "
        "every asperity in contact has yielded (mu = 0) or none is in contact",
        core::format_value(d_star), core::format_value(Q_max_),
        contact::to_string(flat.parameters().model)));
  }
  // Table end: where the virgin curve has saturated at Q_max to kSaturation.
  x_end_ = Q_max_ / k0_;
  for (int i = 0;; ++i) {
    if (1.0 - sum.at(x_end_).Q / Q_max_ < kSaturation) break;
    x_end_ *= 1.5;
    if (i > 120) throw NumericalError("rough-flat backbone: the loading curve does not saturate");
  }

  // Nodes uniform in s = sqrt(delta*) on each segment between knots, tabulating
  // G(s) = Q_l(s^2)/s^2 (G(0) = k0): near 0, Q_l = k0 x + Q''(0) x^2/2 + O(x^{5/2}), so G
  // is a smooth function of s with the same relative accuracy near 0 as elsewhere. Knots
  // sit where Q_l is less smooth (critical_displacements); nodes at a knot are sampled a
  // hair inside their own segment, so each segment sees its one-sided derivatives.
  const double s_end = std::sqrt(x_end_);
  auto sample = [&](double s) -> NodeData {
    if (s == 0.0) return {k0_, 0.0, origin.d2Q};
    const double x = s * s;
    const auto q = sum.at(x);
    const double G = q.Q / x;
    const double Gx = (x * q.dQ - q.Q) / (x * x);
    const double Gxx = (x * x * q.d2Q - 2.0 * x * q.dQ + 2.0 * q.Q) / (x * x * x);
    return {G, 2.0 * s * Gx, 4.0 * x * Gxx + 2.0 * Gx};
  };
  std::vector<double> knots{0.0};
  for (double x : sum.critical_displacements()) {
    const double s = std::sqrt(x);
    if (s > 1e-6 * s_end && s < s_end * (1.0 - 1e-6) && s - knots.back() > 1e-6 * s_end) {
      knots.push_back(s);
    }
  }
  knots.push_back(s_end);

  auto coefficients = [](const NodeData& a, const NodeData& b, double h) {
    return quintic(a.G, a.Gs * h, a.Gss * h * h, b.G, b.Gs * h, b.Gss * h * h);
  };
  constexpr double kInside = 1e-10;  // relative offset of knot samples into their segment
  verified_error_ = 0.0;
  n_ = 0;
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double a = knots[k];
    const double b = knots[k + 1];
    const bool knot_a = k > 0;
    const bool knot_b = k + 2 < knots.size();
    std::size_t n = std::max<std::size_t>(
        4, kInitialIntervals * static_cast<std::size_t>(std::ceil((b - a) / s_end * 4.0)) / 4);
    auto node_s = [&](std::size_t i, std::size_t count) {
      const double s = a + (b - a) * static_cast<double>(i) / static_cast<double>(count);
      if (i == 0 && knot_a) return s * (1.0 + kInside);
      if (i == count && knot_b) return s * (1.0 - kInside);
      return s;
    };
    std::vector<NodeData> nodes(n + 1);
    for (std::size_t i = 0; i <= n; ++i) nodes[i] = sample(node_s(i, n));
    double worst = 0.0;
    while (true) {
      const double h = (b - a) / static_cast<double>(n);
      std::vector<NodeData> mids(n);
      worst = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        mids[i] = sample(a + h * (static_cast<double>(i) + 0.5));
        const auto c = coefficients(nodes[i], nodes[i + 1], h);
        // The relative error of Q = x G equals that of G.
        worst = std::max(worst, std::abs(horner(c.data(), 0.5) - mids[i].G) / mids[i].G);
      }
      if (worst <= rel_tol) break;
      if (n_ + 2 * n > kMaxIntervals) {
        throw NumericalError(fmt::format(
            "rough-flat backbone: table error {:.3g} still above {:.3g} with {} intervals on "
            "delta* in [{:.4g}, {:.4g}]",
            worst, rel_tol, n, a * a, b * b));
      }
      std::vector<NodeData> refined(2 * n + 1);
      for (std::size_t i = 0; i < n; ++i) {
        refined[2 * i] = nodes[i];
        refined[2 * i + 1] = mids[i];
      }
      refined[2 * n] = nodes[n];
      nodes = std::move(refined);
      n *= 2;
    }
    verified_error_ = std::max(verified_error_, worst);
    const double h = (b - a) / static_cast<double>(n);
    segments_.push_back({a, h, 1.0 / h, n, n_});
    for (std::size_t i = 0; i < n; ++i) {
      const auto c = coefficients(nodes[i], nodes[i + 1], h);
      coef_.insert(coef_.end(), c.begin(), c.end());
    }
    n_ += n;
  }
  // Int_0^x Q dx at every interval start.
  cumulative_.assign(n_ + 1, 0.0);
  for (const auto& seg : segments_) {
    for (std::size_t i = 0; i < seg.n; ++i) {
      cumulative_[seg.offset + i + 1] = cumulative_[seg.offset + i] + partial_integral(seg, i, 1.0);
    }
  }
}

double RoughFlatBackbone::partial_integral(const Segment& seg, std::size_t i, double f) const {
  // Q dx = s^2 G(s) 2 s ds: degree 8 in s on an interval; 5-point Gauss-Legendre is exact.
  static constexpr double kNodes[5] = {0.0469100770306680, 0.2307653449471585, 0.5,
                                       0.7692346550528415, 0.9530899229693320};
  static constexpr double kWeights[5] = {0.1184634425280945, 0.2393143352496832, 0.2844444444444444,
                                         0.2393143352496832, 0.1184634425280945};
  const double* c = &coef_[6 * (seg.offset + i)];
  double acc = 0.0;
  for (int q = 0; q < 5; ++q) {
    const double t = f * kNodes[q];
    const double s = seg.s0 + seg.h * (static_cast<double>(i) + t);
    acc += kWeights[q] * 2.0 * s * s * s * horner(c, t);
  }
  return acc * f * seg.h;
}

std::pair<const RoughFlatBackbone::Segment*, double> RoughFlatBackbone::locate(double s) const {
  std::size_t k = 0;
  while (k + 1 < segments_.size() && s >= segments_[k + 1].s0) ++k;
  return {&segments_[k], (s - segments_[k].s0) * segments_[k].inv_h};
}

double RoughFlatBackbone::force(double delta_star) const {
  if (!(delta_star > 0.0)) return 0.0;
  if (delta_star >= x_end_) return Q_max_;
  const auto [seg, t] = locate(std::sqrt(delta_star));
  const auto i = std::min(static_cast<std::size_t>(t), seg->n - 1);
  return delta_star * horner(&coef_[6 * (seg->offset + i)], t - static_cast<double>(i));
}

double RoughFlatBackbone::displacement(double Q_star) const {
  core::require_non_negative("tangential force Q*", Q_star);
  if (Q_star == 0.0) return 0.0;
  const double top = force(x_end_ * (1.0 - 1e-15));
  if (Q_star >= top) {
    throw InvalidInput(fmt::format(
        "tangential force Q* = {} reaches the static friction limit Q*_max = {}: the contact "
        "slides (no finite displacement under force control)",
        core::format_value(Q_star), core::format_value(Q_max_)));
  }
  // Q_l is increasing: bracket in s by bisection on the interval starts, then solve the
  // interval's quintic with TOMS 748.
  double lo = 0.0;
  double hi = std::sqrt(x_end_) * (1.0 - 1e-15);
  for (const auto& seg : segments_) {
    for (std::size_t i = 0; i < seg.n; ++i) {
      const double s = seg.s0 + seg.h * static_cast<double>(i);
      if (s * s * coef_[6 * (seg.offset + i)] <= Q_star)
        lo = s;
      else {
        hi = std::min(hi, s);
        break;
      }
    }
    if (hi < std::sqrt(x_end_) * (1.0 - 1e-15)) break;
  }
  const double s = core::find_root([&](double v) { return force(v * v) - Q_star; }, lo, hi,
                                   "rough-flat backbone inverse", 52);
  return s * s;
}

double RoughFlatBackbone::integral(double delta_star) const {
  core::require_non_negative("tangential displacement delta*", delta_star);
  if (delta_star == 0.0) return 0.0;
  if (delta_star >= x_end_) return cumulative_[n_] + Q_max_ * (delta_star - x_end_);
  const auto [seg, t] = locate(std::sqrt(delta_star));
  const auto i = std::min(static_cast<std::size_t>(t), seg->n - 1);
  return cumulative_[seg->offset + i] + partial_integral(*seg, i, t - static_cast<double>(i));
}

}  // namespace asperity::surface
