#include "asperity/fem/bolt.hpp"

#include <cmath>
#include <map>
#include <numbers>

#include <fmt/format.h>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::fem {
namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

struct Footprint {
  std::map<std::int32_t, double> weight;  // node -> consistent nodal area
  double area = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

Footprint find_footprint(const Mesh& mesh, const std::vector<BoundaryFace>& faces,
                         const BoltSpec& spec, const Eigen::Vector3d& point,
                         const Eigen::Vector3d& axis, const char* side) {
  const double extent = (mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff()).norm();
  const double tol = 1e-6 * extent;
  const double r_in = 0.5 * spec.hole_diameter, r_out = 0.5 * spec.washer_diameter;
  Footprint fp;
  for (const auto& f : faces) {
    const int nc = f.node_count == 6 ? 3 : 4;
    bool in_plane = true;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int i = 0; i < f.node_count && in_plane; ++i) {
      const Eigen::Vector3d x = mesh.nodes.col(f.nodes[i]);
      in_plane = std::abs((x - point).dot(axis)) < tol;
      if (i < nc) c += x / nc;
    }
    if (!in_plane) continue;
    const Eigen::Vector3d d = c - point;
    const double r = (d - d.dot(axis) * axis).norm();
    if (r < r_in || r > r_out) continue;
    for_each_face_point(mesh, f, [&](const double* N, const Eigen::Vector3d& wn) {
      const double jw = wn.norm();
      fp.area += jw;
      for (int i = 0; i < f.node_count; ++i) fp.weight[f.nodes[i]] += jw * N[i];
    });
  }
  const double annulus = std::numbers::pi * (r_out * r_out - r_in * r_in);
  if (fp.area < 0.5 * annulus)
    throw InvalidInput(fmt::format(
        "bolt \"{}\": the {} footprint at ({:g}, {:g}, {:g}) m covers {} m^2 of surface, less than "
        "half of the washer annulus ({} m^2): the point is not on a face of the bodies normal "
        "to the bolt axis (a bolt outside its bodies?)",
        spec.name, side, point.x(), point.y(), point.z(), core::format_value(fp.area),
        core::format_value(annulus)));
  for (const auto& [node, w] : fp.weight) fp.centre += w * mesh.nodes.col(node);
  fp.centre /= fp.area;
  return fp;
}

// Rows of the coupling (u_ref; theta_ref) of one footprint, written at row offset `row0`.
void coupling_rows(const Mesh& mesh, const Footprint& fp, Eigen::Index row0,
                   std::vector<Eigen::Triplet<double>>& t) {
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const auto& [node, w] : fp.weight) {
    const Eigen::Vector3d r = mesh.nodes.col(node) - fp.centre;
    S += w * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  const Eigen::Matrix3d Sinv = S.inverse();
  for (const auto& [node, w] : fp.weight) {
    const Eigen::Vector3d r = mesh.nodes.col(node) - fp.centre;
    const Eigen::Matrix3d rot = Sinv * (w * cross_matrix(r));
    for (int k = 0; k < 3; ++k) {
      t.emplace_back(row0 + k, 3 * Eigen::Index{node} + k, w / fp.area);
      for (int j = 0; j < 3; ++j)
        if (rot(k, j) != 0.0) t.emplace_back(row0 + 3 + k, 3 * Eigen::Index{node} + j, rot(k, j));
    }
  }
}

}  // namespace

void BoltSpec::validate() const {
  const std::string who = fmt::format("bolt \"{}\"", name);
  if (name.empty()) throw InvalidInput("bolt: `name` is empty");
  if (!head.allFinite() || !nut.allFinite())
    throw InvalidInput(who + ": `head` and `nut` must be finite points");
  if ((nut - head).norm() <= 0)
    throw InvalidInput(who + ": `head` and `nut` are the same point; the shank needs a length");
  core::require_positive(who + " shank_diameter", shank_diameter);
  core::require_positive(who + " washer_diameter", washer_diameter);
  core::require_non_negative(who + " hole_diameter", hole_diameter);
  if (hole_diameter >= washer_diameter)
    throw InvalidInput(fmt::format("{}: hole_diameter = {} m is not below washer_diameter = {} m",
                                   who, core::format_value(hole_diameter),
                                   core::format_value(washer_diameter)));
  core::require_positive(who + " E", E);
  core::require_in_half_open(who + " nu", nu, -0.99, 0.5);
  core::require_non_negative(who + " rho", rho);
  core::require_non_negative(who + " head_mass", head_mass);
  core::require_non_negative(who + " preload", preload);
}

