#pragma once
// A backbone tabulated once, with a verified error bound, and evaluated inline: the
// "Coulomb-fast" friction law of ARCHITECTURE.md ("Performance shape"). Only the
// backbone needs the expensive statistical integral; Masing's rules build every other
// branch from it, so one table per load case serves any displacement history.
//
// Representation: Q_l(x) = x G(s) with s = sqrt(x) and G piecewise quintic Hermite in s
// (values, first and second derivatives matched at the nodes). A backbone that starts
// as Q_l = k0 x + Q_l''(0) x^2/2 + O(x^{5/2}) (a rough flat, one Mindlin asperity) has
// a G that is smooth in s with G(0) = k0, so the relative accuracy near the origin is
// the same as elsewhere. Knots given by the caller (where Q_l is less smooth) are
// interval ends; between them intervals are bisected until each interval's quintic
// matches the sample at its midpoint and its two halves' quintics at its quarter points
// to `rel_tol`; the accepted interval is then stored as those two halves (quintic Hermite
// error scales as h^6, so they are far more accurate than what was checked).
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "asperity/hysteresis/backbone.hpp"

namespace asperity::hysteresis {

/// A backbone's value and its first two derivatives in x at one point.
struct BackboneSample {
  double Q = 0.0;
  double dQ = 0.0;
  double d2Q = 0.0;
};

/// What a table is built from. Validated by the TabulatedBackbone constructor.
struct BackboneTabulation {
  /// Q_l(x) with its first two derivatives (finite), called for 0 < x < x_end: knots and
  /// the end are sampled a hair (1e-10 relative) inside the segment they bound, so a
  /// derivative that jumps or diverges there is seen from one side.
  std::function<BackboneSample(double)> sample;
  double initial_stiffness = 0.0;  ///< Q_l'(0), > 0
  double initial_curvature = 0.0;  ///< Q_l''(0), finite
  double limit = 0.0;              ///< sup Q_l, > 0
  double x_end = 0.0;              ///< Q_l = limit for x >= x_end (to the caller's accuracy), > 0
  std::vector<double> knots;       ///< x in (0, x_end) where Q_l or a derivative jumps
  double rel_tol = 1e-9;           ///< verified bound on the relative error, in [1e-12, 1e-3]
  std::size_t max_intervals = 1u << 13;  ///< NumericalError beyond

  void validate() const;
};

/// The tabulated backbone. Immutable after construction: every member is const and
/// thread-safe. force() is final and evaluate() is inline, so Hysteresis calls it
/// without a virtual dispatch.
class TabulatedBackbone : public Backbone {
 public:
  explicit TabulatedBackbone(const BackboneTabulation& input);

