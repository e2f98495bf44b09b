#include "asperity/fem/fixture.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/SparseCholesky>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::fem {

namespace {

void check_direction(const Eigen::Vector3d& v, const std::string& field) {
  if (!(v.allFinite() && v.norm() > 0.0)) {
    throw InvalidInput(fmt::format("{} = [{}, {}, {}]: give a finite vector of non-zero length",
                                   field, v.x(), v.y(), v.z()));
  }
}

}  // namespace

void Fixture::validate() const {
  for (const auto* g : {&held, &driven}) {
    const std::string what = g == &held ? "held" : "driven";
    if (g->body.empty()) throw InvalidInput(what + ".body: name the gripped body");
    if (!g->point.allFinite()) throw InvalidInput(what + ".point: give finite coordinates");
    check_direction(g->normal, what + ".normal");
  }
  check_direction(direction, "direction");
  core::require_positive("drive_stiffness [N/m]", drive_stiffness);
}

std::vector<std::int32_t> grip_nodes(const Mesh& mesh, const std::vector<BoundaryFace>& faces,
                                     const Grip& grip, const std::string& what) {
  const auto it = std::find(mesh.bodies.begin(), mesh.bodies.end(), grip.body);
  if (it == mesh.bodies.end()) {
    throw InvalidInput(fmt::format("{}.body = \"{}\": the mesh has no such body (bodies: {})", what,
                                   grip.body, fmt::join(mesh.bodies, ", ")));
  }
  const auto body = static_cast<std::int32_t>(it - mesh.bodies.begin());
  const Eigen::Vector3d n = grip.normal.normalized();
  const double extent = (mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff()).norm();
  const double tol = 1e-6 * extent;
  std::vector<std::int32_t> nodes;
  for (const auto& f : faces) {
    if (f.body != body) continue;
    bool in_plane = true;
    for (int k = 0; k < f.node_count && in_plane; ++k)
      in_plane =
          std::abs((mesh.nodes.col(f.nodes[static_cast<std::size_t>(k)]) - grip.point).dot(n)) <=
          tol;
    if (!in_plane) continue;
    for (int k = 0; k < f.node_count; ++k) nodes.push_back(f.nodes[static_cast<std::size_t>(k)]);
  }
  if (nodes.empty()) {
    throw InvalidInput(fmt::format(
        "{}: no boundary face of body \"{}\" lies in the plane through [{}, {}, {}] m normal to "
        "[{}, {}, {}]; give a point on the face the grip holds",
        what, grip.body, grip.point.x(), grip.point.y(), grip.point.z(), n.x(), n.y(), n.z()));
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

GrippedJoint condense_gripped(const Mesh& mesh, const Eigen::SparseMatrix<double>& K,
                              const std::vector<Interface>& interfaces,
                              const std::vector<Bolt>& bolts, const Fixture& fixture) {
  fixture.validate();
  const Eigen::Index full = 3 * mesh.node_count();
  if (K.rows() != full || K.cols() != full) {
    throw InvalidInput(fmt::format("condense_gripped: K is {} x {} for a mesh of {} DOFs", K.rows(),
                                   K.cols(), full));
  }
  const auto faces = boundary_faces(mesh);
  const auto held = grip_nodes(mesh, faces, fixture.held, "held");
  const auto driven = grip_nodes(mesh, faces, fixture.driven, "driven");
  for (const auto n : driven)
    if (std::binary_search(held.begin(), held.end(), n))
      throw InvalidInput(
          fmt::format("node {} is in both grips (held and driven); grip separate faces", n));

  // DOF map: kept DOFs numbered first, z last; held DOFs dropped; a driven node's DOF k is
  // d_k z.
  constexpr Eigen::Index kHeld = -1, kDriven = -2;
  std::vector<Eigen::Index> map(static_cast<std::size_t>(full), 0);
  for (const auto n : held)
    for (int k = 0; k < 3; ++k) map[static_cast<std::size_t>(3 * n + k)] = kHeld;
  for (const auto n : driven)
    for (int k = 0; k < 3; ++k) map[static_cast<std::size_t>(3 * n + k)] = kDriven;
  Eigen::Index kept = 0;
  for (auto& m : map)
    if (m == 0) m = kept++;
  const Eigen::Index z = kept, n_red = kept + 1;
  const Eigen::Vector3d d = fixture.direction.normalized();
  // Each full DOF as (reduced index, coefficient); held: none.
  const auto to_reduced = [&](Eigen::Index i, Eigen::Index& r, double& c) {
    const Eigen::Index m = map[static_cast<std::size_t>(i)];
    if (m == kHeld) return false;
    if (m == kDriven) {
      r = z;
      c = d[i % 3];
      return c != 0.0;
    }
    r = m;
    c = 1.0;
    return true;
  };
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(K.nonZeros()) + 1);
  for (Eigen::Index j = 0; j < K.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, j); it; ++it) {
      Eigen::Index ri = 0, rj = 0;
      double ci = 0.0, cj = 0.0;
      if (to_reduced(it.row(), ri, ci) && to_reduced(it.col(), rj, cj))
        t.emplace_back(ri, rj, ci * cj * it.value());
    }
  t.emplace_back(z, z, fixture.drive_stiffness);
  Eigen::SparseMatrix<double> KD(n_red, n_red);
  KD.setFromTriplets(t.begin(), t.end());

  // Unit loads conjugate to x = [g; z; e]: C (n_red x nq).
  Eigen::Index ng = 0;
  for (const auto& itf : interfaces) ng += 3 * static_cast<Eigen::Index>(itf.patches.size());
  const auto nb = static_cast<Eigen::Index>(bolts.size());
  const Eigen::Index nq = ng + 1 + nb;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n_red, nq);
  const auto add_row = [&](const Eigen::SparseMatrix<double, Eigen::RowMajor>& rows, Eigen::Index r,
                           Eigen::Index col) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it) {
      Eigen::Index ri = 0;
      double ci = 0.0;
      if (to_reduced(it.col(), ri, ci)) C(ri, col) += ci * it.value();
    }
  };
  {
    Eigen::Index row0 = 0;
    for (const auto& itf : interfaces) {
      const Eigen::SparseMatrix<double, Eigen::RowMajor> L = itf.local_operator(full);
      for (Eigen::Index r = 0; r < L.rows(); ++r) add_row(L, r, row0 + r);
      row0 += L.rows();
    }
  }
  C(z, ng) = 1.0;
  for (Eigen::Index b = 0; b < nb; ++b) {
    Eigen::SparseMatrix<double, Eigen::RowMajor> h(1, full);
    h.row(0) = bolts[static_cast<std::size_t>(b)].elongation.transpose();
    add_row(h, 0, ng + 1 + b);
  }

  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(KD);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().array() > 0.0).all()) {
    throw NumericalError(fmt::format(
        "condense_gripped: the gripped structure ({} DOFs) is not positive definite: a body is "
        "free to move (held by neither grip nor tied by a bolt)",
        n_red));
  }
  const Eigen::MatrixXd Y = ldlt.solve(C);
  Eigen::MatrixXd F = C.transpose() * Y;
  F = 0.5 * (F + F.transpose()).eval();
  Eigen::LLT<Eigen::MatrixXd> llt(F);
  if (llt.info() != Eigen::Success) {
    throw NumericalError(
        "condense_gripped: the flexibility over the interface, drive and bolt coordinates is "
        "singular (two coordinates measure the same motion)");
  }

  GrippedJoint out;
  out.full_dofs = full;
  out.held_nodes = held.size();
  out.driven_nodes = driven.size();
  out.drive_dof = ng;
  out.drive_stiffness = fixture.drive_stiffness;
  auto& m = out.model;
  m.source = "gripped joint (quasi-static condensation)";
  m.K = llt.solve(Eigen::MatrixXd::Identity(nq, nq));
  m.K = 0.5 * (m.K + m.K.transpose()).eval();
  m.M = Eigen::MatrixXd::Identity(nq, nq);
  m.Q = Eigen::MatrixXd::Zero(ng, nq);
  m.Q.leftCols(ng).setIdentity();
  m.T = Eigen::MatrixXd::Zero(nq, ng);
  for (const auto& itf : interfaces)
    for (const auto& p : itf.patches) {
      const auto e = static_cast<Eigen::Index>(m.elements.size());
      for (int k = 0; k < 3; ++k) m.T(3 * e + k, 3 * e + k) = p.area;
      m.elements.push_back({itf.name, p.area, p.centroid, p.frame});
    }
  m.bolt_load = Eigen::MatrixXd::Zero(nq, nb);
  m.bolt_elongation = Eigen::MatrixXd::Zero(nb, nq);
  m.bolt_axial_stiffness.resize(nb);
  m.bolt_preload.resize(nb);
  for (Eigen::Index b = 0; b < nb; ++b) {
    const auto& bolt = bolts[static_cast<std::size_t>(b)];
    m.bolt_elongation(b, ng + 1 + b) = 1.0;
    m.bolt_load(ng + 1 + b, b) = -1.0;  // a unit tension pulls head to nut
    m.bolt_axial_stiffness[b] = bolt.axial_stiffness;
    m.bolt_preload[b] = bolt.spec.preload;
    m.bolt_names.push_back(bolt.spec.name);
  }
  m.recovery.resize(0, nq);
  m.output_points.resize(0, 3);
  m.validate();
  return out;
}

}  // namespace asperity::fem
