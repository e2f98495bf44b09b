#include "asperity/hysteresis/tabulated_backbone.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <limits>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::hysteresis {

namespace {

// Intervals over the whole range before bisection (per segment pro rata, at least 2).
constexpr double kInitialIntervals = 16.0;
// Knots closer than this (relative to sqrt(x_end)) to 0, to the end or to each other
// are dropped: a segment that short carries no weight in any force.
constexpr double kKnotGap = 1e-6;
// A sample at a knot is taken this far (relative) inside its own segment, so that each
// segment sees its one-sided derivatives.
constexpr double kInside = 1e-10;
// The fast look-up covers 2^-kFastOctaves of the top octave upwards (below: the reference
// interpolant), with 2^m cells per octave, m from kFastMinBits up to kFastMaxBits.
constexpr int kFastOctaves = 24;
constexpr int kFastMinBits = 2;
constexpr int kFastMaxBits = 6;
// Bucket count at most (bucket width down to the narrowest cell otherwise).
constexpr std::size_t kMaxBuckets = std::size_t{1} << 14;

struct Node {
  double s;  // where the node sits (an exact segment end at a knot)
  double G;  // G(s) = Q_l(s^2)/s^2 and its s-derivatives
  double Gs;
  double Gss;
};

// Quintic Hermite on t in [0, 1] from end values y, first derivatives m and second
// derivatives a (already scaled to t), as polynomial coefficients c0..c5 with the
// standard basis H0 = 1 - 10t^3 + 15t^4 - 6t^5, H1 = t - 6t^3 + 8t^4 - 3t^5,
// H2 = (t^2 - 3t^3 + 3t^4 - t^5)/2, H3 = 10t^3 - 15t^4 + 6t^5,
// H4 = -4t^3 + 7t^4 - 3t^5, H5 = (t^3 - 2t^4 + t^5)/2.
std::array<double, 6> quintic(const Node& a, const Node& b) {
  const double h = b.s - a.s;
  const double y0 = a.G, m0 = a.Gs * h, a0 = a.Gss * h * h;
  const double y1 = b.G, m1 = b.Gs * h, a1 = b.Gss * h * h;
  return {y0,
          m0,
          0.5 * a0,
          -10 * y0 - 6 * m0 - 1.5 * a0 + 10 * y1 - 4 * m1 + 0.5 * a1,
          15 * y0 + 8 * m0 + 1.5 * a0 - 15 * y1 + 7 * m1 - a1,
          -6 * y0 - 3 * m0 - 0.5 * a0 + 6 * y1 - 3 * m1 + 0.5 * a1};
}

double polynomial(const double* c, double t) {
  const double t2 = t * t;
  return (c[0] + c[1] * t) + t2 * ((c[2] + c[3] * t) + t2 * (c[4] + c[5] * t));
}

}  // namespace

void BackboneTabulation::validate() const {
  if (!sample) throw InvalidInput("backbone tabulation: no sample function was given");
  core::require_positive("backbone initial stiffness", initial_stiffness);
  core::require_finite("backbone initial curvature", initial_curvature);
  core::require_positive("backbone limit", limit);
  core::require_positive("backbone table end x_end", x_end);
  // The nodes' derivatives divide by x^3, and the fast look-up reads cells off the exponent
  // of x down to 2^-24 x_end: x_end within 1e+-100 keeps all of it in range (tables of
  // physical quantities in SI or scaled units are).
  if (!(x_end >= 1e-100 && x_end <= 1e100)) {
    throw InvalidInput(fmt::format(
        "backbone table end x_end = {} is not allowed: it must lie in [1e-100, 1e100] (scale "
        "the displacement)",
        core::format_value(x_end)));
  }
  if (!(rel_tol >= 1e-12 && rel_tol <= 1e-3)) {
    throw InvalidInput(
        fmt::format("rel_tol = {} (the backbone table's relative tolerance) is not allowed: it "
                    "must lie in [1e-12, 1e-3]",
                    core::format_value(rel_tol)));
  }
  for (double k : knots) {
    if (!(k > 0.0 && k < x_end)) {
      throw InvalidInput(fmt::format("backbone knot x = {} is not allowed: knots lie in (0, {})",
                                     core::format_value(k), core::format_value(x_end)));
    }
  }
  if (max_intervals < 1 || max_intervals > (std::size_t{1} << 24)) {
    throw InvalidInput(
        fmt::format("table size limit {} is not allowed: it must lie in [1, 2^24]", max_intervals));
  }
}

