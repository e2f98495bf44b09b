// Element matrices of linear elasticity and their sparse assembly (elasticity.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "asperity/core/error.hpp"
#include "asperity/core/parallel.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/fem/elasticity.hpp"
#include "element_detail.hpp"

namespace asperity::fem {

void IsotropicMaterial::validate() const {
  core::require_positive("E", E);
  if (!std::isfinite(nu) || nu <= -1.0 || nu >= 0.5) {
    throw InvalidInput(
        fmt::format("nu = {} is not allowed: it must lie in (-1, 0.5)", core::format_value(nu)));
  }
  core::require_positive("rho", rho);
}

Eigen::Matrix<double, 6, 6> elasticity_matrix(const IsotropicMaterial& material) {
  // Lame constants: lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).
  const double lambda =
      material.E * material.nu / ((1.0 + material.nu) * (1.0 - 2.0 * material.nu));
  const double mu = material.E / (2.0 * (1.0 + material.nu));
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.topLeftCorner<3, 3>().setConstant(lambda);
  D.topLeftCorner<3, 3>().diagonal().array() += 2.0 * mu;
  D.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  return D;
}

Eigen::Matrix3Xd natural_node_coordinates(ElementType type) {
  return type == ElementType::tet10 ? detail::tet10_natural_nodes() : detail::hex20_natural_nodes();
}

Eigen::VectorXd shape_functions(ElementType type, const Eigen::Vector3d& xi) {
  return type == ElementType::tet10 ? detail::tet10_shape_functions(xi)
                                    : detail::hex20_shape_functions(xi);
}

Eigen::MatrixX3d shape_derivatives(ElementType type, const Eigen::Vector3d& xi) {
  return type == ElementType::tet10 ? detail::tet10_shape_derivatives(xi)
                                    : detail::hex20_shape_derivatives(xi);
}

bool is_straight_sided(ElementType type, const Eigen::Matrix3Xd& x) {
  return type == ElementType::tet10 && detail::tet10_straight_sided(x);
}

const QuadratureRule& stiffness_rule(ElementType type, const Eigen::Matrix3Xd& x) {
  if (type == ElementType::hex20) return hex_rule_gauss3();
  return detail::tet10_straight_sided(x) ? tet_rule_degree2() : tet_rule_degree5();
}

const QuadratureRule& mass_rule(ElementType type) {
  return type == ElementType::tet10 ? tet_rule_degree5() : hex_rule_gauss3();
}

namespace {

// Shape functions and derivatives at the points of one rule, computed once per rule.
struct TabulatedRule {
  std::vector<Eigen::VectorXd> N;
  std::vector<Eigen::MatrixX3d> dN;
};

const TabulatedRule& tabulated(ElementType type, const QuadratureRule& rule) {
  const auto make = [](ElementType t, const QuadratureRule& r) {
    TabulatedRule tab;
    for (Eigen::Index q = 0; q < r.points.cols(); ++q) {
      tab.N.push_back(shape_functions(t, r.points.col(q)));
      tab.dN.push_back(shape_derivatives(t, r.points.col(q)));
    }
    return tab;
  };
  static const TabulatedRule tet2 = make(ElementType::tet10, tet_rule_degree2());
  static const TabulatedRule tet5 = make(ElementType::tet10, tet_rule_degree5());
  static const TabulatedRule hex3 = make(ElementType::hex20, hex_rule_gauss3());
  if (type == ElementType::hex20) return hex3;
  return &rule == &tet_rule_degree2() ? tet2 : tet5;
}

// J_ij = dx_i / dxi_j.
Eigen::Matrix3d jacobian(const Eigen::Matrix3Xd& x, const Eigen::MatrixX3d& dN) {
  return x * dN;
}

[[noreturn]] void throw_inverted(double det, Eigen::Index q) {
  throw InvalidInput(
      fmt::format("is inverted: Jacobian determinant {:.3g} at quadrature point {}", det, q));
}

}  // namespace

Eigen::Matrix3Xd element_coordinates(const Mesh& mesh, const ElementBlock& block, std::size_t e) {
  const auto nodes = block.element(e);
  Eigen::Matrix3Xd x(3, static_cast<Eigen::Index>(nodes.size()));
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    x.col(static_cast<Eigen::Index>(a)) = mesh.nodes.col(nodes[a]);
  }
  return x;
}