  /// Q_l(x) for x >= 0; InvalidInput for a negative or NaN x.
  [[nodiscard]] double force(double x) const final {
    if (!(x >= 0.0)) reject_displacement(x);
    return evaluate_non_negative(x);
  }
  [[nodiscard]] double displacement(double Q) const final;
  [[nodiscard]] double limit() const final { return limit_; }
  [[nodiscard]] double initial_stiffness() const final { return k0_; }
  [[nodiscard]] double integral(double x) const final;
  /// dQ_l/dx of the same interpolant that force() evaluates (fast cells, or the
  /// reference where a cell defers to it); 0 where the value is capped at the limit.
  [[nodiscard]] double stiffness(double x) const final {
    if (!(x >= 0.0)) reject_displacement(x);
    return slope_non_negative(x);
  }
  [[nodiscard]] double slope_non_negative(double x) const noexcept {
    const std::uint64_t i = (std::bit_cast<std::uint64_t>(x) >> shift_) - base_;
    if (i >= fast_.size()) [[unlikely]]
      return x >= x_end_ ? 0.0 : slope_reference(x);
    const FastCell& c = fast_[i];
    if (c.fallback) [[unlikely]]
      return slope_reference(x);
    const FastPiece& p = c.piece[x >= c.split ? 1 : 0];
    const double u = (x - p.x0) * p.inv_w;
    const double u2 = u * u;
    const double Q =
        (p.c[0] + p.c[1] * u) + u2 * ((p.c[2] + p.c[3] * u) + u2 * (p.c[4] + p.c[5] * u));
    if (!(Q < limit_)) return 0.0;
    return ((p.c[1] + 2.0 * p.c[2] * u) +
            u2 * ((3.0 * p.c[3] + 4.0 * p.c[4] * u) + 5.0 * p.c[5] * u2)) *
           p.inv_w;
  }
  /// evaluate_non_negative(x) and slope_non_negative(x) from one look-up, equal to the two
  /// calls bit for bit.
  struct ValueSlope {
    double Q = 0.0;
    double dQ = 0.0;
  };
  [[nodiscard]] ValueSlope value_and_slope_non_negative(double x) const noexcept {
    const std::uint64_t i = (std::bit_cast<std::uint64_t>(x) >> shift_) - base_;
    if (i >= fast_.size() || fast_[i].fallback) [[unlikely]]
      return {evaluate_non_negative(x), slope_non_negative(x)};
    const FastCell& c = fast_[i];
    const FastPiece& p = c.piece[x >= c.split ? 1 : 0];
    const double u = (x - p.x0) * p.inv_w;
    const double u2 = u * u;
    const double Q =
        (p.c[0] + p.c[1] * u) + u2 * ((p.c[2] + p.c[3] * u) + u2 * (p.c[4] + p.c[5] * u));
    if (!(Q < limit_)) return {limit_, 0.0};
    return {Q, ((p.c[1] + 2.0 * p.c[2] * u) +
                u2 * ((3.0 * p.c[3] + 4.0 * p.c[4] * u) + 5.0 * p.c[5] * u2)) *
                   p.inv_w};
  }
  /// dQ_l/dx of the reference interpolant: Q = x G(s), dQ/dx = G + s G'(s)/2.
  [[nodiscard]] double slope_reference(double x) const noexcept {
    if (x >= x_end_) return 0.0;
    const double s = std::sqrt(x);
    const Cell& c = cells_[locate(s)];
    const double t = (s - c.s0) * c.inv_h;
    const double t2 = t * t;
    const double G =
        (c.c[0] + c.c[1] * t) + t2 * ((c.c[2] + c.c[3] * t) + t2 * (c.c[4] + c.c[5] * t));
    if (!(x * G < limit_)) return 0.0;
    const double dG = ((c.c[1] + 2.0 * c.c[2] * t) +
                       t2 * ((3.0 * c.c[3] + 4.0 * c.c[4] * t) + 5.0 * c.c[5] * t2)) *
                      c.inv_h;
    return G + 0.5 * s * dG;
  }

  /// Q_l(x) for any x: 0 for x <= 0 or NaN, else evaluate_non_negative(x).
  [[nodiscard]] double evaluate(double x) const noexcept {
    return x > 0.0 ? evaluate_non_negative(x) : 0.0;
  }
  /// Q_l(x) for x >= 0 (NaN gives NaN): what Hysteresis calls inline. A look-up by the
  /// floating-point exponent and leading mantissa bits of x (cells uniform within each
  /// 2^-m of an octave), one of at most two quintics in x per cell, no square root.
  /// Never above limit(): the interpolant is capped there, within its error bound.
  [[nodiscard]] double evaluate_non_negative(double x) const noexcept {
    const std::uint64_t i = (std::bit_cast<std::uint64_t>(x) >> shift_) - base_;
    if (i >= fast_.size()) [[unlikely]]
      return evaluate_outside(x);
    const FastCell& c = fast_[i];
    if (c.fallback) [[unlikely]]
      return evaluate_reference(x);
    const FastPiece& p = c.piece[x >= c.split ? 1 : 0];
    const double u = (x - p.x0) * p.inv_w;
    const double u2 = u * u;
    // Estrin's scheme: a shorter dependency chain than Horner's.
    const double Q =
        (p.c[0] + p.c[1] * u) + u2 * ((p.c[2] + p.c[3] * u) + u2 * (p.c[4] + p.c[5] * u));
    return Q < limit_ ? Q : limit_;
  }
  /// The same from the reference interpolant in s = sqrt(x) (the verified one): a square
  /// root, a bucket look-up and a quintic. For x >= 0.
  [[nodiscard]] double evaluate_reference(double x) const noexcept {
    if (x >= x_end_) return limit_;
    const double s = std::sqrt(x);
    const Cell& c = cells_[locate(s)];
    const double t = (s - c.s0) * c.inv_h;
    const double t2 = t * t;
    const double G =
        (c.c[0] + c.c[1] * t) + t2 * ((c.c[2] + c.c[3] * t) + t2 * (c.c[4] + c.c[5] * t));
    const double Q = x * G;
    return Q < limit_ ? Q : limit_;
  }

