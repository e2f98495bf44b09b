#include "asperity/fem/interface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <unordered_map>

#include <fmt/format.h>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::fem {
namespace {

// Outward faces of the canonical tet10 (corners, then mid-edges in the face's edge order).
constexpr std::array<std::array<int, 6>, 4> tet10_faces{{
    {0, 2, 1, 6, 5, 4},  // opposite node 3
    {0, 1, 3, 4, 8, 7},  // opposite node 2
    {1, 2, 3, 5, 9, 8},  // opposite node 0
    {0, 3, 2, 7, 9, 6},  // opposite node 1
}};
// Outward faces of the canonical hex20 (VTK_QUADRATIC_HEXAHEDRON order).
constexpr std::array<std::array<int, 8>, 6> hex20_faces{{
    {0, 3, 2, 1, 11, 10, 9, 8},
    {4, 5, 6, 7, 12, 13, 14, 15},
    {0, 1, 5, 4, 8, 17, 12, 16},
    {1, 2, 6, 5, 9, 18, 13, 17},
    {2, 3, 7, 6, 10, 19, 14, 18},
    {3, 0, 4, 7, 11, 16, 15, 19},
}};

int corner_count(int node_count) {
  return node_count == 6 ? 3 : 4;
}

Eigen::Vector3d face_centroid(const Mesh& mesh, const BoundaryFace& f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  const int nc = corner_count(f.node_count);
  for (int i = 0; i < nc; ++i) c += mesh.nodes.col(f.nodes[i]);
  return c / nc;
}

// Area-weighted normal (unit) and area of a face by its quadrature.
std::pair<Eigen::Vector3d, double> face_normal_area(const Mesh& mesh, const BoundaryFace& f) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double area = 0.0;
  for_each_face_point(mesh, f, [&](const double*, const Eigen::Vector3d& wn) {
    sum += wn;
    area += wn.norm();
  });
  const double s = sum.norm();
  return {s > 0 ? Eigen::Vector3d(sum / s) : Eigen::Vector3d::Zero(), area};
}

// A key of a face by its sorted corner positions, rounded to `tol`.
using CornerKey = std::array<std::int64_t, 12>;
CornerKey corner_key(const Mesh& mesh, const BoundaryFace& f, double tol) {
  const int nc = corner_count(f.node_count);
  std::array<std::array<std::int64_t, 3>, 4> pts{};
  for (int i = 0; i < 4; ++i) pts[i] = {std::numeric_limits<std::int64_t>::max(), 0, 0};
  for (int i = 0; i < nc; ++i)
    for (int k = 0; k < 3; ++k) pts[i][k] = std::llround(mesh.nodes(k, f.nodes[i]) / tol);
  std::sort(pts.begin(), pts.end());  // unused slots hold the largest key: they stay last
  CornerKey key{};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) key[3 * i + k] = pts[i][k];
  return key;
}

}  // namespace

const std::vector<std::array<double, 3>>& face_quadrature(int node_count) {
  // tri6: 6-point rule of degree 4 (Dunavant 1985, rule 4), weights on the reference
  // triangle of area 1/2; quad8: 3 x 3 Gauss-Legendre (degree 5 per direction).
  static const std::vector<std::array<double, 3>> tri = [] {
    const double a = 0.445948490915965, wa = 0.223381589678011 / 2;
    const double b = 0.091576213509771, wb = 0.109951743655322 / 2;
    return std::vector<std::array<double, 3>>{{a, a, wa}, {1 - 2 * a, a, wa}, {a, 1 - 2 * a, wa},
                                              {b, b, wb}, {1 - 2 * b, b, wb}, {b, 1 - 2 * b, wb}};
  }();
  static const std::vector<std::array<double, 3>> quad = [] {
    const double g = std::sqrt(0.6);
    const std::array<double, 3> x{-g, 0.0, g}, w{5.0 / 9, 8.0 / 9, 5.0 / 9};
    std::vector<std::array<double, 3>> r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.push_back({x[i], x[j], w[i] * w[j]});
    return r;
  }();
  return node_count == 6 ? tri : quad;
}