double element_volume(ElementType type, const Eigen::Matrix3Xd& x) {
  const auto& rule = mass_rule(type);
  const auto& tab = tabulated(type, rule);
  double volume = 0.0;
  for (Eigen::Index q = 0; q < rule.weights.size(); ++q) {
    volume += rule.weights[q] * jacobian(x, tab.dN[static_cast<std::size_t>(q)]).determinant();
  }
  return volume;
}

void check_element_geometry(ElementType type, const Eigen::Matrix3Xd& x) {
  const double volume = element_volume(type, x);
  // The bounding box's volume as the cube of its largest side: also for an element
  // flattened onto a coordinate plane, whose box has no volume.
  const double side = (x.rowwise().maxCoeff() - x.rowwise().minCoeff()).maxCoeff();
  const double box = side * side * side;
  if (!(std::abs(volume) > 1e-12 * box)) {
    throw InvalidInput(
        fmt::format("is degenerate: volume {:.3g} m^3 below 1e-12 of the cube of its largest "
                    "extent ({:.3g} m^3)",
                    volume, box));
  }
  const auto& rule = stiffness_rule(type, x);
  const auto& tab = tabulated(type, rule);
  for (Eigen::Index q = 0; q < rule.weights.size(); ++q) {
    const double det = jacobian(x, tab.dN[static_cast<std::size_t>(q)]).determinant();
    if (!(det > 0.0)) throw_inverted(det, q);
  }
}

Eigen::MatrixXd element_stiffness(ElementType type, const Eigen::Matrix3Xd& x,
                                  const IsotropicMaterial& material) {
  const double lambda =
      material.E * material.nu / ((1.0 + material.nu) * (1.0 - 2.0 * material.nu));
  const double mu = material.E / (2.0 * (1.0 + material.nu));
  const auto& rule = stiffness_rule(type, x);
  const auto& tab = tabulated(type, rule);
  const Eigen::Index n = x.cols();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  Eigen::MatrixX3d g(n, 3);
  for (Eigen::Index q = 0; q < rule.weights.size(); ++q) {
    const auto& dN = tab.dN[static_cast<std::size_t>(q)];
    const Eigen::Matrix3d J = jacobian(x, dN);
    const double det = J.determinant();
    if (!(det > 0.0)) throw_inverted(det, q);
    g.noalias() = dN * J.inverse();  // dN_a / dx_j
    const double w = rule.weights[q] * det;
    // B^T D B for isotropic D: K_(a i)(b j) = lambda g_ai g_bj + mu (g_aj g_bi +
    // delta_ij g_a . g_b), each product formed so that (a i) <-> (b j) gives the same
    // bits: K_e is exactly symmetric.
    for (Eigen::Index b = 0; b < n; ++b) {
      for (Eigen::Index a = 0; a < n; ++a) {
        const double dot = g(a, 0) * g(b, 0) + g(a, 1) * g(b, 1) + g(a, 2) * g(b, 2);
        for (int j = 0; j < 3; ++j) {
          for (int i = 0; i < 3; ++i) {
            K(3 * a + i, 3 * b + j) += w * (lambda * (g(a, i) * g(b, j)) +
                                            mu * (g(a, j) * g(b, i)) + (i == j ? mu * dot : 0.0));
          }
        }
      }
    }
  }
  return K;
}

Eigen::MatrixXd element_mass(ElementType type, const Eigen::Matrix3Xd& x, double rho) {
  const auto& rule = mass_rule(type);
  const auto& tab = tabulated(type, rule);
  const Eigen::Index n = x.cols();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index q = 0; q < rule.weights.size(); ++q) {
    const double det = jacobian(x, tab.dN[static_cast<std::size_t>(q)]).determinant();
    if (!(det > 0.0)) throw_inverted(det, q);
    const auto& N = tab.N[static_cast<std::size_t>(q)];
    const double w = rho * rule.weights[q] * det;
    // w (N_a N_b): the same bits for (a, b) and (b, a).
    for (Eigen::Index b = 0; b < n; ++b) {
      for (Eigen::Index a = 0; a < n; ++a) m(a, b) += w * (N[a] * N[b]);
    }
  }
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (Eigen::Index b = 0; b < n; ++b) {
    for (Eigen::Index a = 0; a < n; ++a) {
      for (int i = 0; i < 3; ++i) M(3 * a + i, 3 * b + i) = m(a, b);
    }
  }
  return M;
}

