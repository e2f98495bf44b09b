#pragma once
// Sparse generalized eigenproblems K phi = omega^2 M phi of assembled structures and
// Dirichlet (clamped) DOFs.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace asperity::fem {

using SparseMatrix = Eigen::SparseMatrix<double>;

struct SparseModes {
  Eigen::VectorXd omega2;  ///< [rad^2/s^2], ascending
  Eigen::MatrixXd shapes;  ///< one column per mode, phi^T M phi = 1, largest entry > 0
  /// The factorization of K - shift M used: "SimplicialLDLT" or "SparseLU".
  std::string factorization;
};

/// The sparse direct factorization of K - shift M in sparse_modes() (docs/structures.md,
/// "Sparse eigenvalues", for the measurements behind the default).
enum class SparseFactorization {
  /// Eigen's SimplicialLDLT (AMD ordering): least memory, and the faster one on tet10
  /// meshes (48.6k DOFs: 32 s CPU and 0.67 GB for 10 modes against SparseLU's 47 s and
  /// 1.6 GB). SparseLU takes over when LDLT reports a zero pivot or its solve of a test
  /// vector has a normwise backward error above 1e-10 (an indefinite matrix factorized
  /// without pivoting).
  simplicial_ldlt,
  /// Eigen's supernodal SparseLU (COLAMD ordering): any nonsingular K - shift M; 8x
  /// faster than SimplicialLDLT on hex20 meshes (36.7k DOFs: 5.8 s against 46 s CPU).
  sparse_lu,
};

/// The `count` eigenpairs of (K, M) nearest to `shift` [rad^2/s^2] (on either side: choose
/// it below the lowest one wanted to get the lowest ones, e.g. a negative value for a
/// free structure, whose rigid-body modes have omega^2 = 0) by Lanczos in shift-invert
/// mode (Spectra's SymGEigsShiftSolver) on (K - shift M)^-1 M. The Lanczos tolerance
/// (1e-12) is relative to the largest 1/(omega^2 - shift) of the modes found: for a free
/// structure take |shift| within a few decades of the lowest elastic omega^2 expected,
/// not far below it (shift -1 with elastic omega^2 ~ 1e10 leaves those 1e-10 of the
/// rigid-body modes' and resolves them poorly). K, M square of the same size, symmetric,
/// M positive definite; 1 <= count < size. Throws InvalidInput for sizes or counts that
/// do not fit, NumericalError (saying what was tried) when K - shift M is singular or the
/// iteration does not converge.
[[nodiscard]] SparseModes sparse_modes(
    const SparseMatrix& K, const SparseMatrix& M, int count, double shift,
    SparseFactorization factorization = SparseFactorization::simplicial_ldlt);

/// The DOFs (3 * node + component, each component) of `nodes`, ascending and unique.
[[nodiscard]] std::vector<std::int32_t> node_dofs(std::span<const std::int32_t> nodes);
/// The DOFs in [0, size) not in `removed`, ascending.
[[nodiscard]] std::vector<std::int32_t> complement_dofs(Eigen::Index size,
                                                        std::span<const std::int32_t> removed);
/// A[kept, kept] (kept ascending, unique, in range; InvalidInput otherwise).
[[nodiscard]] SparseMatrix restrict_dofs(const SparseMatrix& A, std::span<const std::int32_t> kept);
/// A with the rows and columns of `clamped` removed: the problem with zero displacement
/// at those DOFs (Dirichlet). The remaining DOFs are complement_dofs(A.rows(), clamped).
[[nodiscard]] SparseMatrix eliminate_dofs(const SparseMatrix& A,
                                          std::span<const std::int32_t> clamped);
/// Vectors (rows = kept.size()) expanded to `size` rows with zeros at the removed DOFs.
[[nodiscard]] Eigen::MatrixXd expand_dofs(const Eigen::MatrixXd& reduced,
                                          std::span<const std::int32_t> kept, Eigen::Index size);

}  // namespace asperity::fem
