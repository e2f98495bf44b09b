#pragma once
// A backbone given as a user table of force against displacement (a measured virgin
// curve, or one exported by `asperity predict --out` / `asperity flat --backbone`),
// interpolated by the monotone piecewise-cubic Hermite of Fritsch and Carlson (1980) with
// the Fritsch-Butland (1984) slopes, so that the interpolant is non-decreasing wherever
// the table is, passes through every point, and has a continuous tangent for the
// harmonic-balance Newton iterations. Masing's rules (masing.hpp, vibration's
// MasingElement) turn it into a hysteretic element.
#include <string>
#include <utility>
#include <vector>

#include "asperity/hysteresis/backbone.hpp"

namespace asperity::hysteresis {

class TableBackbone final : public Backbone {
 public:
  /// Displacements x [m] and forces Q [N]. Throws InvalidInput (naming `source` and the
  /// point) unless there are at least 2 points, all finite, the first is the origin
  /// (x = 0 and |Q| <= 1e-9 of the largest force: a virgin curve starts there), x
  /// increases strictly, Q never decreases, and Q rises over the first interval (a
  /// positive initial stiffness). Beyond the last point the force stays at the last value
  /// (the table should end at the slip force; limit() is that value).
  TableBackbone(std::vector<double> x, std::vector<double> Q, std::string source = "table");

  [[nodiscard]] double force(double x) const override;
  /// The x with force(x) = Q (bisection on the monotone cubic of Q's interval, to 1e-14
  /// of the interval); InvalidInput for Q >= limit().
  [[nodiscard]] double displacement(double Q) const override;
  [[nodiscard]] double limit() const override { return Q_.back(); }
  /// The slope at 0: the first interval's secant (positive; the end slope of the
  /// interpolant). The slope at the last point is 0 (it joins the constant force beyond),
  /// except for a two-point table, a straight line to the slip force.
  [[nodiscard]] double initial_stiffness() const override { return d_.front(); }
  [[nodiscard]] double stiffness(double x) const override;
  /// Exact integral of the cubic Hermite pieces: h (Q0 + Q1)/2 + h^2 (d0 - d1)/12 a piece.
  [[nodiscard]] double integral(double x) const override;

  [[nodiscard]] const std::vector<double>& x() const { return x_; }
  [[nodiscard]] const std::vector<double>& Q() const { return Q_; }

 private:
  std::vector<double> x_, Q_, d_;   // points and the Hermite slopes at them
  std::vector<double> cumulative_;  // integral from 0 to x_[i]
  [[nodiscard]] std::size_t interval(double x) const;
};

/// A table of `backbone` for export (`asperity predict --out`: backbones.csv): `points`
/// (>= 3) displacements uniform from 0 to x_s = backbone.displacement((1 - 1e-9) limit),
/// where the force is within 1e-9 of the slip force, and one more at 1.25 x_s with the
/// slip force itself (the plateau). Returns {x [m], Q [N]}.
[[nodiscard]] std::pair<std::vector<double>, std::vector<double>> tabulate(
    const Backbone& backbone, std::size_t points = 401);

}  // namespace asperity::hysteresis
