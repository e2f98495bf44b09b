#include "gw_fast_sum.hpp"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <numbers>

#include "asperity/core/numerics.hpp"

namespace asperity::surface::detail {

namespace {

constexpr double kTailExponent = 45.0;  // exp(-45) = 3e-20: far below the 1e-12 sums
constexpr int kGridPerSegment = 256;

struct Rule {
  std::array<double, 20> x{};  // nodes on [0, 1]
  std::array<double, 20> w{};
};

const Rule& gauss20() {
  static const Rule rule = [] {
    Rule r;
    const auto& a = boost::math::quadrature::gauss<double, 20>::abscissa();
    const auto& wt = boost::math::quadrature::gauss<double, 20>::weights();
    for (std::size_t i = 0; i < 10; ++i) {
      r.x[i] = 0.5 * (1.0 - a[i]);
      r.w[i] = 0.5 * wt[i];
      r.x[19 - i] = 0.5 * (1.0 + a[i]);
      r.w[19 - i] = 0.5 * wt[i];
    }
    return r;
  }();
  return rule;
}

}  // namespace

FastLoadingSum::FastLoadingSum(const RoughFlat& flat, double d_star)
    : flat_(flat),
      d_(d_star),
      s_a_(flat.sigma_a_over_sigma()),
      wc_(flat.omega_c_star()),
      g_(4.0 * flat.parameters().G_over_E) {
  const double z0 = std::max(d_, 0.0);
  u_max_ = std::sqrt(z0 * z0 + 2.0 * kTailExponent * s_a_ * s_a_) - d_;
  for (double w : flat.laws().break_points()) {
    if (w * wc_ < u_max_) law_breaks_.push_back(w * wc_);
  }
  norm_ = 2.0 * std::numbers::pi / 3.0 * flat.parameters().beta * wc_ /
          (std::sqrt(2.0 * std::numbers::pi) * s_a_);
  // lambda on a grid per law segment (just inside its ends), to bracket slip boundaries.
  std::vector<double> edges{0.0};
  edges.insert(edges.end(), law_breaks_.begin(), law_breaks_.end());
  edges.push_back(u_max_);
  for (std::size_t s = 0; s + 1 < edges.size(); ++s) {
    const double a = edges[s];
    const double b = edges[s + 1];
    for (int i = 0; i <= kGridPerSegment; ++i) {
      const double t = static_cast<double>(i) / kGridPerSegment;
      double u = (s == 0) ? a + (b - a) * t * t : a + (b - a) * t;
      if (i == 0) u = a + (b - a) * 1e-13;
      if (i == kGridPerSegment) u = b - (b - a) * 1e-13;
      grid_u_.push_back(u);
      grid_lambda_.push_back(point(u).lambda);
    }
  }
  // The static friction: every asperity in full slip (Eq. 4.7), by the same rule.
  double total = 0.0;
  const Rule& r = gauss20();
  std::vector<double> cuts{0.0};
  cuts.insert(cuts.end(), law_breaks_.begin(), law_breaks_.end());
  cuts.push_back(u_max_);
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    // Halves with u = end + L s^2 towards both ends (u^{3/2} at 0, square roots at
    // law branch points).
    const double a = cuts[i];
    const double half = 0.5 * (cuts[i + 1] - a);
    const int chunks = std::max(1, static_cast<int>(std::ceil(2.0 * half / s_a_)));
    for (int c = 0; c < chunks; ++c) {
      for (int q = 0; q < 20; ++q) {
        const double s = (c + r.x[q]) / chunks;
        const double wq = r.w[q] / chunks * 2.0 * half * s;
        total += wq * (point(a + half * s * s).W + point(cuts[i + 1] - half * s * s).W);
      }
    }
  }
  Q_max_ = total;
}