void for_each_face_point(
    const Mesh& mesh, const BoundaryFace& f,
    const std::function<void(const double* N, const Eigen::Vector3d& wn)>& point) {
  std::array<double, 8> N{}, dx{}, de{};
  for (const auto& q : face_quadrature(f.node_count)) {
    face_shape(f.node_count, q[0], q[1], N.data(), dx.data(), de.data());
    Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
    for (int i = 0; i < f.node_count; ++i) {
      a += dx[i] * mesh.nodes.col(f.nodes[i]);
      b += de[i] * mesh.nodes.col(f.nodes[i]);
    }
    point(N.data(), q[2] * a.cross(b));
  }
}

void face_shape(int node_count, double xi, double eta, double* N, double* dN_dxi, double* dN_deta) {
  if (node_count == 6) {
    // Quadratic triangle in area coordinates L1 = 1 - xi - eta, L2 = xi, L3 = eta.
    const double L1 = 1 - xi - eta, L2 = xi, L3 = eta;
    N[0] = L1 * (2 * L1 - 1);
    N[1] = L2 * (2 * L2 - 1);
    N[2] = L3 * (2 * L3 - 1);
    N[3] = 4 * L1 * L2;
    N[4] = 4 * L2 * L3;
    N[5] = 4 * L3 * L1;
    dN_dxi[0] = -(4 * L1 - 1);
    dN_dxi[1] = 4 * L2 - 1;
    dN_dxi[2] = 0;
    dN_dxi[3] = 4 * (L1 - L2);
    dN_dxi[4] = 4 * L3;
    dN_dxi[5] = -4 * L3;
    dN_deta[0] = -(4 * L1 - 1);
    dN_deta[1] = 0;
    dN_deta[2] = 4 * L3 - 1;
    dN_deta[3] = -4 * L2;
    dN_deta[4] = 4 * L2;
    dN_deta[5] = 4 * (L1 - L3);
    return;
  }
  // Serendipity quad8: corners (-1,-1), (1,-1), (1,1), (-1,1), then mid-edges.
  constexpr std::array<double, 4> cx{-1, 1, 1, -1}, cy{-1, -1, 1, 1};
  for (int i = 0; i < 4; ++i) {
    const double a = 1 + xi * cx[i], b = 1 + eta * cy[i], c = xi * cx[i] + eta * cy[i] - 1;
    N[i] = 0.25 * a * b * c;
    dN_dxi[i] = 0.25 * cx[i] * b * (c + a);
    dN_deta[i] = 0.25 * cy[i] * a * (c + b);
  }
  // mid-edges 4 (eta = -1), 5 (xi = 1), 6 (eta = 1), 7 (xi = -1)
  N[4] = 0.5 * (1 - xi * xi) * (1 - eta);
  dN_dxi[4] = -xi * (1 - eta);
  dN_deta[4] = -0.5 * (1 - xi * xi);
  N[5] = 0.5 * (1 + xi) * (1 - eta * eta);
  dN_dxi[5] = 0.5 * (1 - eta * eta);
  dN_deta[5] = -(1 + xi) * eta;
  N[6] = 0.5 * (1 - xi * xi) * (1 + eta);
  dN_dxi[6] = -xi * (1 + eta);
  dN_deta[6] = 0.5 * (1 - xi * xi);
  N[7] = 0.5 * (1 - xi) * (1 - eta * eta);
  dN_dxi[7] = -0.5 * (1 - eta * eta);
  dN_deta[7] = -(1 - xi) * eta;
}

std::vector<BoundaryFace> boundary_faces(const Mesh& mesh) {
  // A face is on the boundary when no other element has the same corner nodes.
  std::map<std::array<std::int32_t, 4>, std::pair<BoundaryFace, int>> seen;
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    const auto& block = mesh.blocks[b];
    for (std::size_t e = 0; e < block.size(); ++e) {
      const auto nodes = block.element(e);
      auto add = [&](const auto& local) {
        BoundaryFace f;
        f.node_count = static_cast<int>(local.size());
        for (std::size_t i = 0; i < local.size(); ++i) f.nodes[i] = nodes[local[i]];
        f.body = block.body[e];
        f.block = static_cast<std::int32_t>(b);
        f.element = static_cast<std::int32_t>(e);
        std::array<std::int32_t, 4> key{-1, -1, -1, -1};
        const int nc = corner_count(f.node_count);
        std::copy_n(f.nodes.begin(), nc, key.begin());
        std::sort(key.begin(), key.begin() + nc);
        auto [it, inserted] = seen.try_emplace(key, f, 1);
        if (!inserted) ++it->second.second;
      };
      if (block.type == ElementType::tet10)
        for (const auto& l : tet10_faces) add(l);
      else
        for (const auto& l : hex20_faces) add(l);
    }
  }
  std::vector<BoundaryFace> out;
  for (const auto& [key, value] : seen)
    if (value.second == 1) out.push_back(value.first);
  return out;
}

