// fem/geometry.hpp: validation of constructive solid geometry, point-in-body, the gmsh
// script, and meshing by the gmsh program (conforming across shared faces, volumes
// preserved), including the Brake-Reuss beam of issue 19.
#include "asperity/fem/geometry.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>

#include "../support.hpp"
#include "asperity/core/error.hpp"
#include "mesh_test_support.hpp"

namespace {

using asperity::InvalidInput;
using asperity::NumericalError;
using asperity::testing::body_volume;
using asperity::testing::element_total;
using asperity::testing::invalid_input_message;
using asperity::testing::max_mid_edge_offset;
using asperity::testing::TempDir;
namespace fem = asperity::fem;
using Eigen::Vector3d;

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

fem::Geometry two_boxes() {
  // Two 20 x 10 x 10 mm boxes side by side, sharing the face x = 20 mm.
  fem::Geometry g;
  g.bodies.push_back({"left", {fem::Box{Vector3d(0, 0, 0), Vector3d(0.02, 0.01, 0.01)}}, {}});
  g.bodies.push_back({"right", {fem::Box{Vector3d(0.02, 0, 0), Vector3d(0.02, 0.01, 0.01)}}, {}});
  g.size = {0.005, 0.0025, 0.0025};
  return g;
}

std::string validate_msg(const fem::Geometry& g) {
  return invalid_input_message([&] { g.validate(); });
}

TEST(FemGeometry, ValidateNamesTheItem) {
  EXPECT_EQ(validate_msg(two_boxes()), "");
  auto g = two_boxes();
  g.bodies[1].name = "left";
  EXPECT_CONTAINS(validate_msg(g), "bodies[2] \"left\": another body has the same name");
  g = two_boxes();
  g.bodies[0].name = "";
  EXPECT_CONTAINS(validate_msg(g), "bodies[1]: the name is empty");
  g = two_boxes();
  g.size.interface = 0;
  EXPECT_CONTAINS(validate_msg(g), "size.interface = 0 is not allowed");
  g = two_boxes();
  g.bodies[0].add.clear();
  EXPECT_CONTAINS(validate_msg(g), "bodies[1] \"left\": nothing to add");
  g = two_boxes();
  std::get<fem::Box>(g.bodies[1].add[0]).size.y() = 0;
  EXPECT_CONTAINS(validate_msg(g),
                  "bodies[2] \"right\": add[1] (box): size = (0.02, 0, 0.01) m is degenerate");
  g = two_boxes();
  g.bodies[0].cut.push_back(fem::Cylinder{Vector3d(0.01, 0.005, 0), Vector3d(0, 0, 0.01), 0.0});
  EXPECT_CONTAINS(validate_msg(g),
                  "bodies[1] \"left\": cut[1] (cylinder): radius = 0 is not allowed");
  g = two_boxes();
  g.bodies[0].cut.push_back(fem::Cylinder{Vector3d(0.1, 0.005, 0), Vector3d(0, 0, 0.01), 0.002});
  EXPECT_CONTAINS(validate_msg(g), "bodies[1] \"left\": cut[1] (cylinder) misses the body");
  g = two_boxes();
  g.bodies[0].cut.push_back(fem::Box{Vector3d(-1, -1, -1), Vector3d(2, 2, 2)});
  EXPECT_CONTAINS(validate_msg(g), "bodies[1] \"left\": cut[1] (box) holds the whole body");
  g = two_boxes();
  g.size.global = 1e-5;
  EXPECT_CONTAINS(validate_msg(g), "more than 10 million");
  g.bodies.clear();
  EXPECT_CONTAINS(validate_msg(g), "no body");
}

TEST(FemGeometry, PrismPolygonsAreChecked) {
  const auto with_prism = [](std::vector<Vector3d> polygon, Vector3d extrusion) {
    fem::Geometry g;
    g.bodies.push_back({"p", {fem::Prism{std::move(polygon), extrusion}}, {}});
    g.size = {0.01, 0.01, 0.01};
    return validate_msg(g);
  };
  const Vector3d up(0, 0, 0.01);
  // An L-shaped (non-convex) hexagon, explicitly closed (the first vertex repeated): fine.
  const std::vector<Vector3d> ell = {{0, 0, 0},       {0.02, 0, 0},    {0.02, 0.01, 0},
                                     {0.01, 0.01, 0}, {0.01, 0.02, 0}, {0, 0.02, 0},
                                     {0, 0, 0}};
  EXPECT_EQ(with_prism(ell, up), "");
  EXPECT_CONTAINS(
      with_prism({{0, 0, 0}, {0.01, 0, 0}}, up),
      "bodies[1] \"p\": add[1] (prism): the polygon does not close: 2 distinct vertices");
  EXPECT_CONTAINS(with_prism({{0, 0, 0}, {0.01, 0, 0}, {0.02, 0, 0}}, up),
                  "the polygon does not close: its area is zero");
  EXPECT_CONTAINS(with_prism({{0, 0, 0}, {0.01, 0, 0}, {0.01, 0.01, 0.001}, {0, 0.01, 0}}, up),
                  "the polygon is not planar");
  // An uneven bow tie (net area not zero): edges 1-2 and 3-4 cross (vertices counted from 1).
  EXPECT_CONTAINS(with_prism({{0, 0, 0}, {0.02, 0.01, 0}, {0.02, 0, 0}, {0, 0.005, 0}}, up),
                  "add[1] (prism): the polygon is self-intersecting: edges 1-2 and 3-4 meet");
  EXPECT_CONTAINS(with_prism({{0, 0, 0}, {0.01, 0, 0}, {0, 0.01, 0}}, Vector3d(0.01, 0, 0)),
                  "the extrusion is parallel to the polygon's plane");
}

TEST(FemGeometry, ContainsFollowsTheConstruction) {
  // A 30 mm cube with a 10 mm hole along z through its centre, plus an L-prism on top.
  fem::Body b;
  b.name = "b";
  b.add.push_back(fem::Box{Vector3d(0, 0, 0), Vector3d(0.03, 0.03, 0.03)});
  b.add.push_back(fem::Prism{{{0, 0, 0.03},
                              {0.02, 0, 0.03},
                              {0.02, 0.01, 0.03},
                              {0.01, 0.01, 0.03},
                              {0.01, 0.02, 0.03},
                              {0, 0.02, 0.03}},
                             Vector3d(0, 0, 0.01)});
  b.cut.push_back(fem::Cylinder{Vector3d(0.015, 0.015, -0.01), Vector3d(0, 0, 0.06), 0.005});
  EXPECT_TRUE(fem::contains(b, Vector3d(0.002, 0.002, 0.002), 0));
  EXPECT_FALSE(fem::contains(b, Vector3d(0.015, 0.015, 0.015), 0));   // in the hole
  EXPECT_TRUE(fem::contains(b, Vector3d(0.015, 0.0095, 0.015), 0));   // 0.5 mm from the hole
  EXPECT_FALSE(fem::contains(b, Vector3d(0.015, 0.0105, 0.015), 0));  // 0.5 mm inside it
  EXPECT_TRUE(fem::contains(b, Vector3d(0.005, 0.015, 0.035), 0));    // in the prism's leg
  EXPECT_FALSE(fem::contains(b, Vector3d(0.015, 0.015, 0.035), 0));   // in the L's notch
  EXPECT_FALSE(fem::contains(b, Vector3d(0.005, 0.005, 0.0401), 0));  // above the prism
  // Tolerance: a point 1 um outside counts as inside with a 2 um tolerance.
  EXPECT_FALSE(fem::contains(b, Vector3d(-1e-6, 0.01, 0.01), 0));
  EXPECT_TRUE(fem::contains(b, Vector3d(-1e-6, 0.01, 0.01), 2e-6));
}

TEST(FemGeometry, ScriptFragmentsTheBodies) {
  auto g = two_boxes();
  g.bodies[0].cut.push_back(fem::Cylinder{Vector3d(0.01, 0.005, 0), Vector3d(0, 0, 0.01), 0.002});
  const auto s = fem::gmsh_script(g);
  EXPECT_CONTAINS(s, "SetFactory(\"OpenCASCADE\");");
  EXPECT_CONTAINS(s, "Mesh.ElementOrder = 2;");
  EXPECT_CONTAINS(s, "b0[] = BooleanDifference{ Volume{b0[]}; Delete; }{ Volume{c0_0}; Delete; };");
  EXPECT_CONTAINS(s, "all[] = {b0[], b1[]};");
  EXPECT_CONTAINS(s, "BooleanFragments{ Volume{all[]}; Delete; }{};");
  EXPECT_CONTAINS(s, "= Cylinder;");
  // The interface size on the faces the bodies share, found after the fragments.
  EXPECT_CONTAINS(s, "= Distance;");
  EXPECT_CONTAINS(s, ".FacesList = {shared[]};");
  EXPECT_CONTAINS(s, "= Threshold;");
  EXPECT_EQ(s.find("left"), std::string::npos);  // names stay out of the script
}

// Nodes of the plane `axis` = value, and the bodies whose elements use each node.
std::vector<std::set<int>> bodies_of_nodes(const fem::Mesh& m) {
  std::vector<std::set<int>> of(static_cast<std::size_t>(m.nodes.cols()));
  for (const auto& block : m.blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      for (const auto n : block.element(e)) of[static_cast<std::size_t>(n)].insert(block.body[e]);
    }
  }
  return of;
}

