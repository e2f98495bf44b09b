#pragma once
// The single-degree-of-freedom system of Eq. 7.1 under base excitation, in the
// non-dimensional variables of section 7.2 (Table 7.1):
//
//   u'' + eps u' + u = y + eps y' - F_s,   u = x/A, tau = sqrt(k/m) t, eps = c/sqrt(m k),
//                                          y = (base displacement)/A, F_s = f_s/(k A).
//
// Excitations (Table 7.1), in tau:
//   impulse:  y = a sin(Omega tau) for 0 <= tau < pi/Omega, 0 after (Omega = omega f~ in
//             the table; Table 7.2 / section 7.4 use Omega = 10 pi: a pulse of 0.1);
//   ramp:     y = alpha tau. Deviation from the print: Table 7.1's ramp equation leaves
//             out the damper's share eps*alpha of the base velocity; Eq. 7.1 has it and
//             so does this code (it shifts the sliding equilibrium by eps*alpha = 0.032);
//   harmonic: y = a sin(2 pi f~ tau) (f~ = sqrt(m/k) f, f in Hz).
//
// Energy balance, per unit k A^2, integrated as extra ODE states with the motion:
//   E = u'^2/2 + (u - y)^2/2 (kinetic + spring),
//   W_base     = Int (y - u + eps (y' - u')) y' dtau   work of the base on the system,
//   D_damper   = Int eps (u' - y')^2 dtau              dissipated by the damper,
//   W_friction = Int F_s u' dtau                       work against friction (dissipated,
//                                                       plus elastic energy still stored in
//                                                       a hysteretic or Dankowicz contact),
//   E(tau) - E(0) = W_base - D_damper - W_friction.
#include <functional>
#include <memory>
#include <span>
#include <variant>
#include <vector>

#include "asperity/dynamics/friction_model.hpp"
#include "asperity/dynamics/integrator.hpp"