std::size_t split_shared_nodes(Mesh& mesh) {
  const auto n = static_cast<std::size_t>(mesh.node_count());
  std::vector<std::int32_t> first_body(n, -1);
  // copies[(node, body)] -> new node
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> copies;
  std::vector<Eigen::Vector3d> added;
  for (auto& block : mesh.blocks) {
    const auto npe = static_cast<std::size_t>(nodes_per_element(block.type));
    for (std::size_t e = 0; e < block.size(); ++e) {
      const std::int32_t body = block.body[e];
      for (std::size_t i = 0; i < npe; ++i) {
        auto& node = block.connectivity[e * npe + i];
        auto& owner = first_body[static_cast<std::size_t>(node)];
        if (owner < 0 || owner == body) {
          owner = body;
          continue;
        }
        auto [it, inserted] = copies.try_emplace({node, body}, 0);
        if (inserted) {
          it->second = static_cast<std::int32_t>(n + added.size());
          added.push_back(mesh.nodes.col(node));
        }
        node = it->second;
      }
    }
  }
  if (!added.empty()) {
    const auto old = mesh.nodes.cols();
    mesh.nodes.conservativeResize(3, old + static_cast<Eigen::Index>(added.size()));
    for (std::size_t i = 0; i < added.size(); ++i)
      mesh.nodes.col(old + static_cast<Eigen::Index>(i)) = added[i];
  }
  return added.size();
}

void InterfaceSpec::validate() const {
  if (name.empty()) throw InvalidInput("interface: `name` is empty");
  if (body_a.empty() || body_b.empty())
    throw InvalidInput(fmt::format("interface \"{}\": `bodies` needs two body names", name));
  if (body_a == body_b)
    throw InvalidInput(
        fmt::format("interface \"{}\": `bodies` names \"{}\" twice; an interface joins two bodies",
                    name, body_a));
  if (!normal.allFinite())
    throw InvalidInput(fmt::format("interface \"{}\": `normal` is not finite", name));
  if (patches < 1)
    throw InvalidInput(fmt::format(
        "interface \"{}\": `patches` = {} is not allowed; give at least 1 zero-thickness element",
        name, patches));
}

