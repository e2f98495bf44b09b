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
  /// Integral of Q_l from 0 to x (x >= 0), for energy per cycle. Default: adaptive
  /// quadrature of force().
  [[nodiscard]] virtual double integral(double x) const;
};

}  // namespace asperity::hysteresis
