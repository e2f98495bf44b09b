// The 10-node tetrahedron: quadratic Lagrange shape functions in volume coordinates
// (Zienkiewicz & Taylor vol. 1, 7th ed., sec. 6.6), its quadrature rules and the
// shared Gauss-Legendre points.
#include <cmath>
#include <numbers>

#include "asperity/core/error.hpp"
#include "asperity/fem/elasticity.hpp"
#include "element_detail.hpp"

namespace asperity::fem {

namespace detail {

Gauss1d gauss_legendre(int n) {
  Gauss1d g;
  g.x.resize(static_cast<std::size_t>(n));
  g.w.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      // P_n(x) and P_n'(x) by the three-term recurrence.
      double p0 = 1.0;
      double p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    const auto j = static_cast<std::size_t>(n - 1 - i);
    g.x[j] = x;
    g.w[j] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return g;
}

}  // namespace detail

namespace {

// dL_i / d(r, s, t).
const Eigen::Vector3d& volume_coordinate_gradient(int i) {
  static const Eigen::Vector3d g[4] = {Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 0, 0),
                                       Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1)};
  return g[i];
}

}  // namespace

namespace detail {

Eigen::VectorXd tet10_shape_functions(const Eigen::Vector3d& xi) {
  const double L[4] = {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  Eigen::VectorXd N(10);
  for (int i = 0; i < 4; ++i) N[i] = L[i] * (2.0 * L[i] - 1.0);
  for (int k = 0; k < 6; ++k)
    N[4 + k] = 4.0 * L[detail::kTetEdges[k][0]] * L[detail::kTetEdges[k][1]];
  return N;
}

Eigen::MatrixX3d tet10_shape_derivatives(const Eigen::Vector3d& xi) {
  const double L[4] = {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  Eigen::MatrixX3d dN(10, 3);
  for (int i = 0; i < 4; ++i) {
    dN.row(i) = (4.0 * L[i] - 1.0) * volume_coordinate_gradient(i).transpose();
  }
  for (int k = 0; k < 6; ++k) {
    const int a = detail::kTetEdges[k][0];
    const int b = detail::kTetEdges[k][1];
    dN.row(4 + k) =
        4.0 *
        (L[b] * volume_coordinate_gradient(a) + L[a] * volume_coordinate_gradient(b)).transpose();
  }
  return dN;
}

Eigen::Matrix3Xd tet10_natural_nodes() {
  Eigen::Matrix3Xd x(3, 10);
  x.leftCols<4>() << 0, 1, 0, 0,  //
      0, 0, 1, 0,                 //
      0, 0, 0, 1;
  for (int k = 0; k < 6; ++k) {
    x.col(4 + k) = 0.5 * (x.col(detail::kTetEdges[k][0]) + x.col(detail::kTetEdges[k][1]));
  }
  return x;
}

bool tet10_straight_sided(const Eigen::Matrix3Xd& x) {
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d a = x.col(detail::kTetEdges[k][0]);
    const Eigen::Vector3d b = x.col(detail::kTetEdges[k][1]);
    if ((x.col(4 + k) - 0.5 * (a + b)).norm() > 1e-10 * (b - a).norm()) return false;
  }
  return true;
}

}  // namespace detail

const QuadratureRule& tet_rule_degree2() {
  // Zienkiewicz & Taylor vol. 1, table 6.4 (4 points, degree 2): a = (5 + 3 sqrt 5) / 20,
  // b = (5 - sqrt 5) / 20, weight 1/24 each (the volume is 1/6).
  static const QuadratureRule rule = [] {
    const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0;
    const double b = (5.0 - std::sqrt(5.0)) / 20.0;
    QuadratureRule r;
    r.points.resize(3, 4);
    r.points << b, a, b, b,  //
        b, b, a, b,          //
        b, b, b, a;
    r.weights = Eigen::VectorXd::Constant(4, 1.0 / 24.0);
    r.degree = 2;
    return r;
  }();
  return rule;
}

const QuadratureRule& tet_rule_degree5() {
  // Conical product (Stroud 1971, sec. 2.7; Duffy 1982): u in [0, 1]^3 mapped to
  // r = u1, s = u2 (1 - u1), t = u3 (1 - u1)(1 - u2), Jacobian (1 - u1)^2 (1 - u2). A
  // polynomial of degree p in (r, s, t) has degree <= p + 2 in each u: 4 Gauss-Legendre
  // points (degree 7) per direction integrate p <= 5 exactly.
  static const QuadratureRule rule = [] {
    const auto g = detail::gauss_legendre(4);
    QuadratureRule r;
    r.points.resize(3, 64);
    r.weights.resize(64);
    int q = 0;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        for (int k = 0; k < 4; ++k) {
          const double u1 = 0.5 * (1.0 + g.x[i]);
          const double u2 = 0.5 * (1.0 + g.x[j]);
          const double u3 = 0.5 * (1.0 + g.x[k]);
          r.points.col(q) << u1, u2 * (1.0 - u1), u3 * (1.0 - u1) * (1.0 - u2);
          r.weights[q] = 0.125 * g.w[i] * g.w[j] * g.w[k] * (1.0 - u1) * (1.0 - u1) * (1.0 - u2);
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
