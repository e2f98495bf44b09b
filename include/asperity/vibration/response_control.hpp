#pragma once
// Response-controlled harmonic balance: the force scale becomes an unknown and a
// constraint on the response of one DOF takes its place, as in response-controlled
// stepped-sine testing (Karaagacli & Ozguven, MSSP 146 (2021) 107023) and phase
// resonance testing (Peeters et al., MSSP 25 (2011) 1227-1247).
//
// Amplitude control: the first harmonic of DOF d held at |X_d| = A; continuation in omega
// gives the force scale lambda(omega) that keeps it there (single-valued where the
// force-controlled response folds). Phase control (phase resonance): the first harmonic
// of DOF d lags the excitation at d by 90 degrees, X_d = a (-sin theta_F, cos theta_F) in
// (cos, sin) coefficients with theta_F the phase of the force at d; continuation in
// log10 a gives omega(a) and lambda(a). For a single nonlinear mode with weak damping
// this traces the backbone (for the Duffing oscillator on one harmonic, exactly).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/vibration/continuation.hpp"
#include "asperity/vibration/harmonic_balance.hpp"

namespace asperity::vibration {

struct AmplitudeControlOptions {
  /// Excitation at lambda = 1 in the unknowns' layout (as FrequencyResponseOptions).
  Eigen::VectorXd force;
  Eigen::Index dof = 0;     ///< the controlled DOF
  double amplitude = 0.0;   ///< [m] > 0: its first-harmonic amplitude
  double omega_from = 0.0;  ///< [rad/s] > 0
  double omega_to = 0.0;    ///< [rad/s] > 0, != omega_from
  ContinuationOptions continuation{.step = 0.01, .min_step = 1e-7, .max_step = 0.05};
  void validate(const HarmonicBalance& hb) const;
};

struct AmplitudeControlResult {
  Eigen::VectorXd omega;             ///< [rad/s]
  Eigen::VectorXd force_scale;       ///< lambda per point
  Eigen::MatrixXd output_amplitude;  ///< points x outputs: first harmonic [m]
  std::vector<Eigen::VectorXd> harmonics;
  ContinuationResult continuation;
  std::vector<std::string> warnings;
};

[[nodiscard]] AmplitudeControlResult amplitude_controlled_response(
    const HarmonicBalance& hb, const AmplitudeControlOptions& options,
    const std::vector<Eigen::Index>& output_dofs, const ProgressFunction& progress = {});

struct PhaseResonanceOptions {
  /// Excitation at lambda = 1 in the unknowns' layout; its harmonic 1 at `dof` must not
  /// vanish (the phase reference).
  Eigen::VectorXd force;
  Eigen::Index dof = 0;  ///< the controlled DOF (a driving point)
  int mode = 1;          ///< the stuck structure's mode whose frequency starts the search
  double log10_amplitude_from = -3.0;  ///< log10 of a [m]
  double log10_amplitude_to = 0.0;
  /// Steps in decades of a (the other unknowns normalized by a).
  ContinuationOptions continuation{.step = 0.05, .min_step = 1e-6, .max_step = 0.1};
  void validate(const HarmonicBalance& hb) const;
};

struct PhaseResonanceResult {
  Eigen::VectorXd amplitude;    ///< a [m]: the first-harmonic amplitude of `dof`
  Eigen::VectorXd omega;        ///< [rad/s]
  Eigen::VectorXd force_scale;  ///< lambda per point
  Eigen::MatrixXd output_amplitude;
  std::vector<Eigen::VectorXd> harmonics;  ///< U per point
  ContinuationResult continuation;         ///< raw points [U / a, omega, lambda / a, log10 a]
  std::vector<std::string> warnings;
};

[[nodiscard]] PhaseResonanceResult phase_resonance(const HarmonicBalance& hb,
                                                   const PhaseResonanceOptions& options,
                                                   const std::vector<Eigen::Index>& output_dofs,
                                                   const ProgressFunction& progress = {});

/// Variable-phase resonance nonlinear modes (VPRNM; Porter & Brake, MSSP 215 (2024)
/// 111410): the superharmonic resonance of order r of a forced response, followed as the
/// force scale lambda grows. Harmonic r of the response is driven by the elements' force at
/// harmonic r from the response's lower harmonics alone, F_r = -[F_nl(U_{h<r})]_r; the
/// resonance is where the response's harmonic r is in quadrature with it:
///   F_r . X_r / (|F_r| |X_r|) = 0       (over all DOFs' cosine and sine coefficients),
/// a phase resonance of harmonic r as [[phase_resonance]] is of harmonic 1. Unknowns U,
/// omega; continuation in log10 lambda. A linear structure has no F_r: refused.
struct SuperharmonicResonanceOptions {
  /// Excitation at lambda = 1 in the unknowns' layout (as FrequencyResponseOptions).
  Eigen::VectorXd force;
  int harmonic = 3;  ///< r >= 2, kept in the harmonics (as is 1); the kept ones below r drive it
  int mode = 1;      ///< the stuck mode whose frequency / r starts the search
  double log10_force_from = -2.0;  ///< log10 lambda
  double log10_force_to = 0.0;
  ContinuationOptions continuation{.step = 0.05, .min_step = 1e-6, .max_step = 0.1};
  void validate(const HarmonicBalance& hb) const;
};

struct SuperharmonicResonanceResult {
  int harmonic = 3;
  Eigen::VectorXd force_scale;       ///< lambda per point
  Eigen::VectorXd omega;             ///< [rad/s], the excitation's frequency (r omega: the mode's)
  Eigen::MatrixXd output_amplitude;  ///< points x outputs: harmonic 1 [m]
  Eigen::MatrixXd output_harmonic_amplitude;  ///< points x outputs: harmonic r [m]
  std::vector<Eigen::VectorXd> harmonics;     ///< U per point
  ContinuationResult continuation;            ///< raw points [U / lambda, omega, log10 lambda]
  std::vector<std::string> warnings;
};

/// The VPRNM equations at y = [U / lambda, omega, log10 lambda] (unknowns + 2): R = [the
/// harmonic-balance residual / lambda; max|force| times the quadrature condition] and, when J
/// is given, dR/dy ((unknowns + 1) x (unknowns + 2)). What superharmonic_resonance continues.
void superharmonic_resonance_system(const HarmonicBalance& hb,
                                    const SuperharmonicResonanceOptions& options,
                                    const Eigen::VectorXd& y, Eigen::VectorXd& R,
                                    Eigen::MatrixXd* J);

[[nodiscard]] SuperharmonicResonanceResult superharmonic_resonance(
    const HarmonicBalance& hb, const SuperharmonicResonanceOptions& options,
    const std::vector<Eigen::Index>& output_dofs, const ProgressFunction& progress = {});

}  // namespace asperity::vibration
