#pragma once
// The Odfalk-Vingsbo elastic-plastic tangential law (thesis Eq. 3.10, after Odfalk and
// Vingsbo 1992, thesis ref. [26]): a parallelogram of plastic slip superposed on the
// elastic (Masing) loop, delta = delta_elastic(Q) + delta_p(Q), both at the same force.
//
//   delta_p = beta (gamma (Q + Q_ty)/k_p + (Q_m - Q_ty)/(2 k_p))        (Eq. 3.10)
//   beta = 1 when Q_m > Q_ty, else 0;  gamma = 1 when |Q| > Q_ty and Q dQ/dt > 0, else 0.
//
// A phenomenological law: the fretting yield point Q_ty and the fretting hardening
// coefficient k_p "are obtained experimentally and could not be generalized" (thesis
// section 3.3). They are the user's, measured on the contact whose loop they describe;
// asperity never supplies or fits them (docs/joints.md).
//
// As a history operator: plastic slip grows at dQ/k_p while |Q| > Q_ty and the force moves
// away from zero (gamma), and at dQ/(2 k_p) while |Q| exceeds every earlier |Q| (the
// virgin curve, as Masing's virgin curve is the branch at half scale), so that a symmetric
// cycle of force amplitude Q_m follows Eq. 3.10 from its first reversal on, centred:
// delta_p in [-(Q_m - Q_ty)/(2 k_p), (Q_m - Q_ty)/(2 k_p)]. Cycles that are not symmetric
// follow gamma literally (plastic slip whenever the force passes Q_ty outwards).
#include <memory>
#include <span>
#include <vector>

#include "asperity/hysteresis/masing.hpp"

namespace asperity::hysteresis {

struct OdfalkVingsboParameters {
  double fretting_yield_point = 0.0;   ///< Q_ty [N] (> 0), measured
  double hardening_coefficient = 0.0;  ///< k_p [N/m] (> 0), measured
  /// InvalidInput naming the field unless both are finite and > 0.
  void validate() const;
};

/// delta_p of Eq. 3.10 on the steady symmetric loop of force amplitude Q_m, at force Q on
/// the unloading branch (`unloading` true, from Q_m down to -Q_m) or the reloading branch
/// (its mirror image). [m]
[[nodiscard]] double odfalk_vingsbo_plastic_slip(const OdfalkVingsboParameters& p, double Q,
                                                 double Q_m, bool unloading);

/// Plastic energy dissipated per symmetric cycle of force amplitude Q_m: the parallelogram's
/// area, (Q_m^2 - Q_ty^2)/k_p for Q_m > Q_ty, else 0. [J]
[[nodiscard]] double odfalk_vingsbo_plastic_energy(const OdfalkVingsboParameters& p, double Q_m);

/// Steady symmetric cycle of displacement amplitude x_m: the force amplitude Q_m (the root
/// of x_m = x_l(Q_m) + delta_p(Q_m) on the virgin curve) and the energy per cycle (Masing's
/// on the elastic amplitude x_l(Q_m), plus the parallelogram's).
struct OdfalkVingsboCycle {
  double Q_m = 0.0;                ///< force amplitude [N]
  double elastic_amplitude = 0.0;  ///< x_l(Q_m) [m]
  double plastic_amplitude = 0.0;  ///< (Q_m - Q_ty)^+/(2 k_p) [m]
  double energy = 0.0;             ///< energy per cycle [J]
};
[[nodiscard]] OdfalkVingsboCycle odfalk_vingsbo_cycle(const Backbone& elastic,
                                                      const OdfalkVingsboParameters& p, double x_m);

/// The plastic slip of Eq. 3.10 along a force history (the rules above).
class OdfalkVingsboSlip {
 public:
  explicit OdfalkVingsboSlip(const OdfalkVingsboParameters& p);
  /// delta_p after monotone motion of the force from Q() to Q, without changing the state.
  [[nodiscard]] double peek(double Q) const;
  /// Moves the force to Q (monotone from Q()); returns delta_p.
  double update(double Q);
  [[nodiscard]] double Q() const { return Q_; }
  [[nodiscard]] double slip() const { return delta_p_; }
  [[nodiscard]] const OdfalkVingsboParameters& parameters() const { return p_; }

 private:
  OdfalkVingsboParameters p_;
  double Q_ = 0.0;
  double delta_p_ = 0.0;
  double Q_envelope_ = 0.0;  // largest |Q| so far
};

/// The elastic-plastic contact: Masing hysteresis on the elastic backbone with the plastic
/// slip in series (Eq. 3.10 added to Eq. 3.8/3.9 at the same force), displacement-driven.
class OdfalkVingsboHysteresis {
 public:
  OdfalkVingsboHysteresis(std::shared_ptr<const Backbone> elastic,
                          const OdfalkVingsboParameters& p);
  /// Moves the contact to total displacement x; returns the force. The elastic
  /// displacement is the root (TOMS 748) of x_e + delta_p(Q(x_e)) = x, which rises
  /// strictly with x_e along a monotone step.
  double update(double x);
  /// Moves the force to Q; returns the total displacement (gross slip under force control
  /// is an InvalidInput, as Hysteresis::update_force).
  double update_force(double Q);
  /// Forces along a displacement history from the current state, without changing it.
  [[nodiscard]] std::vector<double> forces(std::span<const double> x_history) const;
  [[nodiscard]] double x() const { return x_; }
  [[nodiscard]] double Q() const { return elastic_.Q(); }
  [[nodiscard]] double plastic_slip() const { return plastic_.slip(); }

 private:
  Hysteresis elastic_;
  OdfalkVingsboSlip plastic_;
  double x_ = 0.0;
};

}  // namespace asperity::hysteresis