namespace asperity::dynamics {

/// No base motion: free vibration from the initial conditions.
struct FreeVibration {};

/// Half-sine pulse y = amplitude sin(Omega tau) for 0 <= tau < pi/Omega (Table 7.1).
struct ImpulseExcitation {
  double Omega = 31.41592653589793;  ///< pulse frequency in rad per unit tau; > 0
  double amplitude = 1.0;            ///< in units of A
};

/// Ramp y = alpha tau (Table 7.1): alpha = beta sqrt(m/k)/A for a base velocity beta.
struct RampExcitation {
  double alpha = 1.0;  ///< non-dimensional base velocity; finite, != 0
};

/// Harmonic y = amplitude sin(2 pi f tau) (Table 7.1).
struct HarmonicExcitation {
  double frequency = 1.0;  ///< f~ = sqrt(m/k) f: cycles per unit tau; > 0
  double amplitude = 1.0;  ///< in units of A
};

using Excitation =
    std::variant<FreeVibration, ImpulseExcitation, RampExcitation, HarmonicExcitation>;

/// Throws InvalidInput naming the bad field.
void validate(const Excitation& e);

struct BaseMotion {
  double y = 0.0;   ///< displacement / A
  double dy = 0.0;  ///< dy/dtau
};

/// Base motion at tau (right-continuous at the end of an impulse).
[[nodiscard]] BaseMotion base_motion(const Excitation& e, double tau);
/// Times where the base velocity jumps (the end of an impulse).
[[nodiscard]] std::vector<double> breakpoints(const Excitation& e);

/// Non-dimensional structural parameters.
struct SystemParameters {
  double epsilon = 0.032;  ///< c/sqrt(m k) = 2 x damping ratio (Table 7.2); in [0, 2)
  void validate() const;
};

/// Conversion between SI and the non-dimensional variables of section 7.2.
struct DimensionalScales {
  double m = 1.0;  ///< mass [kg]; > 0
  double k = 1.0;  ///< structural stiffness [N/m]; > 0
  double A = 1.0;  ///< displacement scale [m] (the excitation amplitude); > 0
  void validate() const;
  [[nodiscard]] double time() const;    ///< sqrt(m/k) [s]: t = time() tau
  [[nodiscard]] double force() const;   ///< k A [N]
  [[nodiscard]] double energy() const;  ///< k A^2 [J]
  /// eps = c/sqrt(m k) for a damping coefficient c [N s/m].
  [[nodiscard]] double epsilon(double c) const;
  /// Regularized Coulomb parameters from F_max [N] and k_tan [s/m] (Eq. 7.3).
  [[nodiscard]] RegularizedCoulombParameters coulomb(double F_max, double k_tan) const;
  /// Dankowicz parameters from F_max [N] and delta [m] (Eq. 7.6-7.7).
  [[nodiscard]] DankowiczParameters dankowicz(double F_max, double delta) const;
};

/// One sample of a time history as SimulationOptions::sink receives it (the columns of
/// Trajectory at one time).
struct TrajectorySample {
  double tau = 0.0, u = 0.0, v = 0.0, y = 0.0, dy = 0.0, friction = 0.0;
  std::span<const double> internal;  ///< the friction model's internal states
  double work_base = 0.0, dissipated_damper = 0.0, work_friction = 0.0, energy = 0.0;
  bool is_event = false;
};

struct SimulationOptions {
  double duration = 100.0;  ///< end of the integration in tau; > 0
  double u0 = 0.0;          ///< initial displacement
  double v0 = 0.0;          ///< initial velocity
  /// Integrator settings. The state is [u, v, internal states..., W_base, D_damper,
  /// W_friction]; atol may have one entry or one per state. One entry applies to every
  /// state except the friction model's internal states, which get it times
  /// FrictionModel::internal_state_scale (Dankowicz: atol * delta, since |z| <= delta).
  IntegratorOptions integrator{};
  /// 0: record every accepted step; > 0: record uniform samples every this much tau
  /// (from the continuous extension), plus every event.
  double output_interval = 0.0;
  /// Locate velocity reversals even for models that do not need them (for the
  /// extrema of a free decay, say). Models with memory always locate them.
  bool locate_reversals = false;
  /// Samples before this tau are not kept in the Trajectory; they still reach `sink`
  /// and the running totals (Trajectory::initial_energy, max_work_base,
  /// max_abs_internal): a long run keeps only the window its analysis needs (the last
  /// cycles of a harmonic response). The final sample is always kept.
  double record_from = 0.0;
  /// Called with every sample as it is produced, kept or not (to stream a run to disk).
  std::function<void(const TrajectorySample&)> sink;
  /// Throws InvalidInput unless duration > 0, u0 and v0 are finite, output_interval >= 0
  /// and the samples kept (from record_from on) number at most 5e7.
  void validate() const;
};

/// A recorded time history, in non-dimensional variables.
struct Trajectory {
  std::vector<double> tau, u, v, y, dy, friction;
  std::vector<double> work_base, dissipated_damper, work_friction, energy;
  /// The friction model's internal ODE states (Dankowicz: z), one vector per state,
  /// each sampled like tau.
  std::vector<std::vector<double>> internal;
  std::vector<double> event_tau;  ///< located velocity reversals
  std::vector<double> event_u;
  std::vector<bool> is_event;  ///< per sample: sample is a located reversal
  /// Over every sample produced, kept or not (SimulationOptions::record_from):
  std::size_t samples = 0;               ///< number of samples
  double initial_energy = 0.0;           ///< mechanical energy of the first sample
  double max_work_base = 0.0;            ///< largest base work
  std::vector<double> max_abs_internal;  ///< largest |state| per internal state
  IntegratorStats stats;
  std::size_t force_evaluations = 0;
  std::string friction_model;

  /// |E_end - E_0 - (W_base - D_damper - W_friction)| divided by the energy put in:
  /// E_0 plus the largest work the base has done up to any recorded time (or 1e-300 if
  /// both vanish; from the running totals, so a run kept from record_from > 0 gets the
  /// same value as a fully kept one). The largest, not the final, base work: a base can take back
  /// what it gave (the transient of a ramp, a lightly damped harmonic response), leaving a net
  /// input far below the energy in play and a ratio that says nothing about accuracy.
  [[nodiscard]] double energy_balance_error() const;
  [[nodiscard]] std::size_t size() const { return tau.size(); }
};

/// Integrates Eq. 7.1 with a copy of `friction` (its state is not changed).
[[nodiscard]] Trajectory simulate(const SystemParameters& system, const Excitation& excitation,
                                  const FrictionModel& friction, const SimulationOptions& options);

}  // namespace asperity::dynamics
