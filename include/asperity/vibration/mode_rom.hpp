#pragma once
// A reduced-order model from one nonlinear mode (single nonlinear mode theory; Krack,
// Comput. Struct. 154 (2015) 59-71, Sec. 5): the forced response near the mode from its
// EPMC backbone omega(a), xi(a) and shape Psi(a), without solving the full system. With
// U = a Psi (mass-normalized first harmonic) and the modal force f(a) = psi^H F (psi, F the
// complex first harmonics, psi = Psi_c - i Psi_s, F = F_c - i F_s):
//   (omega(a)^2 - Omega^2 + i Omega xi(a)) a = f(a),
// so for each backbone point |f|^2 / a^2 = (omega^2 - Omega^2)^2 + (Omega xi)^2 gives
// Omega^2 = omega^2 - xi^2 / 2 -+ sqrt(|f|^2 / a^2 - xi^2 (omega^2 - xi^2 / 4)).
// Exact for a single DOF on one harmonic with amplitude-independent viscous damping;
// an approximation elsewhere (the damping and shape taken at the backbone frequency).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/vibration/analysis.hpp"
#include "asperity/vibration/harmonic_balance.hpp"

namespace asperity::vibration {

struct ModeRomCurve {
  Eigen::VectorXd omega;             ///< excitation frequency Omega [rad/s] per point
  Eigen::VectorXd amplitude;         ///< modal amplitude a per point
  Eigen::MatrixXd output_amplitude;  ///< points x outputs: first harmonic a |Psi_d| [m]
  /// Points on the low-frequency side (Omega below the backbone), in increasing a, then
  /// those of the high-frequency side in decreasing a: one curve over the resonance.
  std::size_t low_side_points = 0;
  double peak_amplitude = 0.0;  ///< the largest modal amplitude a reached (on the refined grid)
  std::vector<std::string> warnings;  ///< e.g. the force drives beyond the backbone's range
};

/// `force`: the excitation in the unknowns' layout (its first harmonic is used).
/// Between the backbone's points omega, xi and Psi are interpolated linearly in log a,
/// `subdivisions` points per interval, so that the peak is resolved. Throws
/// InvalidInput for a force without a first harmonic, a mode result without points or
/// of another system.
[[nodiscard]] ModeRomCurve nonlinear_mode_rom(const HarmonicBalance& hb,
                                              const NonlinearModeResult& mode,
                                              const Eigen::VectorXd& force,
                                              const std::vector<Eigen::Index>& output_dofs,
                                              int subdivisions = 16);

}  // namespace asperity::vibration
