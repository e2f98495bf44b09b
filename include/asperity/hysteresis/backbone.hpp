#pragma once
// The backbone (virgin loading curve) that Masing's rules turn into a hysteretic force
// law (SEED_NOTES.md, "Masing's rules hold exactly").

namespace asperity::hysteresis {

/// The virgin loading curve Q_l(x) for x >= 0 (extended as an odd function):
/// continuous, non-decreasing, Q_l(0) = 0, bounded by limit().
class Backbone {
 public:
  virtual ~Backbone() = default;
  /// Q_l(x) for x >= 0.
  [[nodiscard]] virtual double force(double x) const = 0;
  /// Inverse: the x >= 0 with Q_l(x) = Q for 0 <= Q < limit(). Throws InvalidInput
  /// for Q >= limit() (the contact slides: no finite displacement).
  [[nodiscard]] virtual double displacement(double Q) const = 0;
  /// sup Q_l: the static friction force.
  [[nodiscard]] virtual double limit() const = 0;
  /// dQ_l/dx at x = 0: the stiffness at every reversal.
  [[nodiscard]] virtual double initial_stiffness() const = 0;
  /// dQ_l/dx for x >= 0 (the tangent on the virgin curve; 0 where Q_l has reached its
  /// limit). Default: a central difference of force() with step 1e-6 (x + h) (one-sided at
  /// x < h), relative accuracy ~1e-10 on a smooth backbone; the library's backbones
  /// override it with their exact derivative.
  [[nodiscard]] virtual double stiffness(double x) const;
  /// Integral of Q_l from 0 to x (x >= 0), for energy per cycle. Default: adaptive
  /// quadrature of force().
  [[nodiscard]] virtual double integral(double x) const;
};

}  // namespace asperity::hysteresis
