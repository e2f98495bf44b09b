#pragma once
// Harmonic balance with alternating frequency-time (AFT) for a structure with joint
// elements (Cameron & Griffin 1989; Krack & Gross, "Harmonic Balance for Nonlinear
// Vibration Problems", Springer 2019, ch. 2-3).
//
// Motion x(t) = X_0 + sum_h [X_{c,h} cos(h omega t) + X_{s,h} sin(h omega t)] over the
// harmonics kept (any subset of 0..H that holds 1). The coefficient vector of one DOF is
// [a_0, a_{h1}, b_{h1}, a_{h2}, b_{h2}, ...] (a_0 only when 0 is kept); the unknown
// vector U stacks these per DOF: U[dof * n_c + c] (n_c coefficients per DOF).
//
// Residual R(U, omega) = A(omega) U + F_nl(U, omega) - F_ex, with the dynamic stiffness
// A(omega) = K (x) I + omega C (x) D + omega^2 M (x) D^2 (D: d/d(omega t) on the
// coefficients) and F_nl the coefficients of sum_e T_e^T f_e(T_e x(t)) from N_t samples
// per period: synthesis of u = T x on the samples, the element's periodic response,
// projection (KISS FFT). The Jacobian is analytic: the element's local tangent enters
// through the Fourier coefficients of the tangent signal (product-to-sum identities, one
// FFT per tangent signal), the history terms (dependence on reversal points) through
// the columns they touch.
#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "asperity/vibration/elements.hpp"
#include "asperity/vibration/structure.hpp"

namespace asperity::vibration {

struct HarmonicBalanceOptions {
  std::vector<int> harmonics{0, 1, 2, 3};  ///< distinct, ascending, >= 0, holds 1
  std::size_t time_points = 256;           ///< N_t: even, >= 2 H + 2, <= 2^20
  void validate() const;
};

/// Synthesis and projection on N_t samples of one period, theta_i = 2 pi i / N_t.
class HarmonicBasis {
 public:
  explicit HarmonicBasis(const HarmonicBalanceOptions& options);
  [[nodiscard]] const std::vector<int>& harmonics() const { return harmonics_; }
  /// Number of coefficients per DOF: (1 if 0 kept) + 2 * (harmonics >= 1).
  [[nodiscard]] std::size_t coefficients() const { return n_c_; }
  [[nodiscard]] std::size_t time_points() const { return n_t_; }
  [[nodiscard]] int max_harmonic() const { return harmonics_.back(); }
  /// Harmonic and kind (0 cosine, 1 sine) of coefficient c.
  [[nodiscard]] int harmonic_of(std::size_t c) const { return harm_[c]; }
  [[nodiscard]] int kind_of(std::size_t c) const { return kind_[c]; }
  /// Index of the cosine (kind 0) or sine (kind 1) coefficient of harmonic h; -1 if not kept.
  [[nodiscard]] long index_of(int h, int kind) const;
  /// E (N_t x n_c): E(i, c) = cos or sin of h theta_i.
  [[nodiscard]] const Eigen::MatrixXd& synthesis() const { return E_; }
  /// P (n_c x N_t): coefficients from samples, P E = I.
  [[nodiscard]] const Eigen::MatrixXd& projection() const { return P_; }
  /// D (n_c x n_c): coefficients of d/dtheta.
  [[nodiscard]] const Eigen::MatrixXd& derivative() const { return D_; }
  /// Coefficients of the samples s (length N_t): out = P s. By KISS FFT when many
  /// harmonics are kept; by direct sums over the samples (precomputed cosines and sines)
  /// when the 2 H + 1 frequencies needed are fewer than about 2 log2(N_t) + 4, where a
  /// full transform costs more (H = 3, N_t = 1024: 3 times faster).
  void project(const double* s, double* out) const;
  /// P diag(s) E (n_c x n_c) from the Fourier coefficients of s up to 2 H (product-to-sum
  /// identities), the coefficients as in project().
  void project_diagonal(const double* s, Eigen::Ref<Eigen::MatrixXd> out) const;
  /// True when the transforms use KISS FFT (false: direct sums).
  [[nodiscard]] bool uses_fft() const { return use_fft_; }

