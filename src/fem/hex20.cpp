// The 20-node serendipity hexahedron (Zienkiewicz & Taylor vol. 1, 7th ed., sec. 6.5,
// Abaqus C3D20 node order) and its 3 x 3 x 3 Gauss rule.
#include "asperity/fem/elasticity.hpp"
#include "element_detail.hpp"

namespace asperity::fem {

namespace {

// Natural coordinates of the nodes in the canonical order of mesh.hpp.
constexpr double kHexNodes[20][3] = {
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},  // bottom corners
    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1},   // top corners
    {0, -1, -1},  {1, 0, -1},  {0, 1, -1}, {-1, 0, -1},  // bottom mid-edges
    {0, -1, 1},   {1, 0, 1},   {0, 1, 1},  {-1, 0, 1},   // top mid-edges
    {-1, -1, 0},  {1, -1, 0},  {1, 1, 0},  {-1, 1, 0}};  // vertical mid-edges

}  // namespace

namespace detail {

Eigen::VectorXd hex20_shape_functions(const Eigen::Vector3d& xi) {
  Eigen::VectorXd N(20);
  for (int a = 0; a < 20; ++a) {
    const double* c = kHexNodes[a];
    if (a < 8) {
      // Corner: (1/8)(1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a)(xi xi_a + eta eta_a +
      // zeta zeta_a - 2).
      N[a] = 0.125 * (1 + xi[0] * c[0]) * (1 + xi[1] * c[1]) * (1 + xi[2] * c[2]) *
             (xi[0] * c[0] + xi[1] * c[1] + xi[2] * c[2] - 2.0);
    } else {
      // Mid-edge along direction k (c[k] = 0): (1/4)(1 - xi_k^2) prod_{m != k} (1 + xi_m c_m).
      double value = 0.25;
      for (int m = 0; m < 3; ++m) value *= c[m] == 0 ? 1.0 - xi[m] * xi[m] : 1.0 + xi[m] * c[m];
      N[a] = value;
    }
  }
  return N;
}

Eigen::MatrixX3d hex20_shape_derivatives(const Eigen::Vector3d& xi) {
  Eigen::MatrixX3d dN(20, 3);
  for (int a = 0; a < 20; ++a) {
    const double* c = kHexNodes[a];
    if (a < 8) {
      const double f[3] = {1 + xi[0] * c[0], 1 + xi[1] * c[1], 1 + xi[2] * c[2]};
      const double s = xi[0] * c[0] + xi[1] * c[1] + xi[2] * c[2] - 2.0;
      for (int j = 0; j < 3; ++j) {
        const double others = f[(j + 1) % 3] * f[(j + 2) % 3];
        dN(a, j) = 0.125 * c[j] * others * (s + f[j]);
      }
    } else {
      double f[3];
      double df[3];
      for (int m = 0; m < 3; ++m) {
        if (c[m] == 0) {
          f[m] = 1.0 - xi[m] * xi[m];
          df[m] = -2.0 * xi[m];
        } else {
          f[m] = 1.0 + xi[m] * c[m];
          df[m] = c[m];
        }
      }
      for (int j = 0; j < 3; ++j) dN(a, j) = 0.25 * df[j] * f[(j + 1) % 3] * f[(j + 2) % 3];
    }
  }
  return dN;
}

Eigen::Matrix3Xd hex20_natural_nodes() {
  Eigen::Matrix3Xd x(3, 20);
  for (int a = 0; a < 20; ++a) x.col(a) << kHexNodes[a][0], kHexNodes[a][1], kHexNodes[a][2];
  return x;
}

}  // namespace detail

const QuadratureRule& hex_rule_gauss3() {
  static const QuadratureRule rule = [] {
    const auto g = detail::gauss_legendre(3);
    QuadratureRule r;
    r.points.resize(3, 27);
    r.weights.resize(27);
    int q = 0;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        for (int k = 0; k < 3; ++k) {
          r.points.col(q) << g.x[i], g.x[j], g.x[k];
          r.weights[q] = g.w[i] * g.w[j] * g.w[k];
          ++q;
        }
      }
    }
    r.degree = 5;
    return r;
  }();
  return rule;
}

}  // namespace asperity::fem