TEST(FemGeometry, TwoBoxesMeshConforming) {
  const TempDir dir;
  fem::MeshOptions options;
  options.work_dir = dir.file("work");
  const auto m = fem::mesh_geometry(two_boxes(), options);
  EXPECT_TRUE(std::filesystem::exists(dir.file("work/geometry.geo")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("work/geometry.msh")));
  ASSERT_EQ(m.bodies, (std::vector<std::string>{"left", "right"}));
  ASSERT_EQ(m.blocks.size(), 1u);
  EXPECT_EQ(m.blocks[0].type, fem::ElementType::tet10);
  // Plane faces only: every mid-edge node is the mean of its corners, to rounding of
  // coordinates of 0.04 m (16 digits).
  EXPECT_LE(max_mid_edge_offset(m), 1e-15);
  // Volumes: per body and in total, the boxes' 2e-6 m^3, to 1e-9 relative (straight-sided
  // tetrahedra fill a box exactly; only rounding remains).
  const double box = 0.02 * 0.01 * 0.01;
  const auto [total, smallest] = body_volume(m);
  EXPECT_GT(smallest, 0.0);
  EXPECT_NEAR(total, 2 * box, 1e-9 * 2 * box);
  EXPECT_NEAR(body_volume(m, 0).first, box, 1e-9 * box);
  EXPECT_NEAR(body_volume(m, 1).first, box, 1e-9 * box);
  // Conforming: every node on the shared face x = 20 mm is used by elements of both
  // bodies, and no other node is.
  const auto of = bodies_of_nodes(m);
  std::size_t on_face = 0;
  for (Eigen::Index j = 0; j < m.nodes.cols(); ++j) {
    const bool face = std::abs(m.nodes(0, j) - 0.02) <= 1e-15;
    on_face += face;
    EXPECT_EQ(of[static_cast<std::size_t>(j)].size(), face ? 2u : 1u) << "node " << j;
  }
  // The 10 x 10 mm face at interface size 2.5 mm: at least a 5 x 5 grid of nodes.
  EXPECT_GE(on_face, 25u);
  EXPECT_EQ(m.element_sets.at("left").size() + m.element_sets.at("right").size(),
            m.blocks[0].size());
}