Bolt place_bolt(const Mesh& mesh, const std::vector<BoundaryFace>& faces, const BoltSpec& spec) {
  spec.validate();
  Bolt bolt;
  bolt.spec = spec;
  const Eigen::Vector3d axis = (spec.nut - spec.head).normalized();
  const Footprint head = find_footprint(mesh, faces, spec, spec.head, axis, "head");
  const Footprint nut = find_footprint(mesh, faces, spec, spec.nut, axis, "nut");
  for (const auto& [node, w] : head.weight) bolt.head_nodes.push_back(node);
  for (const auto& [node, w] : nut.weight) bolt.nut_nodes.push_back(node);
  bolt.length = (nut.centre - head.centre).norm();
  bolt.axis = (nut.centre - head.centre) / bolt.length;
  const Eigen::Index dofs = 3 * mesh.node_count();
  std::vector<Eigen::Triplet<double>> t;
  coupling_rows(mesh, head, 0, t);
  coupling_rows(mesh, nut, 6, t);
  bolt.coupling.resize(12, dofs);
  bolt.coupling.setFromTriplets(t.begin(), t.end());
  Eigen::SparseMatrix<double> e(1, 12);
  std::vector<Eigen::Triplet<double>> et;
  for (int k = 0; k < 3; ++k) {
    et.emplace_back(0, k, -bolt.axis[k]);
    et.emplace_back(0, 6 + k, bolt.axis[k]);
  }
  e.setFromTriplets(et.begin(), et.end());
  const Eigen::SparseMatrix<double> h = e * bolt.coupling;
  bolt.elongation = h.transpose();

  // Euler-Bernoulli frame element in local axes (x' along the shank).
  const double d = spec.shank_diameter, L = bolt.length;
  const double A = std::numbers::pi * d * d / 4, I = std::numbers::pi * std::pow(d, 4) / 64;
  const double G = spec.E / (2 * (1 + spec.nu)), J = 2 * I, E = spec.E;
  bolt.axial_stiffness = E * A / L;
  Eigen::Matrix<double, 12, 12> k = Eigen::Matrix<double, 12, 12>::Zero();
  auto sym = [&](int i, int j, double v) { k(i, j) = v, k(j, i) = v; };
  sym(0, 0, E * A / L), sym(6, 6, E * A / L), sym(0, 6, -E * A / L);
  sym(3, 3, G * J / L), sym(9, 9, G * J / L), sym(3, 9, -G * J / L);
  const double a = 12 * E * I / (L * L * L), b = 6 * E * I / (L * L), c = 4 * E * I / L,
               c2 = 2 * E * I / L;
  // bending in the x'-y' plane (v, theta_z)
  sym(1, 1, a), sym(1, 5, b), sym(1, 7, -a), sym(1, 11, b), sym(5, 5, c), sym(5, 7, -b),
      sym(5, 11, c2), sym(7, 7, a), sym(7, 11, -b), sym(11, 11, c);
  // bending in the x'-z' plane (w, theta_y)
  sym(2, 2, a), sym(2, 4, -b), sym(2, 8, -a), sym(2, 10, -b), sym(4, 4, c), sym(4, 8, b),
      sym(4, 10, c2), sym(8, 8, a), sym(8, 10, b), sym(10, 10, c);
  Eigen::Matrix3d R;
  const Eigen::Vector3d ref =
      std::abs(bolt.axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e2 = bolt.axis.cross(ref).normalized();
  R.row(0) = bolt.axis;
  R.row(1) = e2;
  R.row(2) = bolt.axis.cross(e2);
  Eigen::Matrix<double, 12, 12> T = Eigen::Matrix<double, 12, 12>::Zero();
  for (int i = 0; i < 4; ++i) T.block<3, 3>(3 * i, 3 * i) = R;
  bolt.beam_stiffness = T.transpose() * k * T;
  // Lumped mass: half the shank and one head (nut) with its washer at each end
  // (translations only; the rotary inertia of the heads is neglected).
  const double m_end = 0.5 * spec.rho * A * L + spec.head_mass;
  bolt.beam_mass.setZero();
  for (int i : {0, 1, 2, 6, 7, 8}) bolt.beam_mass(i, i) = m_end;
  return bolt;
}

Eigen::SparseMatrix<double> bolt_stiffness(const Bolt& bolt, Eigen::Index dofs, bool axial) {
  Eigen::Matrix<double, 12, 12> k = bolt.beam_stiffness;
  if (!axial) {
    // remove E A / L (e_h - e_n)(e_h - e_n)^T in global directions
    Eigen::Matrix<double, 12, 1> v = Eigen::Matrix<double, 12, 1>::Zero();
    v.segment<3>(0) = -bolt.axis;
    v.segment<3>(6) = bolt.axis;
    k -= bolt.axial_stiffness * v * v.transpose();
  }
  const Eigen::SparseMatrix<double> Gt = bolt.coupling.transpose();
  Eigen::SparseMatrix<double> out =
      Gt * Eigen::SparseMatrix<double>(Eigen::MatrixXd(k).sparseView()) * bolt.coupling;
  out.conservativeResize(dofs, dofs);
  return out;
}

Eigen::SparseMatrix<double> bolt_mass(const Bolt& bolt, Eigen::Index dofs) {
  const Eigen::SparseMatrix<double> Gt = bolt.coupling.transpose();
  Eigen::SparseMatrix<double> out =
      Gt * Eigen::SparseMatrix<double>(Eigen::MatrixXd(bolt.beam_mass).sparseView()) *
      bolt.coupling;
  out.conservativeResize(dofs, dofs);
  return out;
}

}  // namespace asperity::fem