Interface build_interface(const Mesh& mesh, const std::vector<BoundaryFace>& faces,
                          const InterfaceSpec& spec) {
  spec.validate();
  auto body_index = [&](const std::string& b) {
    const auto it = std::find(mesh.bodies.begin(), mesh.bodies.end(), b);
    if (it == mesh.bodies.end())
      throw InvalidInput(
          fmt::format("interface \"{}\": no body named \"{}\" in the mesh", spec.name, b));
    return static_cast<std::int32_t>(it - mesh.bodies.begin());
  };
  Interface out;
  out.name = spec.name;
  out.body_a = body_index(spec.body_a);
  out.body_b = body_index(spec.body_b);

  const double extent = (mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff()).norm();
  const double tol = 1e-9 * std::max(extent, 1e-300);
  std::map<CornerKey, std::size_t> b_faces;
  for (std::size_t i = 0; i < faces.size(); ++i)
    if (faces[i].body == out.body_b) b_faces.emplace(corner_key(mesh, faces[i], tol), i);

  Eigen::Vector3d wanted = spec.normal;
  const bool select_by_normal = wanted.norm() > 0;
  if (select_by_normal) wanted.normalize();
  std::vector<Eigen::Vector3d> normals;
  for (const auto& fa : faces) {
    if (fa.body != out.body_a) continue;
    const auto it = b_faces.find(corner_key(mesh, fa, tol));
    if (it == b_faces.end()) continue;
    const auto [n, area] = face_normal_area(mesh, fa);
    if (select_by_normal && n.dot(wanted) < std::cos(1e-3)) continue;
    const BoundaryFace& fb = faces[it->second];
    if (fb.node_count != fa.node_count) continue;
    FacePair pair{fa, fb};
    // Match B's nodes to A's by position.
    for (int i = 0; i < fa.node_count; ++i) {
      int best = -1;
      double best_d = std::numeric_limits<double>::infinity();
      for (int j = 0; j < fb.node_count; ++j) {
        const double d = (mesh.nodes.col(fa.nodes[i]) - mesh.nodes.col(fb.nodes[j])).norm();
        if (d < best_d) best_d = d, best = j;
      }
      if (best_d > 1e3 * tol)
        throw InvalidInput(fmt::format(
            "interface \"{}\": a face of body \"{}\" and one of body \"{}\" share their corners "
            "but not their mid-edge nodes ({} m apart): the mesh is not conforming there",
            spec.name, spec.body_a, spec.body_b, core::format_value(best_d)));
      pair.side_b.nodes[i] = fb.nodes[best];
    }
    normals.push_back(n);
    out.face_pairs.push_back(pair);
    out.area += area;
  }
  if (out.face_pairs.empty())
    throw InvalidInput(fmt::format(
        "interface \"{}\": the surfaces of bodies \"{}\" and \"{}\" do not touch{} (no faces with "
        "coincident nodes); the bodies must share a face in the mesh",
        spec.name, spec.body_a, spec.body_b,
        select_by_normal
            ? fmt::format(" with normal ({:g}, {:g}, {:g})", wanted[0], wanted[1], wanted[2])
            : ""));
  if (!select_by_normal) {
    for (const auto& n : normals)
      if (n.dot(normals.front()) < std::cos(1e-3))
        throw InvalidInput(fmt::format(
            "interface \"{}\": bodies \"{}\" and \"{}\" touch on faces of different normals, e.g. "
            "({:.3g}, {:.3g}, {:.3g}) and ({:.3g}, {:.3g}, {:.3g}); give `normal` to choose the "
            "contact plane",
            spec.name, spec.body_a, spec.body_b, normals.front()[0], normals.front()[1],
            normals.front()[2], n[0], n[1], n[2]));
  }
  const auto nf = out.face_pairs.size();
  const auto np = static_cast<std::size_t>(spec.patches);
  if (nf < np)
    throw InvalidInput(fmt::format(
        "interface \"{}\": `patches` = {} but the interface has only {} faces; give at most {} "
        "patches or refine the mesh at the interface",
        spec.name, spec.patches, nf, nf / 4 > 0 ? nf / 4 : 1));

  // Area-weighted k-means of face centroids (Lloyd), farthest-point seeding.
  std::vector<Eigen::Vector3d> c(nf);
  std::vector<double> w(nf);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < nf; ++i) {
    c[i] = face_centroid(mesh, out.face_pairs[i].side_a);
    w[i] = face_normal_area(mesh, out.face_pairs[i].side_a).second;
    mean += w[i] * c[i];
  }
  mean /= out.area;
  std::vector<Eigen::Vector3d> centre;
  std::vector<double> dmin(nf, std::numeric_limits<double>::infinity());
  {
    std::size_t first = 0;
    for (std::size_t i = 1; i < nf; ++i)
      if ((c[i] - mean).squaredNorm() < (c[first] - mean).squaredNorm()) first = i;
    centre.push_back(c[first]);
    while (centre.size() < np) {
      std::size_t far = 0;
      for (std::size_t i = 0; i < nf; ++i) {
        dmin[i] = std::min(dmin[i], (c[i] - centre.back()).squaredNorm());
        if (dmin[i] > dmin[far]) far = i;
      }
      centre.push_back(c[far]);
    }
  }
  std::vector<std::size_t> owner(nf, 0);
  for (int iter = 0; iter < 100; ++iter) {
    bool changed = false;
    for (std::size_t i = 0; i < nf; ++i) {
      std::size_t best = 0;
      double bd = std::numeric_limits<double>::infinity();
      for (std::size_t p = 0; p < np; ++p) {
        const double d = (c[i] - centre[p]).squaredNorm();
        if (d < bd) bd = d, best = p;
      }
      if (best != owner[i] || iter == 0) changed = changed || best != owner[i], owner[i] = best;
    }
    std::vector<Eigen::Vector3d> sum(np, Eigen::Vector3d::Zero());
    std::vector<double> ws(np, 0.0);
    for (std::size_t i = 0; i < nf; ++i) sum[owner[i]] += w[i] * c[i], ws[owner[i]] += w[i];
    for (std::size_t p = 0; p < np; ++p)
      if (ws[p] > 0) centre[p] = sum[p] / ws[p];
    if (!changed && iter > 0) break;
  }
  // Patches in a reproducible order: by centroid x, then y, then z.
  std::vector<InterfacePatch> patches(np);
  for (std::size_t i = 0; i < nf; ++i) {
    auto& p = patches[owner[i]];
    p.faces.push_back(static_cast<std::int32_t>(i));
    p.area += w[i];
  }
  std::erase_if(patches, [](const InterfacePatch& p) { return p.faces.empty(); });
  const Eigen::Vector3d ref_n = normals.front();
  for (auto& p : patches) {
    Eigen::Vector3d cc = Eigen::Vector3d::Zero(), nn = Eigen::Vector3d::Zero();
    for (const auto f : p.faces) {
      cc += w[static_cast<std::size_t>(f)] * c[static_cast<std::size_t>(f)];
      nn += w[static_cast<std::size_t>(f)] * normals[static_cast<std::size_t>(f)];
    }
    p.centroid = cc / p.area;
    const Eigen::Vector3d n = nn.norm() > 0 ? Eigen::Vector3d(nn.normalized()) : ref_n;
    // t1: the global x axis projected on the plane (y when x is nearly normal to it).
    Eigen::Vector3d ref =
        std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d t1 = (ref - ref.dot(n) * n).normalized();
    p.frame.row(0) = t1;
    p.frame.row(1) = n.cross(t1);
    p.frame.row(2) = n;
    std::map<std::pair<std::int32_t, std::int32_t>, double> wsum;
    for (const auto fi : p.faces) {
      const auto& pair = out.face_pairs[static_cast<std::size_t>(fi)];
      const auto& f = pair.side_a;
      for_each_face_point(mesh, f, [&](const double* N, const Eigen::Vector3d& wn) {
        const double jw = wn.norm() / p.area;
        for (int i = 0; i < f.node_count; ++i)
          wsum[{f.nodes[i], pair.side_b.nodes[i]}] += jw * N[i];
      });
    }
    for (const auto& [nodes, weight] : wsum)
      if (std::abs(weight) > 1e-14) p.weights.push_back({nodes.first, nodes.second, weight});
  }
  std::sort(patches.begin(), patches.end(), [](const InterfacePatch& a, const InterfacePatch& b) {
    return std::lexicographical_compare(a.centroid.data(), a.centroid.data() + 3, b.centroid.data(),
                                        b.centroid.data() + 3);
  });
  out.patches = std::move(patches);
  return out;
}

