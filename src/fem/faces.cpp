// Element faces: their areas and the consistent nodal forces of a uniform traction
// (elasticity.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/fem/elasticity.hpp"
#include "element_detail.hpp"

namespace asperity::fem {

const std::vector<std::vector<int>>& element_faces(ElementType type) {
  // tet10 mid-edge nodes: 4 (0-1), 5 (1-2), 6 (2-0), 7 (0-3), 8 (1-3), 9 (2-3).
  static const std::vector<std::vector<int>> tet = {
      {0, 2, 1, 6, 5, 4}, {0, 1, 3, 4, 8, 7}, {1, 2, 3, 5, 9, 8}, {0, 3, 2, 7, 9, 6}};
  // hex20 mid-edge nodes: 8-11 bottom (0-1, 1-2, 2-3, 3-0), 12-15 top (4-5, 5-6, 6-7,
  // 7-4), 16-19 vertical (0-4, 1-5, 2-6, 3-7).
  static const std::vector<std::vector<int>> hex = {
      {0, 3, 2, 1, 11, 10, 9, 8},  {4, 5, 6, 7, 12, 13, 14, 15}, {0, 1, 5, 4, 8, 17, 12, 16},
      {1, 2, 6, 5, 9, 18, 13, 17}, {2, 3, 7, 6, 10, 19, 14, 18}, {3, 0, 4, 7, 11, 16, 15, 19}};
  return type == ElementType::tet10 ? tet : hex;
}

namespace {

// Points (u, v) and weights of the face rule on the reference triangle (u, v >= 0,
// u + v <= 1; collapsed 4 x 4 Gauss, degree 5) or square [-1, 1]^2 (4 x 4 Gauss).
struct FaceRule {
  std::vector<std::array<double, 2>> points;
  std::vector<double> weights;
};

const FaceRule& face_rule(ElementType type) {
  static const FaceRule triangle = [] {
    const auto g = detail::gauss_legendre(4);
    FaceRule r;
    for (std::size_t i = 0; i < 4; ++i) {
      for (std::size_t j = 0; j < 4; ++j) {
        const double u = 0.5 * (1.0 + g.x[i]);
        const double v = 0.5 * (1.0 + g.x[j]) * (1.0 - u);
        r.points.push_back({u, v});
        r.weights.push_back(0.25 * g.w[i] * g.w[j] * (1.0 - u));
      }
    }
    return r;
  }();
  static const FaceRule square = [] {
    const auto g = detail::gauss_legendre(4);
    FaceRule r;
    for (std::size_t i = 0; i < 4; ++i) {
      for (std::size_t j = 0; j < 4; ++j) {
        r.points.push_back({g.x[i], g.x[j]});
        r.weights.push_back(g.w[i] * g.w[j]);
      }
    }
    return r;
  }();
  return type == ElementType::tet10 ? triangle : square;
}

// Calls f(N (element's shape functions), dA) at each point of the face rule. The face is
// parametrized in the element's natural coordinates: linearly from its first corners
// (tet10: xi = X0 + u (X1 - X0) + v (X2 - X0); hex20: the bilinear map of its four
// corners, itself linear on a face of the cube).
template <class F>
void integrate_face(ElementType type, const Eigen::Matrix3Xd& x, int face, F&& f) {
  const auto& nodes = element_faces(type)[static_cast<std::size_t>(face)];
  const Eigen::Matrix3Xd natural = natural_node_coordinates(type);
  const auto& rule = face_rule(type);
  for (std::size_t q = 0; q < rule.weights.size(); ++q) {
    const double u = rule.points[q][0];
    const double v = rule.points[q][1];
    Eigen::Vector3d xi;
    Eigen::Vector3d dxi_du;
    Eigen::Vector3d dxi_dv;
    if (type == ElementType::tet10) {
      const Eigen::Vector3d X0 = natural.col(nodes[0]);
      dxi_du = natural.col(nodes[1]) - X0;
      dxi_dv = natural.col(nodes[2]) - X0;
      xi = X0 + u * dxi_du + v * dxi_dv;
    } else {
      // Corners 0..3 of the face at (u, v) = (-1,-1), (1,-1), (1,1), (-1,1).
      const Eigen::Vector3d c0 = natural.col(nodes[0]);
      const Eigen::Vector3d c1 = natural.col(nodes[1]);
      const Eigen::Vector3d c3 = natural.col(nodes[3]);
      dxi_du = 0.5 * (c1 - c0);
      dxi_dv = 0.5 * (c3 - c0);
      xi = c0 + (u + 1.0) * dxi_du + (v + 1.0) * dxi_dv;
    }
    const Eigen::MatrixX3d dN = shape_derivatives(type, xi);
    const Eigen::Matrix3d J = x * dN;
    const double dA = (J * dxi_du).cross(J * dxi_dv).norm();
    f(shape_functions(type, xi), rule.weights[q] * dA);
  }
}

const ElementBlock& checked_block(const Mesh& mesh, const ElementFace& face) {
  if (face.block < 0 || static_cast<std::size_t>(face.block) >= mesh.blocks.size()) {
    throw InvalidInput(
        fmt::format("face of block {}: the mesh has {} blocks", face.block, mesh.blocks.size()));
  }
  const auto& block = mesh.blocks[static_cast<std::size_t>(face.block)];
  const auto faces = static_cast<std::int32_t>(element_faces(block.type).size());
  if (face.element < 0 || static_cast<std::size_t>(face.element) >= block.size() || face.face < 0 ||
      face.face >= faces) {
    throw InvalidInput(fmt::format(
        "face {} of element {} ({}) does not exist: {} elements, "
        "faces 0 to {}",
        face.face, face.element, element_type_name(block.type), block.size(), faces - 1));
  }
  return block;
}

}  // namespace

std::vector<ElementFace> faces_on_nodes(const Mesh& mesh, std::span<const std::int32_t> nodes) {
  std::vector<char> in(static_cast<std::size_t>(mesh.node_count()), 0);
  for (const auto node : nodes) {
    if (node >= 0 && node < mesh.node_count()) in[static_cast<std::size_t>(node)] = 1;
  }
  std::vector<ElementFace> out;
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    const auto& block = mesh.blocks[b];
    const auto& faces = element_faces(block.type);
    for (std::size_t e = 0; e < block.size(); ++e) {
      const auto element = block.element(e);
      for (std::size_t f = 0; f < faces.size(); ++f) {
        const bool all = std::all_of(faces[f].begin(), faces[f].end(), [&](int a) {
          return in[static_cast<std::size_t>(element[static_cast<std::size_t>(a)])] != 0;
        });
        if (all) {
          out.push_back({static_cast<std::int32_t>(b), static_cast<std::int32_t>(e),
                         static_cast<std::int32_t>(f)});
        }
      }
    }
  }
  return out;
}