TabulatedBackbone::TabulatedBackbone(const BackboneTabulation& in)
    : limit_(in.limit), k0_(in.initial_stiffness), x_end_(in.x_end) {
  in.validate();
  const double s_end = std::sqrt(x_end_);

  // G(0) = k0, G'(0) = 0, G''(0) = Q_l''(0) from Q_l = k0 x + Q_l''(0) x^2/2 + o(x^2).
  auto node = [&](double s_geometry, double s_sample) -> Node {
    if (s_sample == 0.0) return {s_geometry, k0_, 0.0, in.initial_curvature};
    const double x = s_sample * s_sample;
    const BackboneSample q = in.sample(x);
    ++samples_;
    if (!std::isfinite(q.Q) || !std::isfinite(q.dQ) || !std::isfinite(q.d2Q)) {
      throw NumericalError(fmt::format(
          "backbone tabulation: the backbone or its derivatives are not finite at x = {:.6g} "
          "(Q = {}, dQ = {}, d2Q = {})",
          x, q.Q, q.dQ, q.d2Q));
    }
    const double G = q.Q / x;
    const double Gx = (x * q.dQ - q.Q) / (x * x);
    const double Gxx = (x * x * q.d2Q - 2.0 * x * q.dQ + 2.0 * q.Q) / (x * x * x);
    return {s_geometry, G, 2.0 * s_sample * Gx, 4.0 * x * Gxx + 2.0 * Gx};
  };

  std::vector<double> edges{0.0};
  {
    std::vector<double> knots = in.knots;
    std::sort(knots.begin(), knots.end());
    for (double x : knots) {
      const double s = std::sqrt(x);
      if (s > kKnotGap * s_end && s < s_end * (1.0 - kKnotGap) &&
          s - edges.back() > kKnotGap * s_end) {
        edges.push_back(s);
      }
    }
    edges.push_back(s_end);
  }

  struct Pending {
    Node a;
    Node b;
  };
  std::vector<Pending> pending;
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    const double a = edges[k];
    const double b = edges[k + 1];
    const auto m = std::max<std::size_t>(
        2, static_cast<std::size_t>(std::ceil(kInitialIntervals * (b - a) / s_end)));
    std::vector<Node> nodes;
    nodes.reserve(m + 1);
    for (std::size_t i = 0; i <= m; ++i) {
      const double s = i == m ? b : a + (b - a) * static_cast<double>(i) / static_cast<double>(m);
      double at = s;
      if (i == 0 && k > 0) at = s * (1.0 + kInside);
      if (i == m) at = s * (1.0 - kInside);  // also at x_end: samples stay in (0, x_end)
      nodes.push_back(node(s, at));
    }
    for (std::size_t i = 0; i < m; ++i) pending.push_back({nodes[i], nodes[i + 1]});
  }
  // Left to right: the stack is popped from its end.
  std::reverse(pending.begin(), pending.end());

  // Bisect every interval whose quintic misses the backbone by more than rel_tol: at its
  // midpoint, against the sample taken there, and at its quarter points, against the two
  // halves' quintics (which use that sample too and are far more accurate: the error of
  // quintic Hermite interpolation scales as h^6). The quarters catch an error that changes
  // sign at the midpoint. An accepted interval is stored as its two halves, so the table
  // is finer than the interpolant whose error was checked.
  while (!pending.empty()) {
    const Pending p = pending.back();
    pending.pop_back();
    const double h = p.b.s - p.a.s;
    const double s_mid = p.a.s + 0.5 * h;
    const Node mid = node(s_mid, s_mid);
    const auto c = quintic(p.a, p.b);
    const auto left = quintic(p.a, mid);
    const auto right = quintic(mid, p.b);
    auto relative = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
    const double error =
        std::max({relative(polynomial(c.data(), 0.5), mid.G),
                  relative(polynomial(c.data(), 0.25), polynomial(left.data(), 0.5)),
                  relative(polynomial(c.data(), 0.75), polynomial(right.data(), 0.5))});
    if (error <= in.rel_tol) {
      for (const auto& [start, coefficients] : {std::pair{p.a.s, left}, std::pair{s_mid, right}}) {
        Cell cell;
        cell.s0 = start;
        cell.inv_h = 2.0 / h;
        std::copy(coefficients.begin(), coefficients.end(), cell.c);
        cells_.push_back(cell);
      }
      verified_error_ = std::max(verified_error_, error);
      continue;
    }
    if (cells_.size() + pending.size() + 2 > in.max_intervals || !(h > 1e-12 * s_end)) {
      throw NumericalError(fmt::format(
          "backbone tabulation: the error {:.3g} near x = {:.6g} is still above {:.3g} with {} "
          "intervals (limit {})",
          error, s_mid * s_mid, in.rel_tol, cells_.size() + pending.size() + 1, in.max_intervals));
    }
    pending.push_back({mid, p.b});
    pending.push_back({p.a, mid});
  }

  // Uniform buckets in s, each pointing at the cell that holds its start.
  const std::size_t n = cells_.size();
  double h_min = std::numeric_limits<double>::infinity();
  for (const Cell& cell : cells_) h_min = std::min(h_min, 1.0 / cell.inv_h);
  const auto buckets = std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(s_end / h_min)),
                                               n, std::max(kMaxBuckets, n));
  inv_bucket_width_ = static_cast<double>(buckets) / s_end;
  Cell sentinel;
  sentinel.s0 = std::numeric_limits<double>::infinity();
  cells_.push_back(sentinel);
  bucket_.resize(buckets + 1);  // + 1: s = s_end maps to the last one
  std::size_t i = 0;
  for (std::size_t j = 0; j <= buckets; ++j) {
    const double start = static_cast<double>(j) / inv_bucket_width_;
    while (i + 1 < n && cells_[i + 1].s0 <= start) ++i;
    bucket_[j] = static_cast<std::uint32_t>(i);
  }

  cumulative_.assign(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    cumulative_[k + 1] = cumulative_[k] + partial_integral(k, 1.0);

  std::vector<double> knots_x;
  for (std::size_t k = 1; k + 1 < edges.size(); ++k) knots_x.push_back(edges[k] * edges[k]);
  build_fast_grid(knots_x, in.rel_tol);
}

