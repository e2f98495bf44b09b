#include "gw_fast_sum.hpp"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <numbers>
#include <utility>

#include "asperity/core/numerics.hpp"
#include "detail/piecewise_quadrature.hpp"

namespace asperity::surface::detail {

namespace {

constexpr double kFastSumTailExponent = 45.0;  // exp(-45) = 3e-20: far below the 1e-13 sums
constexpr int kGridPerSegment = 256;
constexpr double kChunkWidth = 1.0;  // in units of sigma_a

// A fixed quadrature rule on [0, 1]; a node sits at `from_left` distance `x` from the left
// end when left is true, else at distance `x` from the right end (tanh-sinh nodes crowd
// both ends closer than 1 - x can resolve).
struct Rule {
  std::vector<double> x;
  std::vector<double> w;
  std::vector<char> left;
};

template <unsigned N>
Rule gauss_rule() {
  Rule r;
  const auto& a = boost::math::quadrature::gauss<double, N>::abscissa();
  const auto& wt = boost::math::quadrature::gauss<double, N>::weights();
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (const double sign : {-1.0, 1.0}) {
      if (a[i] == 0.0 && sign > 0.0) continue;  // the middle node of an odd rule, once
      r.x.push_back(0.5 * (1.0 + sign * a[i]));
      r.w.push_back(0.5 * wt[i]);
      r.left.push_back(1);
    }
  }
  return r;
}

const Rule& gauss20() {
  static const Rule rule = gauss_rule<20>();
  return rule;
}

const Rule& gauss10() {
  static const Rule rule = gauss_rule<10>();
  return rule;
}

// Tanh-sinh on [0, 1]: x = (1 + tanh(pi/2 sinh t))/2 at t = k h, |t| <= 3.2 (the end
// nodes lie 2e-17 from the ends), weight h pi cosh(t) x (1 - x).
const Rule& tanh_sinh() {
  static const Rule rule = [] {
    constexpr double h = 1.0 / 16.0;
    constexpr int K = 52;  // t_max = 3.25
    Rule r;
    for (int k = -K; k <= K; ++k) {
      const double t = k * h;
      const double e = std::numbers::pi * std::sinh(t);
      const double xl = 1.0 / (1.0 + std::exp(-e));
      const double xr = 1.0 / (1.0 + std::exp(e));
      r.w.push_back(h * std::numbers::pi * std::cosh(t) * xl * xr);
      r.left.push_back(k <= 0 ? 1 : 0);
      r.x.push_back(k <= 0 ? xl : xr);
    }
    return r;
  }();
  return rule;
}

}  // namespace

FastLoadingSum::FastLoadingSum(const RoughFlat& flat, double d_star)
    : flat_(flat),
      table_(flat.summit_heights()),
      d_(d_star),
      s_a_(flat.sigma_a_over_sigma()),
      wc_(flat.omega_c_star()),
      g_(4.0 * flat.parameters().G_over_E),
      elastic_scaling_(flat.parameters().slip_scaling == SlipScaling::elastic) {
  auto range = height_range(table_, d_, s_a_, kFastSumTailExponent);
  u_max_ = range.u_max;
  table_nodes_ = std::move(range.nodes);
  for (double w : flat.laws().break_points()) {
    if (w * wc_ < u_max_) law_breaks_.push_back(w * wc_);
  }
  norm_ = 2.0 * std::numbers::pi / 3.0 * flat.parameters().beta * wc_;
  if (!table_) norm_ /= std::sqrt(2.0 * std::numbers::pi) * s_a_;

  // lambda on a grid per law segment (just inside its ends; denser towards u = 0), its
  // interior extrema refined by Brent's method and added to the grid.
  std::vector<double> edges{0.0};
  edges.insert(edges.end(), law_breaks_.begin(), law_breaks_.end());
  edges.push_back(u_max_);
  for (std::size_t s = 0; s + 1 < edges.size(); ++s) {
    const double a = edges[s];
    const double b = edges[s + 1];
    std::vector<double> us;
    std::vector<double> ls;
    for (int i = 0; i <= kGridPerSegment; ++i) {
      const double t = static_cast<double>(i) / kGridPerSegment;
      double u = (s == 0) ? a + (b - a) * t * t : a + (b - a) * t;
      if (i == 0) u = a + (b - a) * 1e-13;
      if (i == kGridPerSegment) u = b - (b - a) * 1e-13;
      us.push_back(u);
      ls.push_back(point(u).lambda);
    }
    segment_start_.push_back(grid_u_.size());
    for (int i = 0; i <= kGridPerSegment; ++i) {
      grid_u_.push_back(us[i]);
      grid_lambda_.push_back(ls[i]);
      if (i == 0 || i == kGridPerSegment) continue;
      const bool is_max = ls[i] > ls[i - 1] && ls[i] >= ls[i + 1];
      const bool is_min = ls[i] < ls[i - 1] && ls[i] <= ls[i + 1];
      if (!is_max && !is_min) continue;
      const double sign = is_max ? -1.0 : 1.0;
      std::uintmax_t iters = 100;
      const auto r = boost::math::tools::brent_find_minima(
          [&](double u) { return sign * point(u).lambda; }, us[i - 1], us[i + 1], 52, iters);
      if (r.first > us[i - 1] && r.first < us[i + 1]) {
        extrema_.push_back({r.first, sign * r.second});
        // Keep the grid sorted: the extremum goes before or after sample i.
        const std::size_t at = grid_u_.size() - (r.first < us[i] ? 1 : 0);
        grid_u_.insert(grid_u_.begin() + static_cast<std::ptrdiff_t>(at), r.first);
        grid_lambda_.insert(grid_lambda_.begin() + static_cast<std::ptrdiff_t>(at),
                            sign * r.second);
      }
    }
    // lambda jumps at this segment's right end (a law branch point)?
    if (s + 2 < edges.size()) {
      const double left = ls[kGridPerSegment];
      const double right = point(b + (edges[s + 2] - b) * 1e-13).lambda;
      if (std::abs(left - right) > 1e-9 * std::max(std::abs(left), std::abs(right))) {
        jump_levels_.push_back(left);
        jump_levels_.push_back(right);
      }
    }
  }
  segment_start_.push_back(grid_u_.size());
  Q_max_ = moments(std::numeric_limits<double>::infinity()).Q;
}

