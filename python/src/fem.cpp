// fem/: stiffness and consistent mass of quadratic solid elements as scipy.sparse
// matrices. The friendly Python face is python/asperity/fem.py; this file binds into
// asperity._core._fem.
#include <nanobind/eigen/dense.h>
#include <nanobind/eigen/sparse.h>
#include <nanobind/stl/pair.h>

#include <fmt/format.h>

#include <cstdint>
#include <utility>

#include "asperity/core/error.hpp"
#include "asperity/fem/elasticity.hpp"
#include "asperity/fem/mesh.hpp"
#include "bindings.hpp"

namespace asperity::python {

using namespace nb::literals;

namespace {

using Nodes = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Connectivity = Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// One body of one element type from arrays; validated (indices, orientation, unused nodes).
fem::Mesh mesh_from_arrays(const Nodes& nodes, const Connectivity& connectivity) {
  if (nodes.cols() != 3) {
    throw InvalidInput(
        fmt::format("nodes has {} columns: it must be (n, 3), x y z per node [m]", nodes.cols()));
  }
  if (connectivity.cols() != 10 && connectivity.cols() != 20) {
    throw InvalidInput(fmt::format(
        "connectivity has {} columns: 10 (tet10) or 20 (hex20) node indices per element",
        connectivity.cols()));
  }
  fem::Mesh mesh;
  mesh.nodes = nodes.transpose();
  mesh.bodies = {"body"};
  fem::ElementBlock block;
  block.type = connectivity.cols() == 10 ? fem::ElementType::tet10 : fem::ElementType::hex20;
  block.connectivity.reserve(static_cast<std::size_t>(connectivity.size()));
  for (Eigen::Index e = 0; e < connectivity.rows(); ++e) {
    for (Eigen::Index a = 0; a < connectivity.cols(); ++a) {
      const std::int64_t node = connectivity(e, a);
      if (node < 0 || node >= nodes.rows()) {
        throw InvalidInput(fmt::format("connectivity[{}, {}] = {}: node indices run from 0 to {}",
                                       e, a, node, nodes.rows() - 1));
      }
      block.connectivity.push_back(static_cast<std::int32_t>(node));
    }
    block.body.push_back(0);
  }
  mesh.blocks.push_back(std::move(block));
  mesh.validate();
  return mesh;
}

}  // namespace

void bind_fem(nb::module_& parent) {
  nb::module_ m = parent.def_submodule(
      "_fem", "C++ functions of the finite-element layer; use asperity.fem (the friendly face).");

  m.def(
      "assemble",
      [](const Nodes& nodes, const Connectivity& connectivity, double E, double nu, double rho) {
        const fem::IsotropicMaterial material{.E = E, .nu = nu, .rho = rho};
        material.validate();
        const fem::Mesh mesh = mesh_from_arrays(nodes, connectivity);
        auto [K, M] = fem::assemble(mesh, std::span<const fem::IsotropicMaterial>(&material, 1));
        return std::make_pair(std::move(K), std::move(M));
      },
      "nodes"_a, "connectivity"_a, "E"_a, "nu"_a, "rho"_a,
      "(K [N/m], M [kg]) as scipy.sparse CSC matrices of size 3 n (dof 3 node + component) "
      "for one isotropic body: nodes (n, 3) [m], connectivity (m, 10) tet10 or (m, 20) hex20 "
      "0-based node indices in the canonical order (include/asperity/fem/mesh.hpp).");
}

}  // namespace asperity::python
