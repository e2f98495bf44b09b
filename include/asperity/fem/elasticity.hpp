#pragma once
// Linear elasticity with quadratic solid elements (Zienkiewicz & Taylor, The Finite
// Element Method, vol. 1, 7th ed., ch. 6 and 9): isoparametric tet10 and hex20
// (serendipity), 3 DOFs per node (dof = 3 * node + component), stiffness
// K_e = int B^T D B dV and consistent mass M_e = int rho N^T N dV.
//
// Quadrature (the element's natural coordinates, see shape_functions()):
//   tet10 stiffness, straight-sided (each mid-edge node at its edge's midpoint to 1e-10 of
//     the edge length): the 4-point rule of degree 2, exact for B^T D B (degree 2);
//   tet10 stiffness, curved, and tet10 mass (N_i N_j has degree 4): the collapsed
//     (Duffy, conical-product) 4 x 4 x 4 Gauss-Legendre rule, exact to degree 5;
//   hex20 stiffness and mass: 3 x 3 x 3 Gauss-Legendre (exact to degree 5 per direction).
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "asperity/fem/mesh.hpp"

namespace asperity::fem {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// Isotropic linear-elastic material of one body (SI).
struct IsotropicMaterial {
  double E = 0.0;    ///< Young's modulus [Pa], > 0
  double nu = 0.0;   ///< Poisson's ratio [-], in (-1, 0.5)
  double rho = 0.0;  ///< density [kg/m^3], > 0
  void validate() const;
};

/// The 6 x 6 matrix D of Hooke's law, sigma = D epsilon, in Voigt order
/// (xx, yy, zz, yz, zx, xy) with engineering shear strains (gamma = 2 epsilon).
[[nodiscard]] Eigen::Matrix<double, 6, 6> elasticity_matrix(const IsotropicMaterial& material);

/// Quadrature points (columns, natural coordinates) and weights.
struct QuadratureRule {
  Eigen::Matrix3Xd points;
  Eigen::VectorXd weights;
  /// Polynomial degree integrated exactly (per direction for hex20).
  int degree = 0;
};

/// Natural coordinates: tet10 (r, s, t) in the unit tetrahedron r, s, t >= 0,
/// r + s + t <= 1 (volume coordinates L0 = 1 - r - s - t, L1 = r, L2 = s, L3 = t);
/// hex20 (xi, eta, zeta) in [-1, 1]^3. Columns in the canonical node order of mesh.hpp.
[[nodiscard]] Eigen::Matrix3Xd natural_node_coordinates(ElementType type);
/// N_i(xi), one entry per node in canonical order.
[[nodiscard]] Eigen::VectorXd shape_functions(ElementType type, const Eigen::Vector3d& xi);
/// dN_i/dxi_j, one row per node.
[[nodiscard]] Eigen::MatrixX3d shape_derivatives(ElementType type, const Eigen::Vector3d& xi);

/// The tet10 4-point rule of degree 2.
[[nodiscard]] const QuadratureRule& tet_rule_degree2();
/// The collapsed 4 x 4 x 4 Gauss rule on the unit tetrahedron (64 points, degree 5).
[[nodiscard]] const QuadratureRule& tet_rule_degree5();
/// 3 x 3 x 3 Gauss-Legendre on [-1, 1]^3.
[[nodiscard]] const QuadratureRule& hex_rule_gauss3();
/// True unless a tet10's mid-edge node is off its edge's midpoint by more than 1e-10 of
/// the edge length (always false for hex20: its stiffness rule does not depend on it).
[[nodiscard]] bool is_straight_sided(ElementType type, const Eigen::Matrix3Xd& x);
/// The rule element_stiffness() uses for an element with nodes `x` (3 x nodes).
[[nodiscard]] const QuadratureRule& stiffness_rule(ElementType type, const Eigen::Matrix3Xd& x);
/// The rule element_mass() uses.
[[nodiscard]] const QuadratureRule& mass_rule(ElementType type);

/// The nodes of element `e` of `block` as columns (3 x nodes).
[[nodiscard]] Eigen::Matrix3Xd element_coordinates(const Mesh& mesh, const ElementBlock& block,
                                                   std::size_t e);
/// Throws InvalidInput "is degenerate: volume V below 1e-12 of the cube of its largest
/// extent (B)" (its bounding box's volume, made robust for a box of zero thickness) or
/// "is inverted: Jacobian determinant d at quadrature point q" (of stiffness_rule()); the
/// caller prefixes the element's name.
void check_element_geometry(ElementType type, const Eigen::Matrix3Xd& x);
/// Volume [m^3] (integral of det J with the mass rule).
[[nodiscard]] double element_volume(ElementType type, const Eigen::Matrix3Xd& x);
/// Element stiffness (3 n x 3 n, dof 3 a + i for node a, component i), exactly symmetric.
/// Throws InvalidInput if det J <= 0 at a quadrature point.
[[nodiscard]] Eigen::MatrixXd element_stiffness(ElementType type, const Eigen::Matrix3Xd& x,
                                                const IsotropicMaterial& material);
/// Element consistent mass (3 n x 3 n), exactly symmetric.
[[nodiscard]] Eigen::MatrixXd element_mass(ElementType type, const Eigen::Matrix3Xd& x, double rho);

/// Global stiffness and mass (3 * node_count() square, compressed column-major, both
/// triangles stored, exactly symmetric). `per_body[b]` is the material of mesh.bodies[b].
struct StiffnessAndMass {
  SparseMatrix K;  ///< [N/m]
  SparseMatrix M;  ///< [kg]
};
/// Both matrices; element matrices computed in parallel (core::parallel_for). Throws
/// InvalidInput naming the element (block type, 0-based index, body) for an inverted
/// one, or a material or a count of materials that does not fit.
[[nodiscard]] StiffnessAndMass assemble(const Mesh& mesh,
                                        std::span<const IsotropicMaterial> per_body);
[[nodiscard]] SparseMatrix assemble_stiffness(const Mesh& mesh,
                                              std::span<const IsotropicMaterial> per_body);
[[nodiscard]] SparseMatrix assemble_mass(const Mesh& mesh,
                                         std::span<const IsotropicMaterial> per_body);

/// One face of one element: `face` in the element's local numbering (element_faces()).
struct ElementFace {
  std::int32_t block = 0;
  std::int32_t element = 0;
  std::int32_t face = 0;
};
/// The local faces of an element type, each as its node indices (canonical order of
/// mesh.hpp), corners first, then mid-edge nodes, oriented with the outward normal by
/// the right-hand rule on the corners. tet10: 4 faces of 6 nodes, face k opposite corner
/// 3, 2, 0, 1 for k = 0, 1, 2, 3 (t = 0, s = 0, L0 = 0, r = 0); hex20: 6 faces of 8 nodes,
/// zeta = -1, zeta = +1, eta = -1, xi = +1, eta = +1, xi = -1.
[[nodiscard]] const std::vector<std::vector<int>>& element_faces(ElementType type);
/// The element faces whose nodes all belong to `nodes` (a node set), in block and
/// element order.
[[nodiscard]] std::vector<ElementFace> faces_on_nodes(const Mesh& mesh,
                                                      std::span<const std::int32_t> nodes);
/// Area [m^2] of the faces (the element's own shape functions on the face, the face
/// rule: collapsed 4 x 4 Gauss on triangles, degree 5; 4 x 4 Gauss on quadrilaterals).
[[nodiscard]] double faces_area(const Mesh& mesh, std::span<const ElementFace> faces);
/// Consistent nodal forces [N] (3 * node_count(), dof 3 node + component) of a uniform
/// traction `traction` [Pa] (global axes) on the faces: f_(3a+i) = int_faces N_a t_i dA.
/// Throws InvalidInput for a face that does not exist.
[[nodiscard]] Eigen::VectorXd traction_load(const Mesh& mesh, std::span<const ElementFace> faces,
                                            const Eigen::Vector3d& traction);

/// Volume [m^3] of each body (index as mesh.bodies).
[[nodiscard]] std::vector<double> body_volumes(const Mesh& mesh);
/// Mass [kg] of each body.
[[nodiscard]] std::vector<double> body_masses(const Mesh& mesh,
                                              std::span<const IsotropicMaterial> per_body);

}  // namespace asperity::fem
