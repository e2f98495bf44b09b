#pragma once
// Per-type pieces of the elements (src/fem/tet10.cpp, hex20.cpp) behind the
// type-dispatching functions of elasticity.hpp.
#include <vector>

#include <Eigen/Dense>

namespace asperity::fem::detail {

struct Gauss1d {
  std::vector<double> x;  ///< on [-1, 1], ascending
  std::vector<double> w;
};
/// n-point Gauss-Legendre rule on [-1, 1] (Newton on P_n from the Chebyshev guesses;
/// exact to degree 2 n - 1).
[[nodiscard]] Gauss1d gauss_legendre(int n);

/// The corners of each mid-edge node of a tet10 (mesh.hpp: 4 (0-1), 5 (1-2), 6 (2-0),
/// 7 (0-3), 8 (1-3), 9 (2-3)).
inline constexpr int kTetEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

[[nodiscard]] Eigen::VectorXd tet10_shape_functions(const Eigen::Vector3d& xi);
[[nodiscard]] Eigen::MatrixX3d tet10_shape_derivatives(const Eigen::Vector3d& xi);
[[nodiscard]] Eigen::Matrix3Xd tet10_natural_nodes();
[[nodiscard]] bool tet10_straight_sided(const Eigen::Matrix3Xd& x);

[[nodiscard]] Eigen::VectorXd hex20_shape_functions(const Eigen::Vector3d& xi);
[[nodiscard]] Eigen::MatrixX3d hex20_shape_derivatives(const Eigen::Vector3d& xi);
[[nodiscard]] Eigen::Matrix3Xd hex20_natural_nodes();

}  // namespace asperity::fem::detail