 private:
  std::vector<int> harmonics_;
  std::vector<int> harm_;
  std::vector<int> kind_;
  std::size_t n_c_ = 0;
  std::size_t n_t_ = 0;
  Eigen::MatrixXd E_;
  Eigen::MatrixXd P_;
  Eigen::MatrixXd D_;
  struct Fft;
  std::shared_ptr<const Fft> fft_;
  bool use_fft_ = true;
  Eigen::MatrixXd trig_;  // N_t x (2 (2H + 1)): cos(m theta_i), then sin(m theta_i), m = 0..2H
};

/// Counters of the work done (for the summary's `solver`).
struct WorkCounters {
  std::size_t residual_evaluations = 0;
  std::size_t jacobian_evaluations = 0;
};

/// The harmonic-balance system of a structure with elements. Thread-compatible: const
/// evaluation uses internal scratch space, so use one object per thread.
class HarmonicBalance {
 public:
  HarmonicBalance(Structure structure, std::vector<PlacedElement> elements,
                  const HarmonicBalanceOptions& options);

  [[nodiscard]] const Structure& structure() const { return s_; }
  [[nodiscard]] const std::vector<PlacedElement>& elements() const { return elements_; }
  [[nodiscard]] const HarmonicBasis& basis() const { return basis_; }
  [[nodiscard]] Eigen::Index dofs() const { return s_.dofs(); }
  /// n_c * dofs.
  [[nodiscard]] Eigen::Index unknowns() const { return unknowns_; }
  /// Index of coefficient c of DOF `dof` in U.
  [[nodiscard]] Eigen::Index index(Eigen::Index dof, std::size_t c) const {
    return dof * static_cast<Eigen::Index>(basis_.coefficients()) + static_cast<Eigen::Index>(c);
  }

  /// A(omega) U with the damping matrix C_eff (C, or C - xi M for EPMC).
  [[nodiscard]] Eigen::MatrixXd dynamic_stiffness(double omega, const Eigen::MatrixXd& C_eff) const;
  /// d A / d omega.
  [[nodiscard]] Eigen::MatrixXd dynamic_stiffness_derivative(double omega,
                                                             const Eigen::MatrixXd& C_eff) const;

  /// Coefficients of the elements' forces on the structure for motion U at omega; with
  /// dF_dU and dF_domega when given (non-null).
  void nonlinear_force(const Eigen::VectorXd& U, double omega, Eigen::VectorXd& F,
                       Eigen::MatrixXd* dF_dU, Eigen::VectorXd* dF_domega) const;

  /// R = A(omega) U + F_nl(U, omega) - F_ex, with dR/dU and dR/domega when given.
  void residual(const Eigen::VectorXd& U, double omega, const Eigen::VectorXd& F_ex,
                Eigen::VectorXd& R, Eigen::MatrixXd* dR_dU, Eigen::VectorXd* dR_domega) const;

  /// Displacement samples x(t_i) of DOF `dof` over one period (N_t samples), or, with
  /// `samples` > 0, on that many equally spaced points.
  [[nodiscard]] Eigen::VectorXd time_history(const Eigen::VectorXd& U, Eigen::Index dof,
                                             std::size_t samples = 0) const;
  /// Amplitude sqrt(a_h^2 + b_h^2) of harmonic h of DOF `dof` (|a_0| for h = 0).
  [[nodiscard]] double harmonic_amplitude(const Eigen::VectorXd& U, Eigen::Index dof, int h) const;
  /// max_t |x_dof(t)| over a fine grid (at least 8 points per period of the highest
  /// harmonic, and N_t).
  [[nodiscard]] double max_displacement(const Eigen::VectorXd& U, Eigen::Index dof) const;

  /// Stiffness of the structure with every element stuck (its initial stiffness).
  [[nodiscard]] Eigen::MatrixXd stuck_stiffness() const;

  [[nodiscard]] WorkCounters& counters() const { return counters_; }

 private:
  Structure s_;
  std::vector<PlacedElement> elements_;
  HarmonicBasis basis_;
  Eigen::Index unknowns_ = 0;
  mutable WorkCounters counters_;
};

}  // namespace asperity::vibration
