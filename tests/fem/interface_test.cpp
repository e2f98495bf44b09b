// Interfaces, bolts, the Craig-Bampton reduction and the linear prestress of fem/ on
// structured meshes (no mesher needed): two boxes stacked along z, their shared face the
// interface, optionally a bolt through both.

// Eigen's dense eigensolvers inlined at -O3: g++ 12's -Wnull-dereference false positive.
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/SparseCholesky>

#include "asperity/core/error.hpp"
#include "asperity/fem/bolt.hpp"
#include "asperity/fem/elasticity.hpp"
#include "asperity/fem/fixture.hpp"
#include "asperity/fem/gap_map.hpp"
#include "asperity/fem/interface.hpp"
#include "asperity/fem/modes.hpp"
#include "asperity/fem/reduced_model.hpp"
#include "asperity/fem/reduction.hpp"
#include "asperity/fem/rough_prestress.hpp"
#include "asperity/fem/structured.hpp"

namespace asperity::fem {
namespace {

using ::testing::HasSubstr;

// Two boxes [0, lx] x [0, ly] x [0, h] ("lower") and [0, lx] x [0, ly] x [h, 2h] ("upper"),
// one mesh: the upper one's nodes appended (coincident with the lower one's top face).
Mesh stacked_boxes(ElementType type, std::array<int, 3> div, double lx = 0.04, double ly = 0.02,
                   double h = 0.01) {
  Mesh a = structured_box_mesh({0, 0, 0}, {lx, ly, h}, div, type, "lower");
  const Mesh b = structured_box_mesh({0, 0, h}, {lx, ly, h}, div, type, "upper");
  const auto offset = static_cast<std::int32_t>(a.node_count());
  a.nodes.conservativeResize(3, a.node_count() + b.node_count());
  a.nodes.rightCols(b.node_count()) = b.nodes;
  a.bodies.push_back("upper");
  auto& block = a.blocks.front();
  for (const auto n : b.blocks.front().connectivity) block.connectivity.push_back(n + offset);
  for (std::size_t e = 0; e < b.blocks.front().size(); ++e) block.body.push_back(1);
  return a;
}

InterfaceSpec lap_spec(int patches) {
  return {
      .name = "lap", .body_a = "lower", .body_b = "upper", .normal = {0, 0, 1}, .patches = patches};
}

TEST(FemInterface, CoincidentFacesFormTheInterfaceWithItsArea) {
  for (const auto type : {ElementType::tet10, ElementType::hex20}) {
    const Mesh m = stacked_boxes(type, {4, 2, 1});
    const auto faces = boundary_faces(m);
    const Interface itf = build_interface(m, faces, lap_spec(4));
    // 4 x 2 cells on the plane: hex20 one quad each, tet10 two triangles each.
    EXPECT_EQ(itf.face_pairs.size(), type == ElementType::hex20 ? 8u : 16u);
    EXPECT_NEAR(itf.area, 0.04 * 0.02, 1e-15);  // straight faces: exact
    ASSERT_EQ(itf.patches.size(), 4u);
    double area = 0;
    for (const auto& p : itf.patches) {
      area += p.area;
      double wsum = 0;
      for (const auto& w : p.weights) wsum += w.weight;
      EXPECT_NEAR(wsum, 1.0, 1e-13);  // a patch average: the weights sum to one
      EXPECT_NEAR(p.frame.row(2).dot(Eigen::Vector3d::UnitZ()), 1.0, 1e-14);
      EXPECT_NEAR((p.frame * p.frame.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
    }
    EXPECT_NEAR(area, itf.area, 1e-15);
  }
}

TEST(FemInterface, RigidMotionsGiveNoRelativeDisplacement) {
  const Mesh m = stacked_boxes(ElementType::tet10, {4, 2, 2});
  const Interface itf = build_interface(m, boundary_faces(m), lap_spec(6));
  const Eigen::MatrixXd R = rigid_body_modes(m.nodes);
  const Eigen::MatrixXd g = itf.local_operator(3 * m.node_count()) * R;
  EXPECT_LT(g.cwiseAbs().maxCoeff(), 1e-15);
  // A relative translation of the upper body is seen whole by every patch.
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * m.node_count());
  for (const auto& blk : m.blocks)
    for (std::size_t e = 0; e < blk.size(); ++e)
      if (blk.body[e] == 1)
        for (const auto n : blk.element(e))
          u.segment<3>(3 * Eigen::Index{n}) = Eigen::Vector3d(1e-6, -2e-6, 3e-6);
  const Eigen::VectorXd gl = itf.local_operator(3 * m.node_count()) * u;
  for (std::size_t p = 0; p < itf.patches.size(); ++p) {
    const Eigen::Vector3d expect = itf.patches[p].frame * Eigen::Vector3d(1e-6, -2e-6, 3e-6);
    EXPECT_NEAR((gl.segment<3>(3 * static_cast<Eigen::Index>(p)) - expect).norm(), 0.0,
                1e-12 * expect.norm());
  }
}

TEST(FemInterface, UniformTractionGivesNodalForcesSummingToTractionTimesArea) {
  const Mesh m = stacked_boxes(ElementType::hex20, {3, 3, 1});
  const Interface itf = build_interface(m, boundary_faces(m), lap_spec(5));
  const Eigen::Vector3d t_local(2e6, -1e6, -5e6);  // Pa (t1, t2, n): a compressive normal
  Eigen::VectorXd t(3 * itf.patches.size());
  for (std::size_t p = 0; p < itf.patches.size(); ++p)
    t.segment<3>(3 * static_cast<Eigen::Index>(p)) = t_local;
  const Eigen::VectorXd f = itf.nodal_forces(t, 3 * m.node_count());
  Eigen::Vector3d upper = Eigen::Vector3d::Zero(), lower = Eigen::Vector3d::Zero();
  const auto& blk = m.blocks.front();
  std::vector<int> body(static_cast<std::size_t>(m.node_count()), -1);
  for (std::size_t e = 0; e < blk.size(); ++e)
    for (const auto n : blk.element(e)) body[static_cast<std::size_t>(n)] = blk.body[e];
  for (Eigen::Index n = 0; n < m.node_count(); ++n)
    (body[static_cast<std::size_t>(n)] == 1 ? upper : lower) += f.segment<3>(3 * n);
  // The frame is the same for every patch of a flat interface.
  const Eigen::Vector3d t_global = itf.patches.front().frame.transpose() * t_local;
  const Eigen::Vector3d expect = t_global * itf.area;
  EXPECT_NEAR((upper - expect).norm(), 0.0, 1e-12 * expect.norm());
  EXPECT_NEAR((lower + expect).norm(), 0.0, 1e-12 * expect.norm());
}

TEST(FemInterface, SplitSharedNodesSeparatesBodiesOfOneMesh) {
  // One box of two cells in z; the upper cell becomes a second body.
  Mesh m =
      structured_box_mesh({0, 0, 0}, {0.02, 0.02, 0.02}, {2, 2, 2}, ElementType::hex20, "lower");
  m.bodies.push_back("upper");
  auto& blk = m.blocks.front();
  for (std::size_t e = 0; e < blk.size(); ++e) {
    double z = 0;
    for (const auto n : blk.element(e)) z += m.nodes(2, n);
    if (z / 20 > 0.01) blk.body[e] = 1;
  }
  const auto before = m.node_count();
  const auto added = split_shared_nodes(m);
  // The mid-plane of a 2 x 2 hex20 grid: 9 corner nodes and 12 mid-edge nodes.
  EXPECT_EQ(added, 21u);
  EXPECT_EQ(m.node_count(), before + 21);
  const Interface itf = build_interface(m, boundary_faces(m), lap_spec(2));
  EXPECT_NEAR(itf.area, 0.02 * 0.02, 1e-16);
}

TEST(FemInterface, RefusalsNameTheInterface) {
  const Mesh m = stacked_boxes(ElementType::tet10, {2, 2, 1});
  const auto faces = boundary_faces(m);
  auto spec = lap_spec(2);
  spec.normal = {1, 0, 0};
  EXPECT_THAT([&] { (void)build_interface(m, faces, spec); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("do not touch")));
  spec = lap_spec(1000);
  EXPECT_THAT([&] { (void)build_interface(m, faces, spec); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("has only 8 faces")));
  spec = lap_spec(2);
  spec.body_b = "nowhere";
  EXPECT_THAT([&] { (void)build_interface(m, faces, spec); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("no body named \"nowhere\"")));
  spec = lap_spec(0);
  EXPECT_THAT([&] { (void)build_interface(m, faces, spec); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("`patches` = 0")));
}

BoltSpec centre_bolt(double preload) {
  return {.name = "b",
          .head = {0.02, 0.01, 0.02},
          .nut = {0.02, 0.01, 0.0},
          .shank_diameter = 0.004,
          .hole_diameter = 0.0,
          .washer_diameter = 0.012,
          .E = 200e9,
          .nu = 0.3,
          .rho = 7800,
          .head_mass = 0.0,
          .preload = preload};
}

TEST(FemBolt, CouplingFollowsRigidMotionAndPretensionIsSelfEquilibrated) {
  const Mesh m = stacked_boxes(ElementType::hex20, {8, 4, 2});
  const auto faces = boundary_faces(m);
  const Bolt bolt = place_bolt(m, faces, centre_bolt(1000.0));
  EXPECT_NEAR(bolt.length, 0.02, 1e-12);
  EXPECT_GT(bolt.head_nodes.size(), 4u);
  // A rigid rotation about x through the mesh centroid: each end's reference moves as
  // the rigid body does at its centre, and turns by the same angle (RBE3 fit, exact).
  const Eigen::MatrixXd R = rigid_body_modes(m.nodes);
  const Eigen::Vector3d c = m.nodes.rowwise().mean();
  for (int k = 0; k < 6; ++k) {
    const Eigen::VectorXd ref = bolt.coupling * R.col(k);
    for (int end = 0; end < 2; ++end) {
      const Eigen::Vector3d at = (end == 0 ? centre_bolt(0).head : centre_bolt(0).nut) - c;
      Eigen::Vector3d u = Eigen::Vector3d::Zero(), th = Eigen::Vector3d::Zero();
      if (k < 3)
        u[k] = 1.0;
      else
        th[k - 3] = 1.0, u = th.cross(at);
      EXPECT_NEAR((ref.segment<3>(6 * end) - u).norm(), 0.0, 1e-12)
          << "mode " << k << " end " << end;
      EXPECT_NEAR((ref.segment<3>(6 * end + 3) - th).norm(), 0.0, 1e-10) << "mode " << k;
    }
  }
  // A rigid motion strains no shank: K_b R = 0.
  const auto Kb = bolt_stiffness(bolt, 3 * m.node_count());
  EXPECT_LT((Kb * R).cwiseAbs().maxCoeff(), 1e-6 * bolt.axial_stiffness * 1e-3);
  // The pretension force (unit tension) sums to zero force and zero moment.
  const Eigen::VectorXd f = -Eigen::VectorXd(bolt.elongation);
  Eigen::Vector3d F = Eigen::Vector3d::Zero(), Mo = Eigen::Vector3d::Zero();
  for (Eigen::Index n = 0; n < m.node_count(); ++n) {
    F += f.segment<3>(3 * n);
    Mo += (m.nodes.col(n) - c).cross(Eigen::Vector3d(f.segment<3>(3 * n)));
  }
  EXPECT_LT(F.norm(), 1e-12);
  EXPECT_LT(Mo.norm(), 1e-14);
  // On the head's footprint it pushes down (-z) by 1 N in all.
  double head_z = 0;
  for (const auto n : bolt.head_nodes) head_z += f[3 * Eigen::Index{n} + 2];
  EXPECT_NEAR(head_z, -1.0, 1e-12);
}

TEST(FemBolt, AFootprintOffTheBodiesIsRefused) {
  const Mesh m = stacked_boxes(ElementType::hex20, {4, 2, 1});
  auto spec = centre_bolt(1000.0);
  spec.head = {0.2, 0.01, 0.02};  // beyond the box
  EXPECT_THAT([&] { (void)place_bolt(m, boundary_faces(m), spec); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("bolt \"b\": the head footprint")));
}

// The full structure: assembly, a bolt, the interface; reduction and its checks.
struct Assembled {
  Mesh mesh;
  Interface itf;
  Bolt bolt;
  SparseMatrix K, M;
};
Assembled assemble_stack(std::array<int, 3> div, int patches, double preload) {
  Assembled a{stacked_boxes(ElementType::hex20, div), {}, {}, {}, {}};
  const auto faces = boundary_faces(a.mesh);
  const IsotropicMaterial steel{200e9, 0.3, 7800};
  const std::vector<IsotropicMaterial> mats{steel, steel};
  auto km = assemble(a.mesh, mats);
  a.bolt = place_bolt(a.mesh, faces, centre_bolt(preload));
  const auto n = 3 * a.mesh.node_count();
  a.K = km.K + bolt_stiffness(a.bolt, n);
  a.M = km.M + bolt_mass(a.bolt, n);
  a.itf = build_interface(a.mesh, faces, lap_spec(patches));
  return a;
}

ReducedModel reduced(const Assembled& a, const CraigBampton& cb) {
  ReducedModel m;
  m.M = cb.M;
  m.K = cb.K;
  const auto n = m.M.rows(), ng = cb.interface_dofs;
  m.Q = Eigen::MatrixXd::Zero(ng, n);
  m.Q.leftCols(ng).setIdentity();
  m.T = Eigen::MatrixXd::Zero(n, ng);
  for (std::size_t p = 0; p < a.itf.patches.size(); ++p) {
    const auto e = static_cast<Eigen::Index>(p);
    for (int k = 0; k < 3; ++k) m.T(3 * e + k, 3 * e + k) = a.itf.patches[p].area;
    m.elements.push_back(
        {"lap", a.itf.patches[p].area, a.itf.patches[p].centroid, a.itf.patches[p].frame});
  }
  m.bolt_elongation = cb.reduce_row(a.bolt.elongation);
  m.bolt_load = -m.bolt_elongation.transpose();
  m.bolt_axial_stiffness = Eigen::VectorXd::Constant(1, a.bolt.axial_stiffness);
  m.bolt_preload = Eigen::VectorXd::Constant(1, a.bolt.spec.preload);
  m.bolt_names = {"b"};
  m.recovery = Eigen::MatrixXd::Zero(0, n);
  m.output_points = Eigen::MatrixXd::Zero(0, 3);
  return m;
}

TEST(FemReduction, ReducedModesMatchTheFullModelInTheRetainedRange) {
  const Assembled a = assemble_stack({8, 4, 2}, 8, 1000.0);
  // Open interface (bolt only): the full model's lowest elastic modes.
  const auto full = sparse_modes(a.K, a.M, 12, -1e4);
  std::vector<double> worst;
  for (const int modes : {10, 30, 60}) {
    const CraigBampton cb =
        craig_bampton(a.K, a.M, a.mesh.nodes, {a.itf}, {.fixed_interface_modes = modes},
                      {-Eigen::VectorXd(a.bolt.elongation)});
    EXPECT_EQ(cb.rigid_body_modes, 6);
    EXPECT_EQ(cb.K.rows(), 24 + modes + 6 + 1);
    const ReducedModel m = reduced(a, cb);
    const auto red = reduced_linear_modes(m, Eigen::VectorXd::Zero(24), 6, "open");
    EXPECT_EQ(red.rigid_body_modes, 6);
    double w = 0;
    for (Eigen::Index i = 0; i < 6; ++i) {
      const double f_full = std::sqrt(full.omega2[6 + i]) / (2 * std::numbers::pi);
      // Craig-Bampton is a Rayleigh-Ritz method: upper bounds of the full model's.
      EXPECT_GE(red.frequency_hz[i], f_full * (1 - 1e-9)) << modes << " modes, mode " << i;
      w = std::max(w, red.frequency_hz[i] / f_full - 1);
    }
    std::printf(
        "fixed-interface modes %d: largest relative error of the first 6 elastic "
        "frequencies %.3e\n",
        modes, w);
    worst.push_back(w);
  }
  // Converging with the tied modes kept, and below 1e-3 with 60 of them (all the
  // interface motion is retained, so only the bodies' interior dynamics is truncated).
  EXPECT_LT(worst[1], worst[0]);
  EXPECT_LT(worst[2], worst[1]);
  EXPECT_LT(worst[2], 1e-3);
}

// Largest differences between the reduced matrices and the Galerkin products B^T K B,
// B^T M B formed explicitly from the basis in mesh DOFs. Entries relative to
// sqrt(k_ii k_jj), k = K + omega_1^2 M with omega_1 the first elastic tied mode, so the
// rigid-body columns are measured too.
struct GalerkinDifference {
  double k = 0.0, m = 0.0;
};
GalerkinDifference galerkin_difference(const CraigBampton& cb,
                                       const Eigen::SparseMatrix<double>& Kf,
                                       const Eigen::SparseMatrix<double>& Mf) {
  const Eigen::MatrixXd& B = cb.basis;
  const Eigen::MatrixXd K = B.transpose() * (Kf * B), M = B.transpose() * (Mf * B);
  EXPECT_EQ(K.rows(), cb.K.rows());
  const double omega2 = cb.tied_omega2[6];
  EXPECT_GT(omega2, 0.0);
  const Eigen::VectorXd scale = (K + omega2 * M).diagonal().cwiseSqrt();
  GalerkinDifference d;
  for (Eigen::Index i = 0; i < K.rows(); ++i)
    for (Eigen::Index j = 0; j < K.cols(); ++j) {
      const double s = scale[i] * scale[j];
      d.k = std::max(d.k, std::abs(cb.K(i, j) - K(i, j)) / s);
      d.m = std::max(d.m, omega2 * std::abs(cb.M(i, j) - M(i, j)) / s);
    }
  return d;
}

// The reduced matrices are the Galerkin products B^T K B and B^T M B of the basis in mesh
// DOFs (the reduction takes the constraint modes' rows of B^T K B from the interface
// flexibility, Psi^T K Psi = S^-1 and Psi^T K Phi = 0: Craig-Bampton's static
// condensation, exact up to the factorisation's round-off). The reduced K spans 12 decades
// (interface stiffness against modal stiffness); 1e-9 is many digits above round-off of the
// products (5.7e-14 here) and far below a missing term.
TEST(FemReduction, ReducedMatricesAreTheBasissGalerkinProducts) {
  const Assembled a = assemble_stack({8, 4, 2}, 8, 1000.0);
  // Two static loads: the bolt's pretension and the weight (M times a unit z translation).
  Eigen::VectorXd uz = Eigen::VectorXd::Zero(a.M.rows());
  for (Eigen::Index i = 2; i < uz.size(); i += 3) uz[i] = 1.0;
  const Eigen::VectorXd bolt = -Eigen::VectorXd(a.bolt.elongation), weight = a.M * uz;
  const CraigBampton cb =
      craig_bampton(a.K, a.M, a.mesh.nodes, {a.itf}, {.fixed_interface_modes = 20}, {bolt, weight});
  const auto [worst_k, worst_m] = galerkin_difference(cb, a.K, a.M);
  EXPECT_LT(worst_k, 1e-9);
  EXPECT_LT(worst_m, 1e-9);
  // Symmetric as stored, and the basis mass-orthonormal on the kept modes and load vectors.
  EXPECT_EQ((cb.K - cb.K.transpose()).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::Index ng = cb.interface_dofs, nk = cb.K.rows() - ng;
  EXPECT_LT(
      (cb.M.bottomRightCorner(nk, nk) - Eigen::MatrixXd::Identity(nk, nk)).cwiseAbs().maxCoeff(),
      1e-9);
  std::printf("Galerkin products: largest scaled difference K %.3e, M %.3e\n", worst_k, worst_m);
  // A load whose response the basis already holds (a multiple of an earlier one) is refused.
  EXPECT_THAT(
      [&] {
        (void)craig_bampton(a.K, a.M, a.mesh.nodes, {a.itf}, {.fixed_interface_modes = 20},
                            {bolt, -2.0 * bolt});
      },
      ::testing::ThrowsMessage<InvalidInput>(HasSubstr("static load 1 adds nothing")));
}

TEST(FemReduction, BoltPretensionIsInEquilibriumWithTheInterfacePressure) {
  const Assembled a = assemble_stack({8, 4, 2}, 8, 1500.0);
  const CraigBampton cb =
      craig_bampton(a.K, a.M, a.mesh.nodes, {a.itf}, {.fixed_interface_modes = 10},
                    {-Eigen::VectorXd(a.bolt.elongation)});
  const ReducedModel m = reduced(a, cb);
  const LinearPrestress p = linear_prestress(m, 1e14);
  double force = 0;
  for (Eigen::Index e = 0; e < p.pressure.size(); ++e)
    force += p.pressure[e] * m.elements[static_cast<std::size_t>(e)].area;
  // The interface carries the bolt's tension: exact in the reduced model because the
  // bolt's load-dependent Ritz vector is in the basis (round-off of the dense solve).
  EXPECT_NEAR(force, 1500.0, 1e-6 * 1500.0);
  EXPECT_GT(p.contact_area, 0.0);
}

// The bolt on the rough flat of Table 7.2 (BKE): Newton's method converges, the interface
// carries the bolt's tension (to the solver's 1e-10 of the load; the load-dependent Ritz
// vector makes it exact in the reduced model), pressures are positive and largest under the
// bolt; a uniform gap changes nothing (a rigid normal translation of one side, free under
// pre-tension, absorbs it: same pressures to 1e-8), and a gap of many sigma on some
// elements takes their load away.
TEST(FemReduction, RoughPrestressCarriesTheBoltLoad) {
  const Assembled a = assemble_stack({8, 4, 2}, 8, 1500.0);
  const CraigBampton cb =
      craig_bampton(a.K, a.M, a.mesh.nodes, {a.itf}, {.fixed_interface_modes = 10},
                    {-Eigen::VectorXd(a.bolt.elongation)});
  const ReducedModel m = reduced(a, cb);
  const contact::Material steel{.E = 200e9, .nu = 0.3, .G = 0.0, .H = 5.8e9};
  const double sigma = 2.7e-6, R = 30.1e-6, eta = 2.9e8;
  const auto flat = surface::RoughFlat::from_dimensional(steel, steel, sigma, eta, R, 1.0,
                                                         contact::ModelName::bke);
  const RoughSurfaceScales scales{
      .sigma = sigma, .pressure_scale = flat.scales()->force, .eta = eta};
  const RoughPrestress p = rough_prestress(m, flat, scales, {});
  EXPECT_LT(std::abs(p.interface_load - 1500.0), 1e-9 * 1500.0);
  EXPECT_EQ(p.bolt_load, 1500.0);
  EXPECT_LE(p.residual, 1e-10);
  EXPECT_GT(p.pressure.minCoeff(), 0.0);
  EXPECT_GT(p.contact_area, 0.0);
  EXPECT_GT(p.real_contact_area, 0.0);
  EXPECT_LT(p.real_contact_area, p.contact_area);
  for (Eigen::Index e = 0; e < p.pressure.size(); ++e) {
    EXPECT_GT(p.normal_stiffness[e], 0.0);
    EXPECT_GT(p.tangential_stiffness[e], 0.0);
  }
  const Eigen::VectorXd uniform = Eigen::VectorXd::Constant(p.pressure.size(), 3.0 * sigma);
  const RoughPrestress q = rough_prestress(m, flat, scales, uniform);
  EXPECT_LT((q.pressure - p.pressure).cwiseAbs().maxCoeff(), 1e-8 * p.pressure.maxCoeff());
  // The patches farther from the interface's centre than the median, lifted by 20 sigma
  // (symmetric about the bolt, so the block cannot tip onto them): the inner ones carry it all.
  const auto ne = p.pressure.size();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (const auto& el : m.elements) {
    centre += el.area * el.centroid;
    total += el.area;
  }
  centre /= total;
  std::vector<double> dist;
  for (const auto& el : m.elements) dist.push_back((el.centroid - centre).norm());
  std::vector<double> sorted = dist;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  Eigen::VectorXd lifted = Eigen::VectorXd::Zero(ne);
  for (Eigen::Index e = 0; e < ne; ++e)
    if (dist[static_cast<std::size_t>(e)] >= median) lifted[e] = 20.0 * sigma;
  const RoughPrestress h = rough_prestress(m, flat, scales, lifted);
  EXPECT_LT(std::abs(h.interface_load - 1500.0), 1e-9 * 1500.0);
  for (Eigen::Index e = 0; e < ne; ++e)
    if (lifted[e] > 0.0) {
      EXPECT_LT(h.pressure[e], 1e-6 * h.pressure.maxCoeff()) << e;
      EXPECT_FALSE(h.in_contact[static_cast<std::size_t>(e)]) << e;
    }
  EXPECT_THAT([&] { (void)rough_prestress(m, flat, scales, Eigen::VectorXd::Zero(3)); },
              ::testing::ThrowsMessage<InvalidInput>(HasSubstr("gap map has 3 values")));
}

// Two patches with the same nodes and weights constrain the same average twice: the
// interface flexibility C K^-1 C^T is singular and the reduction says why.
TEST(FemReduction, DependentPatchesAreRefused) {
  Assembled a = assemble_stack({8, 4, 2}, 8, 1000.0);
  a.itf.patches.push_back(a.itf.patches.front());
  EXPECT_THAT(
      [&] {
        (void)craig_bampton(a.K, a.M, a.mesh.nodes, {a.itf}, {.fixed_interface_modes = 5},
                            {-Eigen::VectorXd(a.bolt.elongation)});
      },
      ::testing::ThrowsMessage<InvalidInput>(
          HasSubstr("relative displacements are not independent")));
}

TEST(FemReduction, MoreRigidBodyModesThanFreeFreeIsRefused) {
  // No bolt and the interface open: the bodies fly apart (12 rigid-body modes).
  Assembled a = assemble_stack({8, 4, 1}, 4, 0.0);
  const IsotropicMaterial steel{200e9, 0.3, 7800};
  const std::vector<IsotropicMaterial> mats{steel, steel};
  auto km = assemble(a.mesh, mats);
  const CraigBampton cb =
      craig_bampton(km.K, km.M, a.mesh.nodes, {a.itf}, {.fixed_interface_modes = 5});
  // Only the interface joins the bodies: the stabilised patches make the factorised K~
  // regular and leave the reduced matrices those of K (reduction.hpp).
  const auto [worst_k, worst_m] = galerkin_difference(cb, km.K, km.M);
  EXPECT_LT(worst_k, 1e-9);
  EXPECT_LT(worst_m, 1e-9);
  ReducedModel m = reduced(a, cb);
  m.bolt_load.setZero();
  EXPECT_THAT(
      [&] { (void)reduced_linear_modes(m, Eigen::VectorXd::Zero(12), 4, "open interface"); },
      ::testing::ThrowsMessage<InvalidInput>(
          HasSubstr("12 rigid-body modes, more than a free-free")));
}

}  // namespace
}  // namespace asperity::fem

namespace asperity::fem {
namespace {

// The published BRB gap map (examples/brb, data README): 13284 points on a regular grid, 596
// of them NaN (bolt holes), gaps 0 to 109 um. At a grid point the element's gap is the map's
// value (bilinear weights 1, 0, 0, 0: round-off only); midway between four it is their mean;
// outside the map the element is named.
// The gripped joint (fixture.hpp) against closed forms: with nu = 0 a uniform traction on a
// face is carried by uniaxial stress, which quadratic elements represent exactly. Lower
// box held on its bottom face, upper box driven along z by its top face through k; one
// patch. A unit pair across the interface compresses both boxes and the spring:
// F(g_n, g_n) = 2 h / (E A) + 1/k; a unit force on z moves the upper box rigidly:
// F(z, z) = F(g_n, z) = 1/k.
TEST(FemFixture, GrippedColumnFlexibilityIsTheClosedForm) {
  const double lx = 0.04, ly = 0.02, h = 0.01, E = 200e9, k = 5e8;
  const Mesh mesh = stacked_boxes(ElementType::hex20, {4, 2, 2}, lx, ly, h);
  const auto faces = boundary_faces(mesh);
  const IsotropicMaterial m0{E, 0.0, 7800};
  const std::vector<IsotropicMaterial> mats{m0, m0};
  const auto km = assemble(mesh, mats);
  const Interface itf = build_interface(mesh, faces, lap_spec(1));
  const Fixture fx{.held = {"lower", {0, 0, 0}, {0, 0, 1}},
                   .driven = {"upper", {0, 0, 2 * h}, {0, 0, 1}},
                   .direction = {0, 0, 1},
                   .drive_stiffness = k};
  const GrippedJoint j = condense_gripped(mesh, km.K, {itf}, {}, fx);
  ASSERT_EQ(j.model.dofs(), 4);  // g (3), z
  EXPECT_EQ(j.drive_dof, 3);
  // The bottom face's quad8 nodes over 4 x 2 cells: 5 x 3 corners, 4 x 3 and 5 x 2 mid-edges.
  EXPECT_EQ(j.held_nodes, 37u);
  EXPECT_EQ(j.driven_nodes, 37u);
  ASSERT_LT((itf.patches.front().frame.row(2) - Eigen::RowVector3d(0, 0, 1)).norm(), 1e-12);
  const Eigen::MatrixXd F = j.model.K.inverse();
  const double A = lx * ly;
  EXPECT_LT(std::abs(F(2, 2) / (2 * h / (E * A) + 1 / k) - 1), 1e-9);
  EXPECT_LT(std::abs(F(3, 3) * k - 1), 1e-9);
  EXPECT_LT(std::abs(F(2, 3) * k - 1), 1e-9);
  EXPECT_THAT(
      [&] {
        Fixture bad = fx;
        bad.driven.point.z() = 0.5 * h;
        (void)condense_gripped(mesh, km.K, {itf}, {}, bad);
      },
      ::testing::ThrowsMessage<InvalidInput>(
          HasSubstr("driven: no boundary face of body \"upper\"")));
  EXPECT_THAT(
      [&] {
        Fixture bad = fx;
        bad.held.body = "middle";
        (void)condense_gripped(mesh, km.K, {itf}, {}, bad);
      },
      ::testing::ThrowsMessage<InvalidInput>(HasSubstr("held.body = \"middle\"")));
  EXPECT_THAT(
      [&] {
        Fixture bad = fx;
        bad.drive_stiffness = 0.0;
        (void)condense_gripped(mesh, km.K, {itf}, {}, bad);
      },
      ::testing::ThrowsMessage<InvalidInput>(HasSubstr("drive_stiffness")));
}

// The bolt as a pre-tension section in the condensed coordinates equals one in the full
// model: a lap (lower box held at x = 0, upper driven along x at x = lx, as the thesis's
// apparatus holds its joint), the bolt tightened with the interface open. The condensed
// model's K - k_b e e^T loaded by the preload on e gives the patches' relative displacement
// of the full model's (K - k_b h h^T) u = -P h^T with the same grips.
TEST(FemFixture, CondensedPretensionEqualsTheFullModels) {
  const Assembled a = assemble_stack({8, 4, 2}, 8, 1500.0);
  const double lx = 0.04, k = 38e6;
  const Fixture fx{.held = {"lower", {0, 0, 0}, {1, 0, 0}},
                   .driven = {"upper", {lx, 0, 0}, {1, 0, 0}},
                   .direction = {1, 0, 0},
                   .drive_stiffness = k};
  const GrippedJoint j = condense_gripped(a.mesh, a.K, {a.itf}, {a.bolt}, fx);
  const auto& m = j.model;
  ASSERT_EQ(m.dofs(), 24 + 1 + 1);
  Eigen::MatrixXd K0 = m.K;
  K0 -= m.bolt_axial_stiffness[0] * m.bolt_elongation.row(0).transpose() * m.bolt_elongation.row(0);
  const Eigen::VectorXd x = K0.ldlt().solve(m.bolt_preload[0] * m.bolt_load.col(0));

  // The full model with the same grips, by a transformation P (n x n_red).
  const auto faces = boundary_faces(a.mesh);
  const auto held = grip_nodes(a.mesh, faces, fx.held, "held");
  const auto driven = grip_nodes(a.mesh, faces, fx.driven, "driven");
  const Eigen::Index n = 3 * a.mesh.node_count();
  std::vector<Eigen::Index> col(static_cast<std::size_t>(n), 0);
  for (const auto i : held)
    for (int c = 0; c < 3; ++c) col[static_cast<std::size_t>(3 * i + c)] = -1;
  for (const auto i : driven)
    for (int c = 0; c < 3; ++c) col[static_cast<std::size_t>(3 * i + c)] = c == 0 ? -2 : -1;
  Eigen::Index nr = 0;
  for (auto& c : col)
    if (c == 0) c = nr++;
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto c = col[static_cast<std::size_t>(i)];
    if (c >= 0) t.emplace_back(i, c, 1.0);
    if (c == -2) t.emplace_back(i, nr, 1.0);
  }
  SparseMatrix P(n, nr + 1);
  P.setFromTriplets(t.begin(), t.end());
  const Eigen::SparseVector<double> hv = a.bolt.elongation;
  const SparseMatrix hs = SparseMatrix(hv);  // n x 1
  SparseMatrix Kp = a.K - a.bolt.axial_stiffness * (hs * hs.transpose());
  SparseMatrix KD = P.transpose() * Kp * P;
  KD.coeffRef(nr, nr) += k;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(KD);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const Eigen::VectorXd f = P.transpose() * (-1500.0 * Eigen::VectorXd(hs));
  const Eigen::VectorXd u = P * ldlt.solve(f);
  const Eigen::VectorXd g = a.itf.local_operator(n) * u;
  EXPECT_LT((x.head(24) - g).cwiseAbs().maxCoeff(), 1e-9 * g.cwiseAbs().maxCoeff());
  EXPECT_LT(std::abs(x[24] - u[3 * driven.front()]), 1e-9 * g.cwiseAbs().maxCoeff());
  // Tightening pulls the faces together (g_n < 0 under the bolt).
  EXPECT_LT(g.minCoeff(), 0.0);
}

TEST(FemGapMap, PublishedBrbMap) {
  const std::string path =
      std::string(ASPERITY_TEST_DATA_DIR) + "/../../examples/brb/brb_surface_data.mat";
  const GapMap map = read_gap_map(path);
  EXPECT_EQ(map.nx * map.ny, 13284);
  EXPECT_EQ(map.gap.array().isNaN().count(), 596);
  const double gmax = map.gap.array().isNaN().select(0.0, map.gap).maxCoeff();
  EXPECT_GT(gmax, 100e-6);
  EXPECT_LT(gmax, 110e-6);
  // A grid cell with four valid corners, away from the holes.
  const Eigen::Index i = 3, j = 4;
  ASSERT_FALSE(
      std::isnan(map.gap(i, j) + map.gap(i + 1, j) + map.gap(i, j + 1) + map.gap(i + 1, j + 1)));
  ReducedModel m;
  const Eigen::Vector3d origin(0.36, 0.0127, 0.0127);
  const auto at = [&](double fi, double fj) {
    InterfaceElement e;
    e.area = 1e-6;
    e.centroid = origin + Eigen::Vector3d(map.x0 + fi * map.dx, map.y0 + fj * map.dy, 0.0);
    return e;
  };
  m.elements = {at(i, j), at(i + 0.5, j + 0.5)};
  const Eigen::VectorXd g = gap_at_elements(map, m, origin);
  EXPECT_NEAR(g[0], map.gap(i, j), 1e-12 * gmax);
  EXPECT_NEAR(
      g[1], 0.25 * (map.gap(i, j) + map.gap(i + 1, j) + map.gap(i, j + 1) + map.gap(i + 1, j + 1)),
      1e-12 * gmax);
  m.elements.push_back(at(-3.0, 2.0));
  EXPECT_THAT(
      [&] { (void)gap_at_elements(map, m, origin); },
      ::testing::ThrowsMessage<InvalidInput>(HasSubstr("does not cover interface element 2")));
}

}  // namespace
}  // namespace asperity::fem
