#pragma once
// Hurty / Craig-Bampton reduction with the interface retained in relative coordinates
// (beyond the thesis).
//
// The retained (boundary) coordinates are the patch relative displacements g of every
// interface (3 per zero-thickness element, local frame t1, t2, n): the constraint C u = g
// (the patch averages of interface.hpp) is imposed with Lagrange multipliers, so the
// factorised stiffness keeps the mesh's sparsity. On a statically determinate 3-2-1 support,
// with X = K~^-1 C^T and the interface flexibility S = C X:
//   constraint modes  Psi = X S^-1: static response to each unit g with the rest of the
//                          structure free, then made mass-orthogonal to the rigid-body
//                          modes (which do not change g); Psi^T K Psi = S^-1,
//   fixed-interface modes Phi: the lowest modes of the structure with g = 0 (the tied
//                          structure; its rigid-body modes are among them), from the tied
//                          flexibility F_c f = K~^-1 f - Psi C K~^-1 f,
// and u = [Psi Phi] x, x = [g; eta]. K_r = B^T K B, M_r = B^T M B. Psi^T K Phi = 0.
// K~ = K + w C_s^T C_s on three spread-out patches per interface: equal to K on every u
// with C u = g up to a constant, it makes K~ on the support nonsingular when only the
// interface joins the bodies.
// Static loads inside the bodies (the bolt pretensions) add one load-dependent Ritz vector
// each (Wilson, Yuan and Dickens 1982): the static response of the tied structure to the
// load, mass-orthogonalised against the rigid-body and fixed-interface modes. With them
// the static response to those loads, and to any interface reaction, is in the basis
// exactly: the prestress of the reduced model equals that of the full one.
// A patch is like a pair of RBE3 couplings: the tied structure ties the patch averages,
// not each node (the motion of the nodes about the patch average is free).
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "asperity/fem/interface.hpp"

namespace asperity::fem {

struct ReductionOptions {
  int fixed_interface_modes = 40;  ///< elastic modes of the tied structure kept (>= 0)
  void validate() const;
};

/// Time of one phase of craig_bampton().
struct ReductionPhase {
  std::string name;
  double seconds = 0.0;      ///< wall time
  double cpu_seconds = 0.0;  ///< processor time of the process, all threads
};

/// The reduction basis and its products.
struct CraigBampton {
  Eigen::MatrixXd K, M;               ///< reduced, (3N + m) square; first 3N are the interface DOFs
  Eigen::Index interface_dofs = 0;    ///< 3N
  Eigen::Index rigid_body_modes = 0;  ///< rigid-body modes found among the tied structure's modes
  Eigen::VectorXd tied_omega2;        ///< eigenvalues of the kept tied-structure modes [rad^2/s^2]
  Eigen::Index static_vectors = 0;    ///< load-dependent Ritz vectors appended (last columns)
  /// u = basis * x (mesh DOFs x reduced coordinates).
  Eigen::MatrixXd basis;
  /// Costs: the phases in order, the nonzeros of the factor L D L^T (L and D), and the
  /// eigensolver's operator applications (each one forward and backward solve).
  std::vector<ReductionPhase> phases;
  Eigen::Index factor_nonzeros = 0;
  Eigen::Index eigensolver_operations = 0;
  /// Physical displacement (mesh DOFs) of reduced coordinates x.
  [[nodiscard]] Eigen::VectorXd expand(const Eigen::VectorXd& x) const { return basis * x; }
  /// Reduced row of a row over the mesh DOFs (a recovery or elongation row).
  [[nodiscard]] Eigen::RowVectorXd reduce_row(const Eigen::SparseVector<double>& row) const;
};

/// Reduces (K, M) (mesh DOFs, free-free, symmetric) with the interfaces' patches as the
/// boundary. Throws InvalidInput when the patches' averages are not independent (too many
/// patches for the mesh) or the structure has more rigid-body modes than a free-free one (6), and
/// NumericalError when a factorisation or the eigensolver fails.
[[nodiscard]] CraigBampton craig_bampton(const Eigen::SparseMatrix<double>& K,
                                         const Eigen::SparseMatrix<double>& M,
                                         const Eigen::Matrix3Xd& nodes,
                                         const std::vector<Interface>& interfaces,
                                         const ReductionOptions& options,
                                         const std::vector<Eigen::VectorXd>& static_loads = {});

/// Rigid-body modes of a node cloud (3 translations, 3 rotations about the centroid).
[[nodiscard]] Eigen::MatrixXd rigid_body_modes(const Eigen::Matrix3Xd& nodes);

}  // namespace asperity::fem