Eigen::SparseMatrix<double> Interface::global_operator(Eigen::Index dofs) const {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t p = 0; p < patches.size(); ++p)
    for (const auto& nw : patches[p].weights)
      for (int k = 0; k < 3; ++k) {
        const auto row = static_cast<Eigen::Index>(3 * p + static_cast<std::size_t>(k));
        t.emplace_back(row, 3 * Eigen::Index{nw.node_b} + k, nw.weight);
        t.emplace_back(row, 3 * Eigen::Index{nw.node_a} + k, -nw.weight);
      }
  Eigen::SparseMatrix<double> L(static_cast<Eigen::Index>(3 * patches.size()), dofs);
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

Eigen::SparseMatrix<double> Interface::local_operator(Eigen::Index dofs) const {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t p = 0; p < patches.size(); ++p)
    for (const auto& nw : patches[p].weights)
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) {
          const double f = patches[p].frame(r, k) * nw.weight;
          if (f == 0.0) continue;
          const auto row = static_cast<Eigen::Index>(3 * p + static_cast<std::size_t>(r));
          t.emplace_back(row, 3 * Eigen::Index{nw.node_b} + k, f);
          t.emplace_back(row, 3 * Eigen::Index{nw.node_a} + k, -f);
        }
  Eigen::SparseMatrix<double> L(static_cast<Eigen::Index>(3 * patches.size()), dofs);
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

Eigen::VectorXd Interface::nodal_forces(const Eigen::VectorXd& traction, Eigen::Index dofs) const {
  if (traction.size() != static_cast<Eigen::Index>(3 * patches.size()))
    throw InvalidInput(
        fmt::format("interface \"{}\": {} traction components given, {} expected "
                    "(3 per patch)",
                    name, traction.size(), 3 * patches.size()));
  Eigen::VectorXd scaled = traction;
  for (std::size_t p = 0; p < patches.size(); ++p)
    scaled.segment<3>(static_cast<Eigen::Index>(3 * p)) *= patches[p].area;
  return local_operator(dofs).transpose() * scaled;
}

}  // namespace asperity::fem
