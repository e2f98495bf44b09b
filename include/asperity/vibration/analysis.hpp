#pragma once
// The analyses of the vibration layer: nonlinear modes by the extended periodic motion
// concept (EPMC; Krack, Comput. Struct. 154 (2015) 59-71), forced response curves by
// harmonic balance and arclength continuation in frequency, and the quasi-static modal
// estimate from a static push along a linear mode and Masing's rules (Festjens et al.,
// J. Sound Vib. 333 (2014); Lacayo & Allen, MSSP 118 (2019)).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/vibration/continuation.hpp"
#include "asperity/vibration/harmonic_balance.hpp"
#include "asperity/vibration/stability.hpp"

namespace asperity::vibration {

struct NonlinearModeOptions {
  int mode = 1;  ///< 1-based, of the structure with the elements stuck
  double log10_amplitude_from = -6.0;
  double log10_amplitude_to = -3.0;
  /// Steps in decades of amplitude (the other unknowns scaled by the linear mode).
  ContinuationOptions continuation{.step = 0.05, .min_step = 1e-6, .max_step = 0.1};
  void validate() const;
};

/// One branch of a nonlinear mode. Per point: modal amplitude a (of the mass-normalized
/// first harmonic: U = a Psi, Psi_1c^T M Psi_1c + Psi_1s^T M Psi_1s = 1), omega, the
/// extra damping xi that makes the motion periodic, zeta = xi / (2 omega).
struct NonlinearModeResult {
  Eigen::VectorXd log10_amplitude;
  Eigen::VectorXd amplitude;
  Eigen::VectorXd omega;  ///< [rad/s]
  Eigen::VectorXd frequency_hz;
  Eigen::VectorXd xi;  ///< [1/s]
  Eigen::VectorXd damping_ratio;
  Eigen::MatrixXd output_amplitude;        ///< points x outputs: first-harmonic amplitude [m]
  std::vector<Eigen::VectorXd> harmonics;  ///< U = a Psi per point
  double linear_omega = 0.0;               ///< of the stuck structure [rad/s]
  double linear_damping_ratio = 0.0;
  ContinuationResult continuation;  ///< raw points [Psi, omega, xi, log10 a]
  std::vector<std::string> warnings;
};

[[nodiscard]] NonlinearModeResult nonlinear_mode(const HarmonicBalance& hb,
                                                 const NonlinearModeOptions& options,
                                                 const std::vector<Eigen::Index>& output_dofs,
                                                 const ProgressFunction& progress = {});

struct FrequencyResponseOptions {
  /// Excitation coefficients in the unknowns' layout (see HarmonicBalance::index), at
  /// force_scale = 1: F_ex(omega) = force + omega force_per_omega + omega^2
  /// force_per_omega2. The last two (optional, empty = zero) express base excitation:
  /// a base motion y = Y sin(omega t) through a spring k and a damper c gives
  /// k Y sin + omega c Y cos, so force_sin = k Y and force_per_omega (cos) = c Y.
  Eigen::VectorXd force;
  Eigen::VectorXd force_per_omega;
  Eigen::VectorXd force_per_omega2;
  std::vector<double> force_scales{1.0};
  double omega_from = 0.0;  ///< [rad/s] > 0
  double omega_to = 0.0;    ///< [rad/s] > 0, != omega_from
  /// Steps in units of the frequency range (amplitudes scaled by the stuck linear response).
  ContinuationOptions continuation{.step = 0.01, .min_step = 1e-7, .max_step = 0.05};
  /// Hill's stability of every point (stability.hpp); off by default (its cost).
  bool stability = false;
  HillOptions hill;
  void validate(Eigen::Index unknowns) const;
};

/// A resonance peak of one output: a local maximum of its first-harmonic amplitude |X|
/// along the curve (d|X|/ds = 0, so d|X|/d omega = 0 where the curve is not at a fold),
/// located between the computed points to the solver tolerance.
struct ResponsePeak {
  std::size_t output = 0;  ///< index into output_dofs
  double omega = 0.0;      ///< [rad/s]
  double amplitude = 0.0;  ///< [m]
  Eigen::VectorXd harmonics;
};

/// A turning point (fold) of the curve: a local extremum of omega along it
/// (d omega/ds = 0), located to the solver tolerance.
struct ResponseFold {
  double omega = 0.0;                ///< [rad/s]
  Eigen::VectorXd output_amplitude;  ///< first harmonic of each output [m]
  Eigen::VectorXd harmonics;
};

struct FrequencyResponseCurve {
  double force_scale = 1.0;
  Eigen::VectorXd omega;                            ///< [rad/s]
  std::vector<Eigen::MatrixXd> harmonic_amplitude;  ///< per output: points x harmonics kept [m]
  Eigen::MatrixXd output_amplitude;                 ///< points x outputs: first harmonic [m]
  Eigen::MatrixXd max_displacement;                 ///< points x outputs: max_t |x(t)| [m]
  std::vector<Eigen::VectorXd> harmonics;           ///< U per point
  std::vector<ResponsePeak> peaks;                  ///< in order along the curve, per output
  std::vector<ResponseFold> folds;                  ///< in order along the curve
  std::vector<PeriodicStability> stability;         ///< per point when options.stability
  ContinuationResult continuation;
  std::vector<std::string> warnings;
};

[[nodiscard]] std::vector<FrequencyResponseCurve> frequency_response(
    const HarmonicBalance& hb, const FrequencyResponseOptions& options,
    const std::vector<Eigen::Index>& output_dofs, const ProgressFunction& progress = {});

struct QuasiStaticModeOptions {
  int mode = 1;
  double amplitude_from = 1e-7;  ///< modal amplitude a [sqrt(kg) m], > 0
  double amplitude_to = 1e-4;    ///< > amplitude_from
  std::size_t points = 60;       ///< log-spaced, >= 2
  NewtonOptions newton;
  void validate() const;
};

/// omega(a) and zeta(a) from the modal backbone lambda(q) of a static push x(q) with
/// phi^T M x = q: omega^2 = lambda(a)/a (secant), the energy per cycle from Masing's
/// rules on lambda(q), D = 8 int_0^a lambda dq - 4 a lambda(a), zeta = D / (2 pi a^2
/// omega^2) plus the viscous modal damping phi^T C phi / (2 omega). The push follows the
/// stuck mode shape: where the joints slip and the shape changes (several DOFs), the
/// estimate drifts from the nonlinear mode (docs/vibration.md).
struct QuasiStaticModeResult {
  Eigen::VectorXd amplitude;
  Eigen::VectorXd omega;
  Eigen::VectorXd frequency_hz;
  Eigen::VectorXd damping_ratio;
  Eigen::VectorXd modal_force;  ///< lambda(a)
  Eigen::VectorXd dissipation;  ///< D(a) [J]
  double linear_omega = 0.0;
  std::size_t newton_iterations = 0;
  std::vector<std::string> warnings;
};

[[nodiscard]] QuasiStaticModeResult quasi_static_mode(const HarmonicBalance& hb,
                                                      const QuasiStaticModeOptions& options);

}  // namespace asperity::vibration
