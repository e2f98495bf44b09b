#pragma once
// Continuation in force amplitude: the forced response at a fixed frequency with the
// force scale lambda as the continuation parameter, R = A(omega) U + F_nl(U) - lambda
// F_ex(omega) = 0 (the analysis of a stepped-amplitude test at one frequency; Krack &
// Gross, Harmonic Balance for Nonlinear Vibration Problems, Springer 2019, ch. 4).
// Turning points in lambda (the jumps of a hardening or softening response when the
// force is raised or lowered) are located as in the frequency response.
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/vibration/continuation.hpp"
#include "asperity/vibration/harmonic_balance.hpp"

namespace asperity::vibration {

struct ForceResponseOptions {
  /// Excitation coefficients at lambda = 1 in the unknowns' layout, as in
  /// FrequencyResponseOptions: F_ex = force + omega force_per_omega + omega^2
  /// force_per_omega2 (the last two optional).
  Eigen::VectorXd force;
  Eigen::VectorXd force_per_omega;
  Eigen::VectorXd force_per_omega2;
  double omega = 0.0;       ///< [rad/s] > 0
  double scale_from = 0.0;  ///< lambda at the start, >= 0 (0: the structure at rest)
  double scale_to = 1.0;    ///< lambda at the end, >= 0, != scale_from
  /// Steps in units of the lambda range (amplitudes scaled by the stuck linear response).
  ContinuationOptions continuation{.step = 0.01, .min_step = 1e-7, .max_step = 0.05};
  void validate(Eigen::Index unknowns) const;
};

/// A turning point in lambda: a local extremum of the force scale along the curve.
struct ForceResponseFold {
  double force_scale = 0.0;
  Eigen::VectorXd output_amplitude;  ///< first harmonic of each output [m]
  Eigen::VectorXd harmonics;
};

struct ForceResponseCurve {
  double omega = 0.0;                               ///< [rad/s]
  Eigen::VectorXd force_scale;                      ///< lambda per point
  std::vector<Eigen::MatrixXd> harmonic_amplitude;  ///< per output: points x harmonics kept [m]
  Eigen::MatrixXd output_amplitude;                 ///< points x outputs: first harmonic [m]
  Eigen::MatrixXd max_displacement;                 ///< points x outputs: max_t |x(t)| [m]
  std::vector<Eigen::VectorXd> harmonics;           ///< U per point
  std::vector<ForceResponseFold> folds;             ///< in order along the curve
  ContinuationResult continuation;
  std::vector<std::string> warnings;
};

/// Throws InvalidInput for bad options, NumericalError when the first point cannot be
/// corrected; a stall later returns the points reached (continuation.complete = false).
[[nodiscard]] ForceResponseCurve force_response(const HarmonicBalance& hb,
                                                const ForceResponseOptions& options,
                                                const std::vector<Eigen::Index>& output_dofs,
                                                const ProgressFunction& progress = {});

}  // namespace asperity::vibration
