#pragma once
// Stability of a periodic solution of harmonic balance by Hill's method (Hill 1886;
// von Groll & Ewins, J. Sound Vib. 241 (2001) 223-233; Lazarus & Thomas, C. R. Mecanique
// 338 (2010) 510-517; Krack & Gross, "Harmonic Balance for Nonlinear Vibration
// Problems", Springer 2019).
//
// A perturbation y(t) = exp(lambda t) p(t) of the periodic motion x*(t) of
// M x'' + C x' + K x + f_nl(x, x') = f_ex, with p periodic on the same harmonics,
// linearised about x*, gives on the coefficients of p the quadratic eigenvalue problem
//   (Delta_0 + lambda Delta_1 + lambda^2 Delta_2) P = 0,
//   Delta_0 = dR/dU (the harmonic-balance Jacobian at omega, AFT tangent included),
//   Delta_1 = C (x) I + 2 omega M (x) D + J_v,   Delta_2 = M (x) I,
// J_v the elements' velocity tangent P diag(df/dv) E. Its 2 n (2 H + 1) eigenvalues are
// the n-DOF system's 2 n Floquet exponents, each repeated at lambda + i k omega with
// its eigenvector shifted by -k harmonics; the copies near the truncation's edge are
// spoilt. The 2 n whose eigenvectors are centred nearest harmonic 0 (spectral centre
// sum_k k |p_k|^2 / sum_k |p_k|^2 over complex harmonics k = -H..H; the symmetric-
// eigenvector criterion, Bentvelsen & Lazarus, Nonlinear Dyn. (2018)) are taken, ties
// by the smallest |Im lambda| (Lazarus & Thomas 2010). The smallest-|Im| criterion alone
// picks spoilt edge copies when modes lie above H omega (a 10-DOF Jenkins chain at H = 3
// showed spurious Neimark-Sacker instabilities with it). Floquet multipliers are
// mu = exp(lambda 2 pi / omega); the solution is
// asymptotically stable when every chosen exponent has Re lambda < 0 (|mu| < 1).
//
// The linearisation of a hysteretic (non-smooth) element is the AFT Jacobian of the
// harmonic-balance map, history terms included: the perturbed path is taken to keep the
// reversal samples of the periodic one, and the history terms enter without their delay
// factor exp(-lambda (t_i - t_j)), exact at lambda = 0 (folds) only (docs/vibration.md).
#include <complex>
#include <cstddef>
#include <string>

#include <Eigen/Dense>

#include "asperity/vibration/harmonic_balance.hpp"

namespace asperity::vibration {

struct HillOptions {
  /// Exponents reported per point: those of largest real part (the most critical ones,
  /// which hold every unstable exponent first); the stability flag uses all 2 n.
  std::size_t reported_exponents = 6;  ///< [1, 1000]
  /// Stable when max Re lambda <= tolerance omega: round-off on an exponent near 0 does
  /// not read as unstable.
  double tolerance = 1e-8;  ///< (0, 1e-2]
  void validate() const;
};

/// Hill stability of one periodic solution.
struct PeriodicStability {
  bool stable = true;
  /// The reported Floquet exponents lambda [1/s] (complex; conjugate pairs both kept),
  /// largest real part first.
  Eigen::VectorXcd exponents;
  double max_real_exponent = 0.0;       ///< max Re lambda over the 2 n chosen [1/s]
  double max_multiplier_modulus = 0.0;  ///< max |mu| = exp(max Re lambda 2 pi / omega)
  /// How the leading exponent leaves the stable region, when unstable: "fold" (a real
  /// multiplier beyond +1: Im lambda = 0), "period_doubling" (beyond -1: Im lambda =
  /// omega / 2), "neimark_sacker" (a complex pair); "" when stable.
  std::string instability;
  /// The chosen exponent of smallest |lambda| [1/s]: it passes through 0 at a fold of the
  /// branch (Delta_0 singular).
  std::complex<double> smallest_exponent{0.0, 0.0};
};

/// Hill's method at the solution U (coefficients in hb's layout) of frequency omega, with
/// damping matrix C_eff (the structure's C for a forced response). When hb keeps a
/// subset of 0..H, the perturbation is expanded on all of 0..H (a perturbation of a
/// solution with odd harmonics only may hold even ones). Throws NumericalError when
/// the eigenvalue solver does not converge.
[[nodiscard]] PeriodicStability hill_stability(const HarmonicBalance& hb, const Eigen::VectorXd& U,
                                               double omega, const Eigen::MatrixXd& C_eff,
                                               const HillOptions& options = {});

}  // namespace asperity::vibration