  /// Checked error bound: the largest relative error found while building the reference
  /// (each accepted interval's quintic against the midpoint sample and against its halves
  /// at the quarter points; the stored halves are finer still) plus the largest between
  /// the fast cells and the reference at their check points.
  [[nodiscard]] double verified_error() const { return verified_error_ + fast_error_; }
  [[nodiscard]] std::size_t intervals() const { return cells_.size() - 1; }
  /// x where the table ends (Q_l = limit beyond).
  [[nodiscard]] double table_end() const { return x_end_; }
  /// Backbone samples taken to build the table (nodes and check points).
  [[nodiscard]] std::size_t samples() const { return samples_; }
  /// Cells of the fast look-up (2^m per octave of x) and how many of them hold more than
  /// one knot, so that they defer to the reference interpolant.
  [[nodiscard]] std::size_t fast_cells() const { return fast_.size(); }
  [[nodiscard]] std::size_t fallback_cells() const;

 private:
  struct alignas(64) Cell {  // one interval [s0, s0 + h) in s = sqrt(x): one cache line
    double s0 = 0.0;
    double inv_h = 0.0;
    double c[6] = {};  // G(s0 + h t) = sum c_k t^k, t in [0, 1]
  };
  // Q(x) = sum c_k u^k, u = (x - x0) inv_w, on one side of a cell's split.
  struct FastPiece {
    double x0 = 0.0;
    double inv_w = 0.0;
    double c[6] = {};
  };
  struct FastCell {
    double split = 0.0;          // piece[1] from here on (+inf: piece[0] on the whole cell)
    std::uint64_t fallback = 0;  // more than one knot inside: use the reference
    FastPiece piece[2];
  };
  [[nodiscard]] double partial_integral(std::size_t i, double t) const;
  [[noreturn]] static void reject_displacement(double x);
  [[nodiscard]] double evaluate_outside(double x) const noexcept;
  // Q_l and its x-derivatives from the reference interpolant; at a cell boundary, those of
  // the cell on the left when from_left.
  [[nodiscard]] BackboneSample reference_moments(double x, bool from_left) const;
  void build_fast_grid(const std::vector<double>& knots, double rel_tol);
  // The cell holding s in [0, sqrt(x_end)]: a bucket gives the cell at its start; a bucket
  // holds at most one cell boundary unless cells are finer than the finest bucket grid
  // allowed, so one branch-free step almost always suffices.
  [[nodiscard]] std::uint32_t locate(double s) const noexcept {
    std::uint32_t i = bucket_[static_cast<std::size_t>(s * inv_bucket_width_)];
    i += static_cast<std::uint32_t>(s >= cells_[i + 1].s0);
    while (s >= cells_[i + 1].s0) ++i;
    return i;
  }

  double limit_ = 0.0;
  double k0_ = 0.0;
  double x_end_ = 0.0;
  double inv_bucket_width_ = 0.0;
  double verified_error_ = 0.0;
  std::size_t samples_ = 0;
  std::vector<Cell> cells_;            // intervals, then a sentinel with s0 = +inf
  std::vector<std::uint32_t> bucket_;  // uniform buckets in s -> first cell overlapping
  std::vector<double> cumulative_;     // Int_0^{x_i} Q_l dx at every cell start
  std::vector<FastCell> fast_;         // 2^m cells per octave on [x_min, x_top)
  unsigned shift_ = 64;                // 52 - m
  std::uint64_t base_ = 0;             // bits(x_min) >> shift_
  double fast_error_ = 0.0;
};

}  // namespace asperity::hysteresis