double faces_area(const Mesh& mesh, std::span<const ElementFace> faces) {
  double area = 0.0;
  for (const auto& face : faces) {
    const auto& block = checked_block(mesh, face);
    const Eigen::Matrix3Xd x =
        element_coordinates(mesh, block, static_cast<std::size_t>(face.element));
    integrate_face(block.type, x, face.face,
                   [&](const Eigen::VectorXd&, double dA) { area += dA; });
  }
  return area;
}

Eigen::VectorXd traction_load(const Mesh& mesh, std::span<const ElementFace> faces,
                              const Eigen::Vector3d& traction) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.node_count());
  for (const auto& face : faces) {
    const auto& block = checked_block(mesh, face);
    const auto e = static_cast<std::size_t>(face.element);
    const Eigen::Matrix3Xd x = element_coordinates(mesh, block, e);
    const auto nodes = block.element(e);
    integrate_face(block.type, x, face.face, [&](const Eigen::VectorXd& N, double dA) {
      // N_a vanishes on the face for nodes off it: only the face's nodes are touched.
      for (const int a : element_faces(block.type)[static_cast<std::size_t>(face.face)]) {
        f.segment<3>(3 * nodes[static_cast<std::size_t>(a)]) += (N[a] * dA) * traction;
      }
    });
  }
  return f;
}

}  // namespace asperity::fem
