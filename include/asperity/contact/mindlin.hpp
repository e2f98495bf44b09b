#pragma once
// Cattaneo-Mindlin partial slip of an elastic sphere under constant normal load and
// Mindlin-Deresiewicz unloading/reloading (Eq. 3.6-3.12, B.14-B.20).
//
// Tilde variables: Q~ = Q/(mu P), delta~ = 16 G* a delta/(3 mu P) (Appendix B.2).
// Gross slip starts at delta~ = 1 (Q~ = 1).
#include <cstddef>
#include <vector>

namespace asperity::contact {

namespace mindlin {

/// Full stick, B.14: delta~ = 2/3 Q~ for Q~ in [0, 1]. Every function below throws
/// InvalidInput (naming the variable, its value and the allowed range) outside its
/// domain, NaN included.
[[nodiscard]] double stick_displacement_tilde(double Q_tilde);
/// Partial slip, increasing Q, B.15: delta~ = 1 - (1 - Q~)^{2/3}, Q~ in [0, 1].
[[nodiscard]] double loading_displacement_tilde(double Q_tilde);
/// Inverse of B.15: Q~ = 1 - (1 - delta~)^{3/2} for delta~ in [0, 1), 1 beyond
/// (gross slip). Odd in delta~; any finite delta~.
[[nodiscard]] double loading_force_tilde(double delta_tilde);
/// Unloading from Q~max, B.16 (delta~ for a force Q~ in [-Q~max, Q~max]).
[[nodiscard]] double unloading_displacement_tilde(double Q_tilde, double Q_max_tilde);
/// Reloading from -Q~max, B.17.
[[nodiscard]] double reloading_displacement_tilde(double Q_tilde, double Q_max_tilde);
/// Unloading force for a displacement, from a reversal at delta~max (any amplitude,
/// gross slip included): Q~ = Q~l(delta~max) - 2 Q~l((delta~max - delta~)/2).
[[nodiscard]] double unloading_force_tilde(double delta_tilde, double delta_max_tilde);
/// Reloading force from a reversal at -delta~max: -unloading(-delta~).
[[nodiscard]] double reloading_force_tilde(double delta_tilde, double delta_max_tilde);
/// Energy per cycle over 9 (mu P)^2/(10 G* a), B.19, for Q~max in [0, 1].
[[nodiscard]] double energy_tilde(double Q_max_tilde);
/// Small-amplitude form of B.19 (B.20): 5 Q~^3/162 (1 + 2 Q~/3), Q~max in [0, 1].
[[nodiscard]] double energy_tilde_small_amplitude(double Q_max_tilde);
/// Energy per cycle for a displacement amplitude delta~max >= 0 in partial or gross
/// slip: B.19 for delta~max <= 1, 1/6 + 5/6 (delta~max - 1) beyond.
[[nodiscard]] double energy_tilde_for_displacement(double delta_max_tilde);

}  // namespace mindlin

enum class SlipRegime { partial_slip, gross_slip };
[[nodiscard]] const char* to_string(SlipRegime r);

/// Points of a fretting loop: virgin loading 0 -> delta_max, unloading to -delta_max,
/// reloading back to delta_max. `branch` is 0, 1, 2 for the three parts.
struct FrettingLoop {
  std::vector<double> delta;  ///< [m]
  std::vector<double> Q;      ///< [N]
  std::vector<int> branch;
};

/// Dimensional Cattaneo-Mindlin contact: friction coefficient mu, normal load P,
/// combined shear modulus G*, contact radius a. Evaluation is const and cheap.
class MindlinContact {
 public:
  /// mu >= 0, P >= 0, G* > 0, a > 0 (a = 0 only with P = 0). Throws InvalidInput.
  MindlinContact(double mu, double P, double G_star, double a);

  [[nodiscard]] double mu() const { return mu_; }
  [[nodiscard]] double P() const { return P_; }
  /// Static friction force mu P [N].
  [[nodiscard]] double Q_max() const { return mu_ * P_; }
  /// Tangential stiffness at Q = 0 and at every reversal, 8 G* a (Eq. 3.11) [N/m].
  [[nodiscard]] double stiffness() const { return 8.0 * G_star_ * a_; }
  /// Displacement at the onset of gross slip, 3 mu P/(16 G* a) [m].
  [[nodiscard]] double slip_displacement() const;

  /// Virgin loading force for a displacement of either sign (B.15 inverted) [N].
  [[nodiscard]] double loading_force(double delta) const;
  /// Virgin loading displacement for |Q| <= mu P (B.15) [m]; throws beyond.
  [[nodiscard]] double loading_displacement(double Q) const;
  /// Unloading force at delta after a reversal at delta_max > 0 [N].
  [[nodiscard]] double unloading_force(double delta, double delta_max) const;
  /// Reloading force at delta after a reversal at -delta_max [N].
  [[nodiscard]] double reloading_force(double delta, double delta_max) const;
  /// Unloading displacement at Q after a reversal at Q_max <= mu P (B.16) [m].
  [[nodiscard]] double unloading_displacement(double Q, double Q_max) const;
  /// Reloading displacement at Q after a reversal at -Q_max (B.17) [m].
  [[nodiscard]] double reloading_displacement(double Q, double Q_max) const;

  [[nodiscard]] SlipRegime regime_for_displacement(double delta_max) const;
  /// Energy dissipated per cycle of amplitude delta_max (B.19, or gross slip) [J].
  [[nodiscard]] double energy_per_cycle(double delta_max) const;
  /// Energy per cycle for a force amplitude Q_max <= mu P (B.19) [J].
  [[nodiscard]] double energy_per_cycle_for_force(double Q_max) const;

  /// Loading, unloading and reloading branches, `points` per branch (>= 2).
  [[nodiscard]] FrettingLoop loop(double delta_max, std::size_t points = 101) const;

 private:
  double mu_;
  double P_;
  double G_star_;
  double a_;
};

}  // namespace asperity::contact
