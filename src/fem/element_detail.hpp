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

[[nodiscard]] Eigen::VectorXd tet10_shape_functions(const Eigen::Vector3d& xi);
[[nodiscard]] Eigen::MatrixX3d tet10_shape_derivatives(const Eigen::Vector3d& xi);
[[nodiscard]] Eigen::Matrix3Xd tet10_natural_nodes();
[[nodiscard]] bool tet10_straight_sided(const Eigen::Matrix3Xd& x);

[[nodiscard]] Eigen::VectorXd hex20_shape_functions(const Eigen::Vector3d& xi);
[[nodiscard]] Eigen::MatrixX3d hex20_shape_derivatives(const Eigen::Vector3d& xi);
[[nodiscard]] Eigen::Matrix3Xd hex20_natural_nodes();

}  // namespace asperity::fem::detail