BackboneSample TabulatedBackbone::reference_moments(double x, bool from_left) const {
  const std::size_t n = cells_.size() - 1;
  const double s = std::sqrt(x);
  std::size_t i = s >= std::sqrt(x_end_) ? n - 1 : locate(s);
  if (from_left && i > 0 && s <= cells_[i].s0) --i;
  const Cell& c = cells_[i];
  const double t = (s - c.s0) * c.inv_h;
  const double* a = c.c;
  const double G = a[0] + t * (a[1] + t * (a[2] + t * (a[3] + t * (a[4] + t * a[5]))));
  const double Gt = a[1] + t * (2 * a[2] + t * (3 * a[3] + t * (4 * a[4] + t * 5 * a[5])));
  const double Gtt = 2 * a[2] + t * (6 * a[3] + t * (12 * a[4] + t * 20 * a[5]));
  const double Gs = Gt * c.inv_h;
  const double Gss = Gtt * c.inv_h * c.inv_h;
  // Q = x G(s), s = sqrt(x): Q' = G + s G_s/2, Q'' = (3/4) G_s/s + G_ss/4.
  return {x * G, G + 0.5 * s * Gs, 0.75 * Gs / s + 0.25 * Gss};
}

void TabulatedBackbone::build_fast_grid(const std::vector<double>& knots, double rel_tol) {
  // Cells 2^-m of an octave wide on [x_min, x_top): the index is read off the bits of x
  // (biased exponent and m leading mantissa bits, monotone in x > 0). Splits at the knots
  // (where Q_l's derivatives jump) and at x_end (where Q_l becomes the constant limit).
  const double x_top = std::exp2(std::ceil(std::log2(x_end_)));
  const double x_min = std::ldexp(x_top, -kFastOctaves);
  std::vector<double> splits;
  for (double k : knots) {
    if (k > x_min) splits.push_back(k);
  }
  if (x_end_ < x_top) splits.push_back(x_end_);
  std::sort(splits.begin(), splits.end());

  auto piece_for = [&](double p0, double p1, FastPiece& piece) -> double {
    piece.x0 = p0;
    piece.inv_w = 1.0 / (p1 - p0);
    if (p0 >= x_end_) {
      std::fill(std::begin(piece.c), std::end(piece.c), 0.0);
      piece.c[0] = limit_;
      return 0.0;
    }
    const auto a = reference_moments(p0, false);
    const auto b = reference_moments(p1, true);
    const auto c = quintic(Node{p0, a.Q, a.dQ, a.d2Q}, Node{p1, b.Q, b.dQ, b.d2Q});
    std::copy(c.begin(), c.end(), piece.c);
    double worst = 0.0;
    for (const double u : {0.25, 0.5, 0.75}) {
      const double ref = evaluate_reference(p0 + u * (p1 - p0));
      worst = std::max(worst, std::abs(polynomial(piece.c, u) - ref) / std::abs(ref));
    }
    return worst;
  };

  for (int m = kFastMinBits;; ++m) {
    shift_ = static_cast<unsigned>(52 - m);
    base_ = std::bit_cast<std::uint64_t>(x_min) >> shift_;
    const std::uint64_t n = (std::bit_cast<std::uint64_t>(x_top) >> shift_) - base_;
    fast_.assign(n, FastCell{});
    fast_error_ = 0.0;
    bool refine = false;
    auto k = splits.begin();
    for (std::uint64_t i = 0; i < n && !refine; ++i) {
      FastCell& cell = fast_[i];
      const double a = std::bit_cast<double>((base_ + i) << shift_);
      const double b = std::bit_cast<double>((base_ + i + 1) << shift_);
      while (k != splits.end() && *k <= a) ++k;
      auto k_end = k;
      while (k_end != splits.end() && *k_end < b) ++k_end;
      const auto inside = k_end - k;
      double error = 0.0;
      if (inside == 0) {
        cell.split = std::numeric_limits<double>::infinity();
        error = piece_for(a, b, cell.piece[0]);
        cell.piece[1] = cell.piece[0];
      } else if (inside == 1) {
        cell.split = *k;
        error = std::max(piece_for(a, *k, cell.piece[0]), piece_for(*k, b, cell.piece[1]));
      } else {
        cell.fallback = 1;
        continue;
      }
      if (!(error <= rel_tol)) {
        if (m < kFastMaxBits) {
          refine = true;
          continue;
        }
        cell.fallback = 1;  // the finest grid allowed: this cell defers to the reference
        continue;
      }
      fast_error_ = std::max(fast_error_, error);
    }
    if (!refine) return;
  }
}

