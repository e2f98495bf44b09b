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

/// Q*_l and its derivatives at separation d*: composite 20-point Gauss-Legendre over
/// chunks no wider than sigma_a, split at the laws' branch points and at the asperity
/// slip boundaries lambda(u) = 4 (G*/E*) delta*, with u = u_b + L s^2 near each boundary
/// (and near u = 0) so that the (u - u_b)^{k/2} behaviour becomes polynomial.
class FastLoadingSum {
 public:
  FastLoadingSum(const RoughFlat& flat, double d_star);
  [[nodiscard]] LoadingMoments at(double delta_star) const;
  [[nodiscard]] double static_friction() const { return Q_max_; }
  /// Values of 4 (G*/E*) delta* where Q*_l is less smooth: the slip length lambda(u) on
  /// either side of each law branch point, and its interior extrema (where two slip
  /// boundaries meet). The table puts knots there.
  [[nodiscard]] std::vector<double> critical_displacements() const;

 private:
  struct Point {
    double W;       // prefactor * mu f phi
    double lambda;  // slip length
  };
  [[nodiscard]] Point point(double u) const;
  [[nodiscard]] std::vector<double> boundaries(double level) const;

  const RoughFlat& flat_;
  double d_;
  double s_a_;
  double wc_;
  double g_;  // 4 G*/E*
  double u_max_ = 0.0;
  double norm_ = 0.0;
  double Q_max_ = 0.0;
  std::vector<double> law_breaks_;
  std::vector<double> grid_u_;  // for locating slip boundaries
  std::vector<double> grid_lambda_;
};

}  // namespace asperity::surface::detail