namespace {

std::string element_name(const Mesh& mesh, const ElementBlock& block, std::size_t e) {
  const auto body = static_cast<std::size_t>(block.body[e]);
  return fmt::format("element {} ({}, body \"{}\")", e, element_type_name(block.type),
                     body < mesh.bodies.size() ? core::printable(mesh.bodies[body]) : "?");
}

void check_materials(const Mesh& mesh, std::span<const IsotropicMaterial> per_body) {
  if (per_body.size() != mesh.bodies.size()) {
    throw InvalidInput(fmt::format("{} material(s) given for {} bodies: one per body is required",
                                   per_body.size(), mesh.bodies.size()));
  }
  for (std::size_t b = 0; b < per_body.size(); ++b) {
    try {
      per_body[b].validate();
    } catch (const InvalidInput& e) {
      throw InvalidInput(
          fmt::format("material of body \"{}\": {}", core::printable(mesh.bodies[b]), e.what()));
    }
  }
}

// The sparsity of a matrix with a 3 x 3 block (or, diagonal_blocks, only the diagonal of
// it) for each pair of nodes sharing an element: per node, its sorted neighbours.
struct NodeGraph {
  std::vector<std::vector<std::int32_t>> neighbours;
};

NodeGraph node_graph(const Mesh& mesh) {
  NodeGraph graph;
  graph.neighbours.resize(static_cast<std::size_t>(mesh.node_count()));
  for (const auto& block : mesh.blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      const auto nodes = block.element(e);
      for (const auto a : nodes) {
        auto& list = graph.neighbours[static_cast<std::size_t>(a)];
        list.insert(list.end(), nodes.begin(), nodes.end());
      }
    }
  }
  for (auto& list : graph.neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return graph;
}

// A compressed column-major matrix under construction with its fixed pattern.
struct PatternMatrix {
  Eigen::Index n = 0;
  bool diagonal_blocks = false;
  std::vector<int> outer;
  std::vector<int> inner;
  std::vector<double> values;

  PatternMatrix(const NodeGraph& graph, bool diagonal_only)
      : n(3 * static_cast<Eigen::Index>(graph.neighbours.size())), diagonal_blocks(diagonal_only) {
    const int per_neighbour = diagonal_only ? 1 : 3;
    std::int64_t nnz = 0;
    for (const auto& list : graph.neighbours) {
      nnz += 3 * per_neighbour * static_cast<std::int64_t>(list.size());
    }
    if (nnz > std::numeric_limits<int>::max()) {
      throw InvalidInput(
          fmt::format("the mesh's matrices would have {} nonzeros, more than the "
                      "{} that 32-bit sparse indices allow",
                      nnz, std::numeric_limits<int>::max()));
    }
    inner.reserve(static_cast<std::size_t>(nnz));
    outer.reserve(static_cast<std::size_t>(n) + 1);
    outer.push_back(0);
    for (const auto& list : graph.neighbours) {
      for (int c = 0; c < 3; ++c) {
        outer.push_back(outer.back() + per_neighbour * static_cast<int>(list.size()));
        for (const auto m : list) {
          if (diagonal_only) {
            inner.push_back(3 * m + c);
          } else {
            for (int r = 0; r < 3; ++r) inner.push_back(3 * m + r);
          }
        }
      }
    }
    values.assign(inner.size(), 0.0);
  }

  // Adds the element matrix A (3 n x 3 n) of `nodes`; `slot[a][b]` is the position of
  // node nodes[b] in the neighbour list of nodes[a].
  void add(std::span<const std::int32_t> nodes, const std::vector<int>& slot,
           const Eigen::MatrixXd& A) {
    const auto count = static_cast<Eigen::Index>(nodes.size());
    for (Eigen::Index a = 0; a < count; ++a) {
      for (int j = 0; j < 3; ++j) {
        const int start =
            outer[static_cast<std::size_t>(3 * nodes[static_cast<std::size_t>(a)] + j)];
        for (Eigen::Index b = 0; b < count; ++b) {
          const int k = slot[static_cast<std::size_t>(a * count + b)];
          if (diagonal_blocks) {
            values[static_cast<std::size_t>(start + k)] += A(3 * b + j, 3 * a + j);
          } else {
            for (int i = 0; i < 3; ++i) {
              values[static_cast<std::size_t>(start + 3 * k + i)] += A(3 * b + i, 3 * a + j);
            }
          }
        }
      }
    }
  }

