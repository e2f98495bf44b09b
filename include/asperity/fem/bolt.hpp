#pragma once
// Bolts of a finite-element structure: a beam shank (Euler-Bernoulli, 12 DOFs) whose two
// ends are distributing couplings (RBE3, Abaqus *DISTRIBUTING COUPLING) over the washer
// footprints of the head side and the nut side. Why this form: it is what a structural
// engineer builds in Abaqus or ANSYS for a bolt whose shank does not touch its hole; it
// needs no mesh of the bolt, no contact between the head and the part, and carries the
// pretension as one axial force; the couplings spread the load over the annulus without
// stiffening it (an RBE2 would make the washer area rigid).
//
// Reference motion of a coupling over footprint nodes i with weights w_i (consistent
// nodal areas) and arms r_i from the weighted centre:
//   u_ref = sum w_i u_i / sum w_i,
//   theta_ref = S^-1 sum w_i r_i x (u_i - u_ref),  S = sum w_i (|r_i|^2 I - r_i r_i^T)
// (the least-squares rigid fit). Both are linear in the nodal DOFs: u_ref, theta_ref = G u.
// The shank adds K_b = G^T k_beam G. Pretension (Abaqus *PRE-TENSION SECTION, step 1):
// the shank's axial stiffness is replaced by the force P along its axis, so the tension is
// exactly P; afterwards the shank keeps its length and vibrates with its full stiffness.
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "asperity/fem/interface.hpp"
#include "asperity/fem/mesh.hpp"

namespace asperity::fem {

struct BoltSpec {
  std::string name;
  Eigen::Vector3d head =
      Eigen::Vector3d::Zero();                    ///< centre of the washer footprint, head side [m]
  Eigen::Vector3d nut = Eigen::Vector3d::Zero();  ///< centre of the washer footprint, nut side [m]
  double shank_diameter = 0.0;                    ///< [m]
  double hole_diameter = 0.0;                     ///< inner diameter of the footprint annulus [m]
  double washer_diameter = 0.0;                   ///< outer diameter of the footprint annulus [m]
  double E = 0.0;                                 ///< shank Young's modulus [Pa]
  double nu = 0.3;                                ///< shank Poisson's ratio
  double rho = 0.0;                               ///< shank density [kg/m^3]
  double head_mass = 0.0;  ///< head (or nut) and washer, lumped at each end [kg]
  double preload = 0.0;    ///< pretension P [N]
  void validate() const;
};

/// A bolt placed on the mesh.
struct Bolt {
  BoltSpec spec;
  double length = 0.0;   ///< |nut - head| [m]
  Eigen::Vector3d axis;  ///< (nut - head) / length
  std::vector<std::int32_t> head_nodes, nut_nodes;
  /// 12 x dofs: rows 0-2 u_ref, 3-5 theta_ref of the head end; 6-11 of the nut end.
  Eigen::SparseMatrix<double> coupling;
  /// Shank elongation e . (u_ref,nut - u_ref,head) as a row over the mesh DOFs.
  Eigen::SparseVector<double> elongation;
  double axial_stiffness = 0.0;  ///< E A / L [N/m]
  /// Shank stiffness and mass (12 x 12, global directions) at the coupling ends.
  Eigen::Matrix<double, 12, 12> beam_stiffness, beam_mass;
};

/// Finds each bolt's footprints (boundary-face nodes in the plane through head / nut
/// normal to the axis, at a radius between hole/2 and washer/2, within 1e-6 of the mesh
/// extent) and builds the couplings. Throws InvalidInput naming the bolt when a
/// footprint has no face (a bolt outside its bodies, or not on a surface) or its faces
/// cover less than half of the annulus area.
[[nodiscard]] Bolt place_bolt(const Mesh& mesh, const std::vector<BoundaryFace>& faces,
                              const BoltSpec& spec);

/// The shank's stiffness (with or without its axial part) and mass over the mesh DOFs.
[[nodiscard]] Eigen::SparseMatrix<double> bolt_stiffness(const Bolt& bolt, Eigen::Index dofs,
                                                         bool axial = true);
[[nodiscard]] Eigen::SparseMatrix<double> bolt_mass(const Bolt& bolt, Eigen::Index dofs);

}  // namespace asperity::fem