TEST(FemGeometry, ObliquePrismWithACapMeshes) {
  // An L-shaped hexagon (area 2 x 1 + 1 x 1 cm^2 = 3e-4 m^2) swept along (2, 0, 10) mm:
  // an oblique prism of volume area x height = 3e-6 m^3 (Cavalieri); on its top face a
  // 10 x 10 x 5 mm box, sharing the part of the face under it.
  fem::Geometry g;
  const std::vector<Vector3d> ell = {{0, 0, 0},       {0.02, 0, 0},    {0.02, 0.01, 0},
                                     {0.01, 0.01, 0}, {0.01, 0.02, 0}, {0, 0.02, 0}};
  g.bodies.push_back({"ell", {fem::Prism{ell, Vector3d(0.002, 0, 0.01)}}, {}});
  g.bodies.push_back(
      {"cap", {fem::Box{Vector3d(0.002, 0, 0.01), Vector3d(0.01, 0.01, 0.005)}}, {}});
  g.size = {0.004, 0.002, 0.002};
  const auto m = fem::mesh_geometry(g);
  ASSERT_EQ(m.bodies, (std::vector<std::string>{"ell", "cap"}));
  EXPECT_LE(max_mid_edge_offset(m), 1e-15);
  // Straight-sided tetrahedra fill plane-faced solids exactly: 1e-9 relative is rounding.
  EXPECT_NEAR(body_volume(m, 0).first, 3e-6, 1e-9 * 3e-6);
  EXPECT_NEAR(body_volume(m, 1).first, 5e-7, 1e-9 * 5e-7);
  EXPECT_GT(body_volume(m).second, 0.0);
  // Every element's centroid is in its own body and not in the other.
  for (std::size_t e = 0; e < m.blocks[0].size(); ++e) {
    const auto el = m.blocks[0].element(e);
    Vector3d c = Vector3d::Zero();
    for (int k = 0; k < 4; ++k) c += 0.25 * m.nodes.col(el[static_cast<std::size_t>(k)]);
    const auto b = static_cast<std::size_t>(m.blocks[0].body[e]);
    EXPECT_TRUE(fem::contains(g.bodies[b], c, 0.0)) << e;
    EXPECT_FALSE(fem::contains(g.bodies[1 - b], c, 0.0)) << e;
  }
  // Conforming on the shared 10 x 10 mm patch of the plane z = 10 mm.
  const auto of = bodies_of_nodes(m);
  std::size_t shared = 0;
  for (Eigen::Index j = 0; j < m.nodes.cols(); ++j) {
    const Vector3d p = m.nodes.col(j);
    if (std::abs(p.z() - 0.01) > 1e-15 || p.x() < 0.002 - 1e-15 || p.x() > 0.012 + 1e-15 ||
        p.y() > 0.01 + 1e-15) {
      continue;
    }
    EXPECT_EQ(of[static_cast<std::size_t>(j)].size(), 2u) << j;
    ++shared;
  }
  EXPECT_GE(shared, 25u);  // a 5 x 5 grid at 2 mm at least
}