  [[nodiscard]] SparseMatrix matrix() const {
    const Eigen::Map<const SparseMatrix> map(n, n, static_cast<Eigen::Index>(values.size()),
                                             outer.data(), inner.data(), values.data());
    return SparseMatrix(map);
  }
};

StiffnessAndMass assemble_impl(const Mesh& mesh, std::span<const IsotropicMaterial> per_body,
                               bool want_K, bool want_M) {
  check_materials(mesh, per_body);
  const NodeGraph graph = node_graph(mesh);
  PatternMatrix K(graph, false);
  PatternMatrix M(graph, true);
  // Element matrices in parallel, a chunk at a time; added in element order, so that the
  // sums do not depend on the number of threads.
  constexpr std::size_t kChunk = 2048;
  for (const auto& block : mesh.blocks) {
    const auto n = static_cast<std::size_t>(nodes_per_element(block.type));
    std::vector<Eigen::MatrixXd> Ke(kChunk);
    std::vector<Eigen::MatrixXd> Me(kChunk);
    std::vector<std::vector<int>> slots(kChunk);
    for (std::size_t first = 0; first < block.size(); first += kChunk) {
      const std::size_t count = std::min(kChunk, block.size() - first);
      core::parallel_for(count, [&](std::size_t i) {
        const std::size_t e = first + i;
        const auto& material = per_body[static_cast<std::size_t>(block.body[e])];
        const Eigen::Matrix3Xd x = element_coordinates(mesh, block, e);
        try {
          if (want_K) Ke[i] = element_stiffness(block.type, x, material);
          if (want_M) Me[i] = element_mass(block.type, x, material.rho);
        } catch (const InvalidInput& error) {
          throw InvalidInput(fmt::format("{} {}", element_name(mesh, block, e), error.what()));
        }
        const auto nodes = block.element(e);
        auto& slot = slots[i];
        slot.resize(n * n);
        for (std::size_t a = 0; a < n; ++a) {
          const auto& list = graph.neighbours[static_cast<std::size_t>(nodes[a])];
          for (std::size_t b = 0; b < n; ++b) {
            slot[a * n + b] = static_cast<int>(
                std::lower_bound(list.begin(), list.end(), nodes[b]) - list.begin());
          }
        }
      });
      for (std::size_t i = 0; i < count; ++i) {
        const auto nodes = block.element(first + i);
        if (want_K) K.add(nodes, slots[i], Ke[i]);
        if (want_M) M.add(nodes, slots[i], Me[i]);
      }
    }
  }
  StiffnessAndMass out;
  if (want_K) out.K = K.matrix();
  if (want_M) out.M = M.matrix();
  return out;
}

}  // namespace

StiffnessAndMass assemble(const Mesh& mesh, std::span<const IsotropicMaterial> per_body) {
  return assemble_impl(mesh, per_body, true, true);
}

SparseMatrix assemble_stiffness(const Mesh& mesh, std::span<const IsotropicMaterial> per_body) {
  return assemble_impl(mesh, per_body, true, false).K;
}

SparseMatrix assemble_mass(const Mesh& mesh, std::span<const IsotropicMaterial> per_body) {
  return assemble_impl(mesh, per_body, false, true).M;
}

std::vector<double> body_volumes(const Mesh& mesh) {
  std::vector<double> volume(mesh.bodies.size(), 0.0);
  for (const auto& block : mesh.blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      volume[static_cast<std::size_t>(block.body[e])] +=
          element_volume(block.type, element_coordinates(mesh, block, e));
    }
  }
  return volume;
}

std::vector<double> body_masses(const Mesh& mesh, std::span<const IsotropicMaterial> per_body) {
  check_materials(mesh, per_body);
  auto mass = body_volumes(mesh);
  for (std::size_t b = 0; b < mass.size(); ++b) mass[b] *= per_body[b].rho;
  return mass;
}

}  // namespace asperity::fem
