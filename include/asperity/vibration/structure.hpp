#pragma once
// A linear structure M x'' + C x' + K x = f(t) (SI: kg, N*s/m, N/m, any consistent
// set), dense, of any size; read from MatrixMarket files (coordinate or array format,
// general or symmetric) or given inline. The vibration layer adds joint elements to it.
#include <string>

#include <Eigen/Dense>

namespace asperity::vibration {

/// Rayleigh damping C = alpha M + beta K.
struct RayleighDamping {
  double alpha = 0.0;  ///< [1/s], >= 0
  double beta = 0.0;   ///< [s], >= 0
  void validate() const;
};

/// Mass, stiffness and damping matrices of n degrees of freedom.
struct Structure {
  Eigen::MatrixXd M;  ///< symmetric positive definite
  Eigen::MatrixXd K;  ///< symmetric positive semi-definite (the elements may add stiffness)
  Eigen::MatrixXd C;  ///< square, finite, entries any sign; empty means zero

  [[nodiscard]] Eigen::Index dofs() const { return M.rows(); }
  /// Throws InvalidInput naming the matrix and what is wrong: sizes that differ, a
  /// non-finite entry, M or K not symmetric (relative tolerance 1e-10 of the largest
  /// entry), M not positive definite (a Cholesky factorisation fails: singular mass).
  /// An empty C becomes the zero matrix.
  void validate();
};

/// C = alpha M + beta K.
[[nodiscard]] Eigen::MatrixXd rayleigh(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K,
                                       const RayleighDamping& d);

/// Reads a MatrixMarket file (`%%MatrixMarket matrix coordinate|array real|integer
/// general|symmetric`); throws InvalidInput naming the file and line on anything else.
/// Files larger than 1 GiB or matrices with more than 2^31 entries are refused.
[[nodiscard]] Eigen::MatrixXd read_matrix_market(const std::string& path);

/// Linear modes of (K, M): omega^2 ascending, shapes mass-normalized (phi^T M phi = 1),
/// each shape's largest-magnitude entry positive.
struct LinearModes {
  Eigen::VectorXd omega;   ///< [rad/s] (0 for a negative eigenvalue)
  Eigen::MatrixXd shapes;  ///< columns
  /// The eigenvalues omega^2 [(rad/s)^2] with their sign: negative when K is indefinite.
  Eigen::VectorXd eigenvalues;
};
[[nodiscard]] LinearModes linear_modes(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M);

}  // namespace asperity::vibration
