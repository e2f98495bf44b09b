#pragma once
// Hurty / Craig-Bampton reduction with the interface retained in relative coordinates
// (beyond the thesis).
//
// The retained (boundary) coordinates are the patch relative displacements g of every
// interface (3 per zero-thickness element, local frame t1, t2, n). The constraint L u = g
// (the patch averages of interface.hpp) is imposed exactly by eliminating one interior
// node of side B per patch (3 DOFs): u = T_c [v; g]. Then
//   constraint modes  Psi: static response to each unit g with the rest of the structure
//                          free (statically determinate 3-2-1 support, then made
//                          mass-orthogonal to the rigid-body modes, which do not change g),
//   fixed-interface modes Phi: the lowest modes of the structure with g = 0 (the tied
//                          structure; its rigid-body modes are among them),
// and x = [g; eta], u = T_c [Psi Phi] x. K_r = B^T K B, M_r = B^T M B. Psi^T K Phi = 0.
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
  /// u = elimination * basis * x (elimination sparse n x n_t, basis dense n_t x n_r).
  Eigen::SparseMatrix<double> elimination;
  Eigen::MatrixXd basis;
  /// Costs: the phases in order, the nonzeros of the factor L D L^T (L and D), and the
  /// eigensolver's operator applications (each one forward and backward solve).
  std::vector<ReductionPhase> phases;
  Eigen::Index factor_nonzeros = 0;
  Eigen::Index eigensolver_operations = 0;
  /// Physical displacement (mesh DOFs) of reduced coordinates x.
  [[nodiscard]] Eigen::VectorXd expand(const Eigen::VectorXd& x) const {
    return elimination * (basis * x);
  }
  /// Reduced row of a row over the mesh DOFs (a recovery or elongation row).
  [[nodiscard]] Eigen::RowVectorXd reduce_row(const Eigen::SparseVector<double>& row) const;
};

/// Reduces (K, M) (mesh DOFs, free-free, symmetric) with the interfaces' patches as the
/// boundary. Throws InvalidInput when a patch has no interior node (too many patches for
/// the mesh) or the structure has more rigid-body modes than a free-free one (6), and
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