TEST(FemGeometry, UnionOfOverlappingPrimitivesIsOneBody) {
  // A tee: a 30 x 10 x 10 mm bar and a 10 x 10 x 30 mm post overlapping over a 10 mm
  // cube; union volume 3 + 3 - 1 = 5 cm^3, exactly (plane faces).
  fem::Geometry g;
  g.bodies.push_back({"tee",
                      {fem::Box{Vector3d(0, 0, 0), Vector3d(0.03, 0.01, 0.01)},
                       fem::Box{Vector3d(0.01, 0, 0), Vector3d(0.01, 0.01, 0.03)}},
                      {}});
  g.size = {0.005, 0.005, 0.005};
  const auto m = fem::mesh_geometry(g);
  ASSERT_EQ(m.bodies, std::vector<std::string>{"tee"});
  EXPECT_NEAR(body_volume(m).first, 5e-6, 1e-9 * 5e-6);
  EXPECT_GT(body_volume(m).second, 0.0);
}

TEST(FemGeometry, BrakeReussBeam) {
  // Issue 19's BRB: two half-beams 420 mm long, 25.4 x 25.4 mm, lapped over 120 mm at
  // half thickness, three 8.5 mm holes through the lap at -30, 0, +30 mm from its centre.
  const double w = 0.0254;
  const double t = 0.0127;
  fem::Geometry g;
  const auto holes = [&] {
    std::vector<fem::Primitive> cuts;
    for (const double x : {0.33, 0.36, 0.39}) {
      cuts.push_back(fem::Cylinder{Vector3d(x, w / 2, 0), Vector3d(0, 0, w), 0.0085 / 2});
    }
    return cuts;
  };
  fem::Body a{"half A",
              {fem::Box{Vector3d(0, 0, 0), Vector3d(0.42, w, w)}},
              {fem::Box{Vector3d(0.30, 0, t), Vector3d(0.12, w, t)}}};
  fem::Body b{"half B",
              {fem::Box{Vector3d(0.30, 0, 0), Vector3d(0.42, w, w)}},
              {fem::Box{Vector3d(0.30, 0, 0), Vector3d(0.12, w, t)}}};
  for (auto& c : holes()) a.cut.push_back(c);
  for (auto& c : holes()) b.cut.push_back(c);
  g.bodies = {a, b};
  g.size = {0.006, 0.003, 0.0015};
  const auto start = std::chrono::steady_clock::now();
  const auto m = fem::mesh_geometry(g);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "BRB mesh (global 6 mm, interface 3 mm, hole 1.5 mm): %lld nodes, %zu elements, "
      "%.2f s\n",
      static_cast<long long>(m.nodes.cols()), element_total(m), seconds);
  ASSERT_EQ(m.bodies, (std::vector<std::string>{"half A", "half B"}));
  // Volume of each half: 420 x 25.4 x 25.4 mm less the 120 x 25.4 x 12.7 mm step and the
  // three holes through the 12.7 mm lap. The corners of the tetrahedra on a hole lie on
  // its circle, so straight-sided volumes see an inscribed polygon: with elements of
  // 1.5 mm on a 4.25 mm radius (about 18 sides) the hole's area is ~2 % low, i.e.
  // ~4e-4 of the half's volume; 1e-3 relative bounds it.
  const double half = 0.42 * w * w - 0.12 * w * t - 3 * std::numbers::pi * 0.00425 * 0.00425 * t;
  for (int body = 0; body < 2; ++body) {
    const auto [v, smallest] = body_volume(m, body);
    EXPECT_GT(smallest, 0.0);
    EXPECT_NEAR(v, half, 1e-3 * half) << m.bodies[static_cast<std::size_t>(body)];
    EXPECT_GT(v, half) << "an inscribed polygon leaves more material, never less";
  }
  // Conforming across the lap plane z = 12.7 mm (x in 300..420 mm, outside the holes)
  // and the step faces x = 300 and 420 mm: nodes there are used by both halves.
  const auto of = bodies_of_nodes(m);
  std::size_t lap = 0;
  for (Eigen::Index j = 0; j < m.nodes.cols(); ++j) {
    const Vector3d p = m.nodes.col(j);
    const bool on_lap = std::abs(p.z() - t) < 1e-12 && p.x() > 0.30 + 1e-9 && p.x() < 0.42 - 1e-9;
    if (!on_lap) continue;
    bool in_hole = false;
    for (const double x : {0.33, 0.36, 0.39}) {
      in_hole |= std::hypot(p.x() - x, p.y() - w / 2) < 0.00425 - 1e-9;
    }
    EXPECT_FALSE(in_hole);
    EXPECT_EQ(of[static_cast<std::size_t>(j)].size(), 2u) << "lap node " << j;
    ++lap;
  }
  // 120 x 25.4 mm at 3 mm: more than 40 x 8 nodes.
  EXPECT_GT(lap, 320u);
  std::printf("BRB lap-plane nodes shared by both halves: %zu\n", lap);
}