std::vector<double> FastLoadingSum::critical_displacements() const {
  std::vector<double> levels;
  const std::size_t per = kGridPerSegment + 1;
  const std::size_t segments = grid_u_.size() / per;
  for (std::size_t seg = 0; seg < segments; ++seg) {
    const std::size_t b = seg * per;
    // One-sided limits at a law branch point where lambda jumps (not u = 0 or u_max).
    if (seg + 1 < segments) {
      const double left = grid_lambda_[b + per - 1];
      const double right = grid_lambda_[b + per];
      if (std::abs(left - right) > 1e-9 * std::max(std::abs(left), std::abs(right))) {
        levels.push_back(left);
        levels.push_back(right);
      }
    }
    // Interior extrema, refined by Brent's method on -lambda or lambda.
    for (std::size_t i = b + 1; i + 1 < b + per; ++i) {
      const double l0 = grid_lambda_[i - 1], l1 = grid_lambda_[i], l2 = grid_lambda_[i + 1];
      const bool is_max = l1 > l0 && l1 >= l2;
      const bool is_min = l1 < l0 && l1 <= l2;
      if (!is_max && !is_min) continue;
      const double sign = is_max ? -1.0 : 1.0;
      std::uintmax_t iters = 100;
      const auto r =
          boost::math::tools::brent_find_minima([&](double u) { return sign * point(u).lambda; },
                                                grid_u_[i - 1], grid_u_[i + 1], 52, iters);
      levels.push_back(sign * r.second);
    }
  }
  std::vector<double> out;
  for (double l : levels) {
    if (l > 0.0 && std::isfinite(l)) out.push_back(l / g_);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

FastLoadingSum::Point FastLoadingSum::point(double u) const {
  if (u <= 0.0) return {0.0, 0.0};
  const auto& laws = flat_.laws();
  const double w = u / wc_;
  const double f = laws.load_star(w);
  const double m = laws.mu(w);
  const double z = (d_ + u) / s_a_;
  const double W = norm_ * m * f * std::exp(-0.5 * z * z);
  double lambda = m * u;
  if (flat_.parameters().slip_scaling == SlipScaling::own_law) {
    const double a = laws.radius_star(w);
    lambda = a > 0.0 ? m * wc_ * f / a : 0.0;
  }
  return {W, lambda};
}

std::vector<double> FastLoadingSum::boundaries(double level) const {
  std::vector<double> roots;
  if (!(level > 0.0)) return roots;
  for (std::size_t i = 0; i + 1 < grid_u_.size(); ++i) {
    if (grid_u_[i + 1] <= grid_u_[i]) continue;  // across a law break
    const bool below0 = grid_lambda_[i] < level;
    const bool below1 = grid_lambda_[i + 1] < level;
    if (below0 == below1) continue;
    roots.push_back(core::find_root([&](double u) { return point(u).lambda - level; }, grid_u_[i],
                                    grid_u_[i + 1], "asperity slip boundary", 52));
  }
  return roots;
}

LoadingMoments FastLoadingSum::at(double delta_star) const {
  const double c = g_ * delta_star;
  // Pieces between 0, law breaks, slip boundaries and u_max; sqrt-type ends at 0 and at
  // slip boundaries.
  struct Cut {
    double u;
    bool sqrt_type;
  };
  std::vector<Cut> cuts{{0.0, true}};
  for (double u : law_breaks_) cuts.push_back({u, true});  // e.g. CEB mu ~ (1 - w)^{1/2}
  for (double u : boundaries(c)) cuts.push_back({u, true});
  cuts.push_back({u_max_, false});
  std::sort(cuts.begin(), cuts.end(), [](const Cut& x, const Cut& y) { return x.u < y.u; });

  const Rule& r = gauss20();
  LoadingMoments m;
  auto accumulate = [&](double u, double weight) {
    const Point p = point(u);
    if (p.W == 0.0) return;
    if (p.lambda <= c) {  // full slip: Q = mu P, no stiffness
      m.Q += weight * p.W;
      return;
    }
    const double t = c / p.lambda;
    const double rt = std::sqrt(1.0 - t);  // (1 - t)^{1/2}
    const double gl = g_ / p.lambda;
    // h(t) = 1 - (1 - t)^{3/2}; its series for small t avoids the cancellation.
    const double h =
        t < 1e-3 ? t * (1.5 - t * (0.375 + t * (0.0625 + t * 0.0234375))) : 1.0 - (1.0 - t) * rt;
    m.Q += weight * p.W * h;
    m.dQ += weight * p.W * 1.5 * rt * gl;
    m.d2Q += weight * p.W * (-0.75) / rt * gl * gl;
  };
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const Cut lo = cuts[i];
    const Cut hi = cuts[i + 1];
    const double L = hi.u - lo.u;
    if (!(L > 0.0)) continue;
    auto piece = [&](double a, double len, int dir /* +1: sqrt at a, -1: sqrt at a+len, 0 */) {
      const int chunks = std::max(1, static_cast<int>(std::ceil(2.0 * len / s_a_)));
      for (int k = 0; k < chunks; ++k) {
        for (int q = 0; q < 20; ++q) {
          const double s = (k + r.x[q]) / chunks;
          const double wq = r.w[q] / chunks;
          if (dir > 0) {
            accumulate(a + len * s * s, wq * 2.0 * len * s);
          } else if (dir < 0) {
            accumulate(a + len - len * s * s, wq * 2.0 * len * s);
          } else {
            accumulate(a + len * s, wq * len);
          }
        }
      }
    };
    if (lo.sqrt_type && hi.sqrt_type) {
      piece(lo.u, 0.5 * L, +1);
      piece(lo.u + 0.5 * L, 0.5 * L, -1);
    } else if (lo.sqrt_type) {
      piece(lo.u, L, +1);
    } else if (hi.sqrt_type) {
      piece(lo.u, L, -1);
    } else {
      piece(lo.u, L, 0);
    }
  }
  return m;
}

}  // namespace asperity::surface::detail
