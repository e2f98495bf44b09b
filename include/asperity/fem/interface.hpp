#pragma once
// Contact interfaces of a finite-element mesh as zero-thickness elements (beyond the
// thesis: the thesis's rough flat is meant to be the contact law of each of them).
//
// Two bodies meet on faces whose nodes coincide. Each such pair of faces carries
// quadrature points; the relative displacement at a point is g = u_B - u_A (side B minus
// side A), resolved in the local frame (t1, t2, n) with n the outward normal of side A.
// An interface is reduced to N patches: each patch is one zero-thickness element whose
// relative displacement is the area-weighted mean of g over its faces,
//   g_p = (1/A_p) sum_q w_q sum_i N_i(q) (u_B,i - u_A,i),              (patch average)
// and whose traction t_p (Pa, local frame) acts back on the nodes as the forces
//   f = L_p^T (A_p t_p)                                                 (virtual work)
// so that the operator pair is consistent (power t_p . g_p A_p).
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "asperity/fem/mesh.hpp"

namespace asperity::fem {

/// A boundary face of a solid element: tri6 (of a tet10) or quad8 (of a hex20), nodes
/// ordered so that the right-hand normal points out of the element.
struct BoundaryFace {
  std::array<std::int32_t, 8> nodes{};
  int node_count = 6;  ///< 6 or 8
  std::int32_t body = 0;
  std::int32_t block = 0;
  std::int32_t element = 0;
};

/// Faces of the mesh that belong to exactly one element (its outer surface, including
/// the faces where two bodies touch once their nodes are split).
[[nodiscard]] std::vector<BoundaryFace> boundary_faces(const Mesh& mesh);

/// Gives every body its own copy of the nodes it shares with another body (a mesh made
/// conforming across bodies by gmsh shares them). Returns the number of nodes added.
std::size_t split_shared_nodes(Mesh& mesh);

/// Which faces form an interface.
struct InterfaceSpec {
  std::string name;
  std::string body_a;  ///< side A: the normal n points out of it
  std::string body_b;
  /// When non-zero, only the coincident faces whose outward normal of side A is within
  /// 1e-3 rad of this direction; otherwise all of them, which must then share one normal.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  int patches = 0;  ///< zero-thickness elements (patches) to reduce the interface to (>= 1)
  void validate() const;
};

/// One zero-thickness element: a patch of faces.
struct InterfacePatch {
  double area = 0.0;                ///< A_p [m^2]
  Eigen::Vector3d centroid;         ///< area-weighted [m]
  Eigen::Matrix3d frame;            ///< rows t1, t2, n (orthonormal)
  std::vector<std::int32_t> faces;  ///< indices into Interface::face_pairs
  /// The patch average as node weights: g_p = sum_k weight_k (u[node_b_k] - u[node_a_k]),
  /// weight_k = (1/A_p) sum_q w_q |J_q| N_k(q) (sum of weights = 1).
  struct NodeWeight {
    std::int32_t node_a = 0, node_b = 0;
    double weight = 0.0;
  };
  std::vector<NodeWeight> weights;
};

/// A pair of coincident faces, side A and side B, with their nodes matched:
/// side_b.nodes[i] sits where side_a.nodes[i] does.
struct FacePair {
  BoundaryFace side_a;
  BoundaryFace side_b;
};

/// An interface of the mesh, reduced to patches.
struct Interface {
  std::string name;
  std::int32_t body_a = 0, body_b = 0;
  std::vector<FacePair> face_pairs;
  std::vector<InterfacePatch> patches;
  double area = 0.0;  ///< total [m^2]

  /// Patch relative displacements in the global frame: rows 3p..3p+2 (x, y, z) of
  /// patch p, columns the mesh's DOFs (3 per node). Rigid motions give zero.
  [[nodiscard]] Eigen::SparseMatrix<double> global_operator(Eigen::Index dofs) const;
  /// The same in each patch's local frame: rows 3p (t1), 3p+1 (t2), 3p+2 (n).
  [[nodiscard]] Eigen::SparseMatrix<double> local_operator(Eigen::Index dofs) const;
  /// Nodal forces (global DOFs) of the patch tractions `traction` (3 per patch, local
  /// frame, Pa): local_operator^T diag(A_p) t.
  [[nodiscard]] Eigen::VectorXd nodal_forces(const Eigen::VectorXd& traction,
                                             Eigen::Index dofs) const;
};

/// Finds the coincident faces of spec.body_a and spec.body_b (nodes already split; their
/// corners matched to 1e-9 of the mesh's extent) and groups them into spec.patches
/// patches by area-weighted k-means of the face centroids (deterministic: farthest-point
/// seeding from the centroid). Throws InvalidInput naming the interface when a body is
/// unknown, the two surfaces do not touch, the faces do not share one normal (and no
/// `normal` is given), or there are fewer faces than patches.
[[nodiscard]] Interface build_interface(const Mesh& mesh, const std::vector<BoundaryFace>& faces,
                                        const InterfaceSpec& spec);

/// Shape functions of a tri6 / quad8 face at (xi, eta) (node_count values).
void face_shape(int node_count, double xi, double eta, double* N, double* dN_dxi, double* dN_deta);
/// Quadrature points of a face: (xi, eta, weight on the reference face).
[[nodiscard]] const std::vector<std::array<double, 3>>& face_quadrature(int node_count);
/// Calls point(N, w n) at each quadrature point of a face: N the shape function values,
/// w the quadrature weight and n = dx/dxi x dx/deta (|n| the area element; n points out
/// of the face's element). Summing w |n| gives the face's area.
void for_each_face_point(
    const Mesh& mesh, const BoundaryFace& face,
    const std::function<void(const double* N, const Eigen::Vector3d& wn)>& point);

}  // namespace asperity::fem
