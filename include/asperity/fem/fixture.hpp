#pragma once
// A finite-element joint in the thesis's fretting apparatus (section 5.2, Fig. 5.1 and 5.7):
// one end of the joint held by the load cell, the other driven along the friction direction
// by the piezo actuator through the apparatus's compliance, condensed exactly onto the
// coordinates a quasi-static fretting cycle needs (beyond the thesis).
//
// Grips: the nodes of a body's boundary faces lying in a plane. The held grip's nodes do not
// move (a rigid, stiff load cell: section 5.2 chose it "relatively stiff" and Fig. 5.7 puts
// the apparatus's compliance on the PZT side). The driven grip's nodes move together along
// `direction` by z, their other components held (the clamp guides the joint end); a spring
// `drive_stiffness` joins z to the actuator's tip (Fig. 5.7: the PZT side's 38 N/um). The
// measured joint displacement delta (the laser sensor on the driven end, section 5.2) is z;
// the measured friction force (the load cell) is the spring's force k (Delta - z).
//
// Coordinates x = [g; z; e]: g the interface elements' relative displacements (3 per
// element, local frame t1, t2, n, as the Craig-Bampton model), z, and e the bolts' shank
// elongations. K is the static condensation of the structure (bodies, bolts, the drive
// spring) onto them: the flexibility C^T K_D^-1 C over the unit loads conjugate to x (the
// patch traction pairs, a force on z, a tension pair on each shank), inverted. It is exact
// for any static load on those coordinates, which are all the loads of a quasi-static cycle
// (the interface tractions, the drive, the bolt pretensions). The bolts are pre-tension
// sections as in the Craig-Bampton model: rough_prestress removes their axial stiffness
// (exactly, since e is a coordinate) and loads them with their preloads.
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "asperity/fem/bolt.hpp"
#include "asperity/fem/interface.hpp"
#include "asperity/fem/mesh.hpp"
#include "asperity/fem/reduced_model.hpp"

namespace asperity::fem {

/// The nodes of a body's boundary faces whose nodes all lie in the plane through `point`
/// normal to `normal` (within 1e-6 of the mesh's extent).
struct Grip {
  std::string body;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< [m]
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< any length > 0
};

struct Fixture {
  Grip held;    ///< every DOF of its nodes held (the load cell)
  Grip driven;  ///< its nodes move by z along `direction`, other components held
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< friction direction, any length > 0
  double drive_stiffness = 0.0;  ///< spring from the actuator's tip to z [N/m], > 0
  void validate() const;
};

struct GrippedJoint {
  /// x = [g (3 per interface element); z; e (one per bolt)]. M is the identity (a
  /// quasi-static model has no inertia; kept so the model is valid for the solvers); Q
  /// selects g, T = diag(area) maps element tractions to the forces on g, as in
  /// `asperity structure`'s models. No recovery rows.
  ReducedModel model;
  Eigen::Index drive_dof = 0;    ///< index of z in x
  double drive_stiffness = 0.0;  ///< [N/m], included in K(z, z)
  std::size_t held_nodes = 0, driven_nodes = 0;
  Eigen::Index full_dofs = 0;  ///< DOFs of the mesh
};

/// Condenses the structure (mesh, its stiffness K with the bolts' shanks, interfaces,
/// bolts) in the fixture. Throws InvalidInput naming the grip when its body is unknown, no
/// face of the body lies in its plane, or the two grips share a node; NumericalError when
/// the held structure cannot be factorised (a body not held: a grip missing).
[[nodiscard]] GrippedJoint condense_gripped(const Mesh& mesh, const Eigen::SparseMatrix<double>& K,
                                            const std::vector<Interface>& interfaces,
                                            const std::vector<Bolt>& bolts, const Fixture& fixture);

/// The nodes of a grip (sorted, distinct). Throws InvalidInput as condense_gripped.
[[nodiscard]] std::vector<std::int32_t> grip_nodes(const Mesh& mesh,
                                                   const std::vector<BoundaryFace>& faces,
                                                   const Grip& grip, const std::string& what);

}  // namespace asperity::fem