std::vector<double> FastLoadingSum::critical_displacements() const {
  std::vector<double> out;
  auto add = [&](double level) {
    if (level > 0.0 && std::isfinite(level)) out.push_back(level / g_);
  };
  for (double l : jump_levels_) add(l);
  for (const auto& e : extrema_) add(e.lambda);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

FastLoadingSum::Point FastLoadingSum::point(double u) const {
  if (u <= 0.0) return {0.0, 0.0};
  const auto& laws = flat_.laws();
  const double w = u / wc_;
  const auto [f, m] = laws.load_and_mu(w);
  const double z = (d_ + u) / s_a_;
  const double W = norm_ * m * f * (table_ ? table_->density(d_ + u) : std::exp(-0.5 * z * z));
  double lambda = m * u;
  if (!elastic_scaling_) {
    const double a = laws.radius_star(w);
    lambda = a > 0.0 ? m * wc_ * f / a : 0.0;
  }
  return {W, lambda};
}

std::vector<double> FastLoadingSum::boundaries(double level) const {
  std::vector<double> roots;
  if (!(level > 0.0) || !std::isfinite(level)) return roots;
  for (std::size_t s = 0; s + 1 < segment_start_.size(); ++s) {
    // lambda is monotone between neighbouring grid points (extrema are grid points).
    for (std::size_t i = segment_start_[s]; i + 1 < segment_start_[s + 1]; ++i) {
      const bool below0 = grid_lambda_[i] < level;
      const bool below1 = grid_lambda_[i + 1] < level;
      if (below0 == below1) continue;
      roots.push_back(core::find_root([&](double u) { return point(u).lambda - level; }, grid_u_[i],
                                      grid_u_[i + 1], "asperity slip boundary", 52));
    }
  }
  return roots;
}

LoadingMoments FastLoadingSum::at(double delta_star) const {
  return moments(g_ * delta_star);
}

LoadingMoments FastLoadingSum::moments(double c) const {
  std::vector<double> cuts{0.0};
  cuts.insert(cuts.end(), law_breaks_.begin(), law_breaks_.end());
  for (const auto& e : extrema_) cuts.push_back(e.u);
  for (double u : boundaries(c)) cuts.push_back(u);
  cuts.push_back(u_max_);
  std::sort(cuts.begin(), cuts.end());

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
    // h(t) = 1 - (1 - t)^{3/2} (B.15 inverted); its series for small t avoids cancellation.
    const double h =
        t < 1e-3 ? t * (1.5 - t * (0.375 + t * (0.0625 + t * 0.0234375))) : 1.0 - (1.0 - t) * rt;
    m.Q += weight * p.W * h;
    m.dQ += weight * p.W * 1.5 * rt * gl;
    m.d2Q += weight * p.W * (-0.75) / rt * gl * gl;
  };
  auto apply = [&](const Rule& r, double a, double b) {
    const double L = b - a;
    for (std::size_t q = 0; q < r.x.size(); ++q) {
      const double u = r.left[q] ? a + L * r.x[q] : b - L * r.x[q];
      accumulate(u, L * r.w[q]);
    }
  };
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i];
    const double b = cuts[i + 1];
    const double L = b - a;
    if (!(L > 0.0)) continue;
    if (table_) {
      // A measured density: its nodes split the piece; tanh-sinh next to a cut (which may
      // lie far closer than a piece's width), 10-point Gauss-Legendre on the inner pieces
      // (~0.01 wide), 20-point chunks on wider ones.
      split_at_nodes(
          a, b, table_nodes_, [&](double x0, double x1) { apply(tanh_sinh(), x0, x1); },
          [&](double x0, double x1) {
            if (x1 - x0 <= kFixedRuleWidth * s_a_) {
              apply(gauss10(), x0, x1);
              return;
            }
            const auto n = static_cast<std::size_t>(std::ceil((x1 - x0) / (kChunkWidth * s_a_)));
            const double w = (x1 - x0) / static_cast<double>(n);
            for (std::size_t k = 0; k < n; ++k)
              apply(gauss20(), x0 + w * static_cast<double>(k),
                    x0 + w * static_cast<double>(k + 1));
          });
      continue;
    }
    if (point(a + 0.5 * L).W == 0.0) continue;  // mu = 0 on the whole piece (CEB w > 1, KE w > 6.2)
    const auto n =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(L / (kChunkWidth * s_a_))));
    const double w = L / static_cast<double>(n);
    if (n == 1) {
      apply(tanh_sinh(), a, b);
      continue;
    }
    apply(tanh_sinh(), a, a + w);
    for (std::size_t k = 1; k + 1 < n; ++k) {
      apply(gauss20(), a + w * static_cast<double>(k), a + w * static_cast<double>(k + 1));
    }
    apply(tanh_sinh(), b - w, b);
  }
  return m;
}

}  // namespace asperity::surface::detail