double TabulatedBackbone::evaluate_outside(double x) const noexcept {
  if (x >= x_end_) return limit_;
  if (x >= 0.0) return evaluate_reference(x);
  return std::numeric_limits<double>::quiet_NaN();
}

std::size_t TabulatedBackbone::fallback_cells() const {
  std::size_t n = 0;
  for (const auto& c : fast_) n += c.fallback ? 1 : 0;
  return n;
}

void TabulatedBackbone::reject_displacement(double x) {
  core::require_non_negative("displacement x", x);
  throw InvalidInput("displacement x must be >= 0");  // not reached: x is negative or NaN
}

double TabulatedBackbone::partial_integral(std::size_t i, double t) const {
  // Q_l dx = s^2 G(s) 2 s ds: degree 8 in s on a cell; 5-point Gauss-Legendre is exact.
  static constexpr double kNodes[5] = {0.0469100770306680, 0.2307653449471585, 0.5,
                                       0.7692346550528415, 0.9530899229693320};
  static constexpr double kWeights[5] = {0.1184634425280945, 0.2393143352496832, 0.2844444444444444,
                                         0.2393143352496832, 0.1184634425280945};
  const Cell& c = cells_[i];
  const double h = 1.0 / c.inv_h;
  double acc = 0.0;
  for (int q = 0; q < 5; ++q) {
    const double u = t * kNodes[q];
    const double s = c.s0 + h * u;
    acc += kWeights[q] * 2.0 * s * s * s * polynomial(c.c, u);
  }
  return acc * t * h;
}

double TabulatedBackbone::integral(double x) const {
  core::require_non_negative("displacement x", x);
  if (x == 0.0) return 0.0;
  const std::size_t n = cells_.size() - 1;
  if (x >= x_end_) return cumulative_[n] + limit_ * (x - x_end_);
  const double s = std::sqrt(x);
  const std::uint32_t i = locate(s);
  return cumulative_[i] + partial_integral(i, (s - cells_[i].s0) * cells_[i].inv_h);
}

double TabulatedBackbone::displacement(double Q) const {
  core::require_non_negative("tangential force", Q);
  if (Q == 0.0) return 0.0;
  const double top = evaluate(x_end_ * (1.0 - 1e-15));
  if (Q >= top) {
    throw InvalidInput(fmt::format(
        "tangential force {} reaches the static friction limit {}: the contact slides (no "
        "finite displacement under force control)",
        core::format_value(Q), core::format_value(limit_)));
  }
  // Q_l is increasing: the last cell starting at or below Q, then its quintic by TOMS 748.
  const std::size_t n = cells_.size() - 1;
  const auto first_above =
      std::partition_point(cells_.begin(), cells_.begin() + static_cast<std::ptrdiff_t>(n),
                           [Q](const Cell& c) { return c.s0 * c.s0 * c.c[0] <= Q; });
  const auto i = static_cast<std::size_t>(first_above - cells_.begin());  // >= 1: cell 0 has Q = 0
  const double lo = cells_[i - 1].s0;
  const double hi = i < n ? cells_[i].s0 : std::sqrt(x_end_ * (1.0 - 1e-15));
  const double s = core::find_root([&](double v) { return evaluate(v * v) - Q; }, lo, hi,
                                   "tabulated backbone inverse", 52);
  return s * s;
}

}  // namespace asperity::hysteresis
