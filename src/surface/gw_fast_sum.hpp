#pragma once
// Internal: a fast, fixed-rule evaluation of the rough flat's virgin loading curve and
// its first two derivatives in one pass, for building the tabulated backbone.
#include <vector>

#include "asperity/surface/rough_flat.hpp"

namespace asperity::surface::detail {

struct LoadingMoments {
  double Q = 0.0;    ///< Q*_l
  double dQ = 0.0;   ///< dQ*_l/d delta*
  double d2Q = 0.0;  ///< d2Q*_l/d delta*2
};

/// Q*_l and its derivatives at separation d* (Eq. 4.10 with the erratum, and its
/// delta*-derivatives), summed over asperity heights u = z* - d* in [0, u_max] by a fixed
/// rule: the range is cut at u = 0, at the laws' branch points, at the interior extrema
/// of the slip length lambda(u) and at the slip boundaries lambda(u) = 4 (G*/E*) delta*;
/// every piece is split into chunks no wider than sigma_a; chunks that touch a cut use a
/// fixed tanh-sinh rule (the integrand may behave like (u - u_b)^{k/2}, like u^{1.04} at
/// u = 0 for BKE, or have a singularity just outside the chunk, e.g. CEB's
/// (1 - w)^{1/2} next to a slip boundary), inner chunks 20-point Gauss-Legendre. The
/// nodes move continuously with delta* except where a slip boundary appears or vanishes
/// (critical_displacements), so Q*_l is as smooth in delta* as the exact sum between
/// those points. Over a measured summit-height table its nodes split the pieces too (inner
/// pieces 10-point Gauss-Legendre). Relative accuracy ~1e-13 (tests/surface/rough_flat_test.cpp
/// checks it against the adaptive quadrature of RoughFlat).
class FastLoadingSum {
 public:
  FastLoadingSum(const RoughFlat& flat, double d_star);
  [[nodiscard]] LoadingMoments at(double delta_star) const;
  /// Q*_max (Eq. 4.7): the same rule with every asperity in full slip, so that Q*_l
  /// equals it exactly once the slip boundaries have left the range.
  [[nodiscard]] double static_friction() const { return Q_max_; }
  /// Values of delta* where Q*_l is less smooth: a slip boundary crossing a jump of
  /// lambda at a law branch point, or an interior extremum of lambda (where two slip
  /// boundaries meet). The table puts knots there.
  [[nodiscard]] std::vector<double> critical_displacements() const;

 private:
  struct Point {
    double W;       // prefactor * mu f phi
    double lambda;  // slip length
  };
  struct Extremum {
    double u;
    double lambda;
  };
  [[nodiscard]] Point point(double u) const;
  [[nodiscard]] LoadingMoments moments(double c) const;
  [[nodiscard]] std::vector<double> boundaries(double level) const;

  const RoughFlat& flat_;
  const SummitHeightTable* table_;  // null: Gaussian heights (Eq. 4.2)
  double d_;
  double s_a_;
  double wc_;
  double g_;  // 4 G*/E*
  bool elastic_scaling_;
  double u_max_ = 0.0;
  double norm_ = 0.0;
  double Q_max_ = 0.0;
  std::vector<double> law_breaks_;
  std::vector<double> table_nodes_;  // a measured table's nodes in u, ascending
  std::vector<Extremum> extrema_;
  // lambda sampled on each law segment, including its interior extrema, so that lambda is
  // monotone between neighbouring samples: [segment_start_[k], segment_start_[k+1]).
  std::vector<double> grid_u_;
  std::vector<double> grid_lambda_;
  std::vector<std::size_t> segment_start_;
  std::vector<double> jump_levels_;  // one-sided lambda at law breaks where it jumps
};

}  // namespace asperity::surface::detail