TEST(FemGeometry, OverlappingBodiesAreRefused) {
  auto g = two_boxes();
  std::get<fem::Box>(g.bodies[1].add[0]).corner.x() = 0.015;  // 5 mm into "left"
  const auto msg = invalid_input_message([&] { (void)fem::mesh_geometry(g); });
  EXPECT_CONTAINS(msg, "bodies[1] \"left\" and bodies[2] \"right\" overlap in volume");
}

TEST(FemGeometry, VanishedBodyIsRefused) {
  // A cylinder cut that removes all of the box (validate cannot tell a box from a
  // cylinder holding it): gmsh leaves nothing of the body.
  auto g = two_boxes();
  g.bodies[1].cut.push_back(
      fem::Cylinder{Vector3d(0.03, 0.005, -0.01), Vector3d(0, 0, 0.03), 0.02});
  const auto msg = invalid_input_message([&] { (void)fem::mesh_geometry(g); });
  EXPECT_CONTAINS(msg, "bodies[2] \"right\" vanished");
}

TEST(FemGeometry, MissingOrFailingGmsh) {
  const auto g = two_boxes();
  fem::MeshOptions options;
  options.gmsh = "asperity-no-such-gmsh";
  auto msg = invalid_input_message([&] { (void)fem::mesh_geometry(g, options); });
  EXPECT_CONTAINS(msg, "not found on PATH: install the gmsh program: apt-get install gmsh");
  options.gmsh = "/nonexistent/gmsh";
  msg = invalid_input_message([&] { (void)fem::mesh_geometry(g, options); });
  EXPECT_CONTAINS(msg, "install the gmsh program: apt-get install gmsh");
  // A stand-in gmsh that fails as gmsh does: its last error lines reach the message.
  const TempDir dir;
  const auto fake = dir.write("fake-gmsh",
                              "#!/bin/sh\necho 'Info    : Reading' \n"
                              "echo 'Error   : OpenCASCADE exception' >&2\nexit 1\n");
  chmod(fake.c_str(), 0755);
  options.gmsh = fake;
  msg = invalid_input_message([&] { (void)fem::mesh_geometry(g, options); });
  EXPECT_CONTAINS(msg, "gmsh failed to mesh the geometry (exit status 1)");
  EXPECT_CONTAINS(msg, "Error   : OpenCASCADE exception");
  // A gmsh that hangs is killed at the time limit.
  const auto slow = dir.write("slow-gmsh", "#!/bin/sh\nexec sleep 30\n");
  chmod(slow.c_str(), 0755);
  options.gmsh = slow;
  options.time_limit = 0.5;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW((void)fem::mesh_geometry(g, options), NumericalError);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  options.time_limit = 600;
  options.work_dir = fake + "/sub";  // under a regular file: cannot be created
  EXPECT_CONTAINS(invalid_input_message([&] { (void)fem::mesh_geometry(g, options); }),
                  "mesh options: work_dir");
  options.work_dir.clear();
  options.threads = 0;
  EXPECT_CONTAINS(invalid_input_message([&] { (void)fem::mesh_geometry(g, options); }),
                  "threads = 0 is not allowed");
}

}  // namespace
