// fem/mesh_io.hpp: gmsh MSH 4.1/2.2 and Abaqus .inp readers (node order checked
// geometrically: a straight edge's mid node is the mean of its corners), VTU and MSH
// writers, and the refusals of bad files.
#include "asperity/fem/mesh_io.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "../support.hpp"
#include "asperity/core/error.hpp"
#include "mesh_test_support.hpp"

namespace {

using asperity::InvalidInput;
using asperity::testing::body_volume;
using asperity::testing::element_total;
using asperity::testing::invalid_input_message;
using asperity::testing::max_mid_edge_offset;
using asperity::testing::slurp;
using asperity::testing::TempDir;
namespace fem = asperity::fem;

const std::string kData = std::string(ASPERITY_TEST_DATA_DIR) + "/fem/";

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

// Mid-edge nodes are within this distance of the mean of their corners on plane faces:
// gmsh writes coordinates with 16 significant digits, so a few ulps of 0.03 m.
constexpr double kStraight = 1e-15;

// The nodes whose coordinate `axis` equals `value` (exactly, as gmsh places them on the
// plane face of a box).
std::vector<std::int32_t> nodes_on_plane(const fem::Mesh& m, int axis, double value) {
  std::vector<std::int32_t> on;
  for (Eigen::Index j = 0; j < m.nodes.cols(); ++j) {
    if (std::abs(m.nodes(axis, j) - value) <= 1e-15) on.push_back(static_cast<std::int32_t>(j));
  }
  return on;
}

void expect_box_tet10(const fem::Mesh& m) {
  ASSERT_EQ(m.blocks.size(), 1u);
  EXPECT_EQ(m.blocks[0].type, fem::ElementType::tet10);
  ASSERT_EQ(m.bodies, std::vector<std::string>{"block"});
  EXPECT_LE(max_mid_edge_offset(m), kStraight);
  // The elements fill the 20 x 10 x 30 mm box of box_tet10.geo: their volumes (each
  // positive: the canonical orientation) sum to its volume, to rounding (relative 1e-12:
  // ~100 elements of coordinates with 16 digits).
  const auto [volume, smallest] = body_volume(m);
  EXPECT_GT(smallest, 0.0);
  EXPECT_NEAR(volume, 0.02 * 0.01 * 0.03, 1e-12 * 0.02 * 0.01 * 0.03);
  // Every node is used by an element (the reader drops unused ones): no column is unused.
  std::vector<bool> used(static_cast<std::size_t>(m.nodes.cols()), false);
  for (const auto n : m.blocks[0].connectivity) used[static_cast<std::size_t>(n)] = true;
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
  // The physical surface "bottom" (z = 0) holds exactly the nodes on that plane.
  ASSERT_EQ(m.node_sets.count("bottom"), 1u);
  EXPECT_EQ(m.node_sets.at("bottom"), nodes_on_plane(m, 2, 0.0));
  EXPECT_GE(m.node_sets.at("bottom").size(), 6u);  // a quadratic triangle at least
  ASSERT_EQ(m.element_sets.count("block"), 1u);
  EXPECT_EQ(m.element_sets.at("block").size(), m.blocks[0].size());
}

TEST(FemMeshIo, GmshTet10Version41) {
  expect_box_tet10(fem::read_gmsh(kData + "box_tet10_v41.msh"));
}

TEST(FemMeshIo, GmshTet10Version22) {
  expect_box_tet10(fem::read_gmsh(kData + "box_tet10_v22.msh"));
}

TEST(FemMeshIo, GmshVersionsGiveTheSameMesh) {
  // The same gmsh mesh saved in both formats: same nodes, same elements, same order.
  const auto a = fem::read_gmsh(kData + "box_tet10_v41.msh");
  const auto b = fem::read_gmsh(kData + "box_tet10_v22.msh");
  ASSERT_EQ(a.nodes.cols(), b.nodes.cols());
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.blocks[0].connectivity, b.blocks[0].connectivity);
  EXPECT_EQ(a.node_sets, b.node_sets);
}

void expect_hex20(const fem::Mesh& m) {
  ASSERT_EQ(m.blocks.size(), 1u);
  EXPECT_EQ(m.blocks[0].type, fem::ElementType::hex20);
  // hex20.geo: 3 points per edge of the box (transfinite): 2 x 2 x 2 elements; nodes:
  // 3^3 corners of the grid + 3 * (2 * 3 * 3) = 54 edge mid nodes.
  EXPECT_EQ(m.blocks[0].size(), 8u);
  EXPECT_EQ(m.nodes.cols(), 27 + 54);
  EXPECT_LE(max_mid_edge_offset(m), kStraight);
  const auto [volume, smallest] = body_volume(m);
  EXPECT_GT(smallest, 0.0);
  EXPECT_NEAR(volume, 0.02 * 0.01 * 0.01, 1e-12 * 0.02 * 0.01 * 0.01);
  // Each hexahedron is a 10 x 5 x 5 mm brick.
  EXPECT_NEAR(smallest, 0.01 * 0.005 * 0.005, 1e-12 * 0.01 * 0.005 * 0.005);
  EXPECT_EQ(m.node_sets.at("x0"), nodes_on_plane(m, 0, 0.0));
  EXPECT_EQ(m.node_sets.at("x0").size(), 21u);  // 5 x 5 grid of a quadratic face less 4 centres
  EXPECT_EQ(m.bodies, std::vector<std::string>{"bar"});
}

TEST(FemMeshIo, GmshHex20BothVersions) {
  expect_hex20(fem::read_gmsh(kData + "hex20_v41.msh"));
  expect_hex20(fem::read_gmsh(kData + "hex20_v22.msh"));
}

TEST(FemMeshIo, GmshWithoutPhysicalGroupsOneBodyPerVolume) {
  const auto m = fem::read_gmsh(kData + "two_boxes_v41.msh");
  ASSERT_EQ(m.bodies, (std::vector<std::string>{"volume 1", "volume 2"}));
  // Each body is one 10 mm cube (relative 1e-12: rounding of the coordinates).
  for (int b = 0; b < 2; ++b) {
    EXPECT_NEAR(body_volume(m, b).first, 1e-6, 1e-18) << "body " << b;
  }
  // Conforming at the shared face x = 10 mm: every node there is used by both bodies.
  std::vector<std::set<int>> bodies_of(static_cast<std::size_t>(m.nodes.cols()));
  const auto& block = m.blocks[0];
  for (std::size_t e = 0; e < block.size(); ++e) {
    for (const auto n : block.element(e))
      bodies_of[static_cast<std::size_t>(n)].insert(block.body[e]);
  }
  const auto shared = nodes_on_plane(m, 0, 0.01);
  EXPECT_GE(shared.size(), 6u);
  for (const auto n : shared) EXPECT_EQ(bodies_of[static_cast<std::size_t>(n)].size(), 2u) << n;
  EXPECT_TRUE(m.node_sets.empty());
}

// --- refusals ----------------------------------------------------------------------

std::string read_msg(const std::string& path) {
  return invalid_input_message([&] { (void)fem::read_gmsh(path); });
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(FemMeshIo, GmshRefusesBinaryAndOtherVersions) {
  const TempDir dir;
  const std::string good = slurp(kData + "box_tet10_v41.msh");
  auto msg = read_msg(dir.write("bin.msh", replaced(good, "4.1 0 8", "4.1 1 8")));
  EXPECT_CONTAINS(msg, "bin.msh, line 2: binary MSH files are not read");
  msg = read_msg(dir.write("v40.msh", replaced(good, "4.1 0 8", "4 0 8")));
  EXPECT_CONTAINS(msg, "v40.msh, line 2: MSH version 4 is not read");
  msg = read_msg(dir.write("v1.msh", "$NOD\n1\n1 0 0 0\n$ENDNOD\n"));
  EXPECT_CONTAINS(msg, "MSH version 1 is not read");
  msg = read_msg(dir.write("text.msh", "solid cube\n"));
  EXPECT_CONTAINS(msg, "not a gmsh MSH file");
  msg = read_msg(kData + "does-not-exist.msh");
  EXPECT_CONTAINS(msg, "does-not-exist.msh");
}

TEST(FemMeshIo, GmshRefusesLinearElements) {
  const auto msg = read_msg(kData + "box_tet4_v41.msh");
  EXPECT_CONTAINS(msg, "linear elements (gmsh type 4, 4-node tetrahedron): mesh with -order 2");
  EXPECT_CONTAINS(msg, "box_tet4_v41.msh, line ");
}

TEST(FemMeshIo, GmshRefusesTruncatedFiles) {
  const TempDir dir;
  for (const char* version : {"v41", "v22"}) {
    const std::string good = slurp(kData + "box_tet10_" + version + ".msh");
    // Cut inside $Nodes, inside $Elements, and just before $EndElements.
    for (const auto& [marker, extra] : {std::pair<std::string, std::size_t>{"$Nodes", 40},
                                        {"$Elements", 60},
                                        {"$EndElements", 0}}) {
      const auto at = good.find(marker) + extra;
      const auto msg = read_msg(dir.write("cut.msh", good.substr(0, at)));
      EXPECT_CONTAINS(msg, "truncated?") << version << " cut after " << marker;
    }
  }
}

TEST(FemMeshIo, GmshRefusesUndefinedNodes) {
  const TempDir dir;
  // The last element line of the 2.2 file with its last node tag replaced by one that
  // does not exist.
  std::string text = slurp(kData + "box_tet10_v22.msh");
  const auto end = text.find("\n$EndElements");
  const auto last_space = text.rfind(' ', end);
  text.replace(last_space + 1, end - last_space - 1, "99999");
  const auto msg = read_msg(dir.write("bad-node.msh", text));
  EXPECT_CONTAINS(msg, "refers to node 99999, which is not defined");
  EXPECT_CONTAINS(msg, "bad-node.msh, line ");
}

TEST(FemMeshIo, GmshRefusesWrongCountsAndNodeCounts) {
  const TempDir dir;
  const std::string good = slurp(kData + "box_tet10_v22.msh");
  // An element line missing one node tag.
  const auto end = good.find("\n$EndElements");
  const auto last_space = good.rfind(' ', end);
  auto msg = read_msg(dir.write("short.msh", good.substr(0, last_space) + good.substr(end)));
  EXPECT_CONTAINS(msg, "has 9 node tags, a 10-node tetrahedron has 10");
  // A count that announces one node more than the section holds.
  const auto nodes_at = good.find("$Nodes\n") + 7;
  const auto eol = good.find('\n', nodes_at);
  const auto count = std::stoll(good.substr(nodes_at, eol - nodes_at));
  std::string more = good;
  more.replace(nodes_at, eol - nodes_at, std::to_string(count + 1));
  msg = read_msg(dir.write("count.msh", more));
  EXPECT_CONTAINS(msg, "count.msh, line ");
}

// --- Abaqus ---------------------------------------------------------------------------

std::string inp_msg(const std::string& path) {
  return invalid_input_message([&] { (void)fem::read_abaqus_inp(path); });
}

TEST(FemMeshIo, AbaqusC3D10CubeWithSets) {
  const auto m = fem::read_abaqus_inp(kData + "cube_c3d10.inp");
  // Five tetrahedra in a cube use its 12 edges and its 6 face diagonals: 8 corner nodes
  // and 18 mid-edge nodes (node 999, used by no element, is left out).
  EXPECT_EQ(m.nodes.cols(), 8 + 18);
  ASSERT_EQ(m.blocks.size(), 1u);
  EXPECT_EQ(m.blocks[0].size(), 5u);
  EXPECT_EQ(m.bodies, (std::vector<std::string>{"Steel", "CORE"}));
  EXPECT_EQ(m.blocks[0].body, (std::vector<std::int32_t>{0, 0, 0, 0, 1}));
  EXPECT_LE(max_mid_edge_offset(m), kStraight);
  // The corner tetrahedra are 1/6 of the cube each, the central one 1/3 (relative 1e-14:
  // coordinates of 0.01 m written with 17 digits).
  const double cube = 1e-6;
  EXPECT_NEAR(body_volume(m, 0).first, 4 * cube / 6, 1e-14 * cube);
  EXPECT_NEAR(body_volume(m, 1).first, cube / 3, 1e-14 * cube);
  EXPECT_GT(body_volume(m).second, 0.0);
  // Node 999 (at (1, 1, 1) m) is used by no element: left out, also from ALLNODES.
  for (Eigen::Index j = 0; j < m.nodes.cols(); ++j) EXPECT_LE(m.nodes.col(j).maxCoeff(), 0.01);
  EXPECT_EQ(m.node_sets.at("ALLNODES").size(), static_cast<std::size_t>(m.nodes.cols()));
  // Bottom: every node on z = 0; CORNERS (GENERATE 1..8): the nodes at the cube's
  // corners; the set naming Bottom plus node 8 (the corner (1, 1, 1) cm).
  EXPECT_EQ(m.node_sets.at("Bottom"), nodes_on_plane(m, 2, 0.0));
  const auto& corners = m.node_sets.at("CORNERS");
  ASSERT_EQ(corners.size(), 8u);
  for (const auto n : corners) {
    for (int c = 0; c < 3; ++c) {
      const double x = m.nodes(c, n);
      EXPECT_TRUE(x == 0.0 || x == 0.01) << n;
    }
  }
  const auto& both = m.node_sets.at("BOTTOM_AND_TOP_CORNER");
  EXPECT_EQ(both.size(), m.node_sets.at("Bottom").size() + 1);
  EXPECT_EQ(m.node_sets.count("BOTTOM"), 0u);  // names keep their first spelling
  // Element sets: ELSET= of *ELEMENT, GENERATE, a list.
  EXPECT_EQ(m.element_sets.at("Steel").size(), 4u);
  EXPECT_EQ(m.element_sets.at("CORE"), (std::vector<std::array<std::int32_t, 2>>{{0, 4}}));
  EXPECT_EQ(m.element_sets.at("ALL").size(), 5u);
  EXPECT_EQ(m.element_sets.at("ODD"),
            (std::vector<std::array<std::int32_t, 2>>{{0, 0}, {0, 2}, {0, 4}}));
}

TEST(FemMeshIo, AbaqusC3D20RPartAndInstance) {
  const auto m = fem::read_abaqus_inp(kData + "block_c3d20r.inp");
  ASSERT_EQ(m.blocks.size(), 1u);
  EXPECT_EQ(m.blocks[0].type, fem::ElementType::hex20);
  EXPECT_EQ(m.bodies, std::vector<std::string>{"Block"});  // the part's name
  EXPECT_EQ(m.nodes.cols(), 20);  // the assembly's reference node is not the part's
  EXPECT_LE(max_mid_edge_offset(m), kStraight);
  const double v = 0.01 * 0.02 * 0.03;
  EXPECT_NEAR(body_volume(m).first, v, 1e-14 * v);  // a rigid motion keeps the volume
  // Translated by (0.1, 0, 0) m, then turned by 90 degrees about the z line through
  // (0.1, 0): the 10 x 20 mm section now spans x in [0.08, 0.1], y in [0, 0.01].
  const Eigen::Vector3d lo = m.nodes.rowwise().minCoeff();
  const Eigen::Vector3d hi = m.nodes.rowwise().maxCoeff();
  EXPECT_NEAR(lo.x(), 0.08, 1e-15);
  EXPECT_NEAR(hi.x(), 0.10, 1e-15);
  EXPECT_NEAR(lo.y(), 0.0, 1e-15);
  EXPECT_NEAR(hi.y(), 0.01, 1e-15);
  EXPECT_NEAR(hi.z(), 0.03, 1e-15);
  EXPECT_EQ(m.node_sets.at("Base").size(), 8u);
  EXPECT_EQ(m.node_sets.count("RP"), 0u);  // an assembly-level set of the reference node
  ASSERT_EQ(m.node_sets.at("Corner").size(), 1u);
}

TEST(FemMeshIo, AbaqusRefusals) {
  const TempDir dir;
  const std::string cube = slurp(kData + "cube_c3d10.inp");
  const std::string block = slurp(kData + "block_c3d20r.inp");
  auto msg = inp_msg(dir.write("lin.inp", replaced(cube, "TYPE=C3D10", "TYPE=C3D8R")));
  EXPECT_CONTAINS(msg, "TYPE=C3D8R is a linear element: quadratic elements are needed");
  EXPECT_CONTAINS(msg, "lin.inp, line ");
  msg = inp_msg(dir.write("shell.inp", replaced(cube, "TYPE=C3D10", "TYPE=S4R")));
  EXPECT_CONTAINS(msg, "element type S4R is not read");
  msg = inp_msg(dir.write("two.inp", replaced(block, "*End Instance\n",
                                              "*End Instance\n*Instance, name=Block-2, "
                                              "part=Block\n*End Instance\n")));
  EXPECT_CONTAINS(msg, "more than one instance (\"Block-1\" and \"Block-2\")");
  msg = inp_msg(dir.write("parts.inp",
                          replaced(block, "*Assembly", "*Part, name=Other\n*End Part\n*Assembly")));
  EXPECT_CONTAINS(msg, "a second *PART (\"Other\"): only single-part files are read");
  msg = inp_msg(
      dir.write("inc.inp", replaced(cube, "*Heading", "*INCLUDE, INPUT=nodes.inp\n*Heading")));
  EXPECT_CONTAINS(msg, "inc.inp, line 1: *INCLUDE is not read");
  msg = inp_msg(dir.write("node.inp", replaced(cube, "5, 5, 3, 2, 8,", "5, 5, 3, 2, 88,")));
  EXPECT_CONTAINS(msg, "element 5 refers to node 88, which is not defined");
  msg = inp_msg(dir.write("set.inp", replaced(cube, "1, 3, 5\n", "1, 3, 7\n")));
  EXPECT_CONTAINS(msg, "element set \"ODD\" names element 7, which is not defined");
  msg = inp_msg(dir.write("dup.inp", replaced(cube, "999, 1, 1, 1", "1, 1, 1, 1")));
  EXPECT_CONTAINS(msg, "node 1 is defined twice");
  msg = inp_msg(dir.write("short.inp", replaced(cube, ", 110, 115\n*Nset", "\n*Nset")));
  EXPECT_CONTAINS(msg, "element 5 has 8 nodes, TYPE=C3D10 has 10");
  msg = inp_msg(dir.write("name.inp", replaced(cube, "bottom, 8", "bottum, 8")));
  EXPECT_CONTAINS(msg, "\"bottum\" is neither a label nor a defined node set");
  msg = inp_msg(dir.write("gen.inp", replaced(cube, "1, 8, 1", "1, 100000000, 1")));
  EXPECT_CONTAINS(msg, "GENERATE 1, 100000000, 1 lists more labels than the file can define");
  msg = inp_msg(dir.write("empty.inp", "*HEADING\n"));
  EXPECT_CONTAINS(msg, "the file has no elements");
}

TEST(FemMeshIo, DamagedFilesGiveInvalidInputOnly) {
  // Deterministic damage to every test file (a cut at a random byte, or a few bytes
  // replaced by characters that matter to the parsers): each read either succeeds or
  // throws InvalidInput; never another exception, a crash or a hang (run under ASan by
  // scripts/test.sh).
  const TempDir dir;
  std::mt19937 rng(19);
  const std::string alphabet = "0123456789 -+.eE,*$\n\"";
  for (const char* name :
       {"box_tet10_v41.msh", "box_tet10_v22.msh", "hex20_v41.msh", "hex20_v22.msh",
        "two_boxes_v41.msh", "cube_c3d10.inp", "block_c3d20r.inp"}) {
    const std::string good = slurp(kData + name);
    const bool inp = std::string(name).find(".inp") != std::string::npos;
    for (int trial = 0; trial < 150; ++trial) {
      std::string bad = good;
      if (trial % 3 == 0) {
        bad.resize(std::uniform_int_distribution<std::size_t>(0, good.size() - 1)(rng));
      } else {
        for (int k = 0; k < 1 + trial % 4; ++k) {
          const auto at = std::uniform_int_distribution<std::size_t>(0, bad.size() - 1)(rng);
          bad[at] =
              alphabet[std::uniform_int_distribution<std::size_t>(0, alphabet.size() - 1)(rng)];
        }
      }
      const auto path = dir.write(inp ? "bad.inp" : "bad.msh", bad);
      try {
        if (inp) {
          (void)fem::read_abaqus_inp(path);
        } else {
          (void)fem::read_gmsh(path);
        }
      } catch (const InvalidInput&) {
      } catch (const std::exception& e) {
        ADD_FAILURE() << name << " trial " << trial << ": " << e.what();
      }
    }
  }
}

// --- writers -------------------------------------------------------------------------

TEST(FemMeshIo, GmshWriterRoundTrips) {
  const TempDir dir;
  for (const char* name : {"box_tet10_v41.msh", "hex20_v41.msh", "two_boxes_v41.msh"}) {
    const auto m = fem::read_gmsh(kData + name);
    const auto path = dir.file("out.msh");
    fem::write_gmsh(path, m);
    const auto back = fem::read_gmsh(path);
    EXPECT_EQ(back.nodes, m.nodes) << name;  // shortest round-trip decimal forms
    ASSERT_EQ(back.blocks.size(), m.blocks.size()) << name;
    EXPECT_EQ(back.bodies, m.bodies) << name;
    // The writer groups elements by body; within a body the order is kept.
    for (std::size_t k = 0; k < m.blocks.size(); ++k) {
      std::vector<std::pair<std::int32_t, std::vector<std::int32_t>>> a;
      std::vector<std::pair<std::int32_t, std::vector<std::int32_t>>> b;
      for (std::size_t e = 0; e < m.blocks[k].size(); ++e) {
        const auto el = m.blocks[k].element(e);
        a.emplace_back(m.blocks[k].body[e], std::vector<std::int32_t>(el.begin(), el.end()));
      }
      for (std::size_t e = 0; e < back.blocks[k].size(); ++e) {
        const auto el = back.blocks[k].element(e);
        b.emplace_back(back.blocks[k].body[e], std::vector<std::int32_t>(el.begin(), el.end()));
      }
      std::stable_sort(a.begin(), a.end(),
                       [](const auto& x, const auto& y) { return x.first < y.first; });
      EXPECT_EQ(a, b) << name;
    }
  }
}

TEST(FemMeshIo, VtuHasEveryCellPointAndField) {
  const TempDir dir;
  const auto m = fem::read_gmsh(kData + "two_boxes_v41.msh");
  const auto n = m.nodes.cols();
  fem::PointField u{"displacement", Eigen::MatrixXd(3, n)};
  fem::PointField p{"pressure <Pa>", Eigen::MatrixXd(1, n)};
  for (Eigen::Index j = 0; j < n; ++j) {
    u.values.col(j) = 1e-6 * m.nodes.col(j);
    p.values(0, j) = static_cast<double>(j);
  }
  const auto path = dir.file("mesh.vtu");
  fem::write_vtu(path, m, {u, p});
  const auto text = slurp(path);
  const auto cells = element_total(m);
  EXPECT_CONTAINS(text, fmt::format("NumberOfPoints=\"{}\" NumberOfCells=\"{}\"", n, cells));
  EXPECT_CONTAINS(text, "Name=\"displacement\" NumberOfComponents=\"3\"");
  EXPECT_CONTAINS(text, "Name=\"pressure &lt;Pa&gt;\" NumberOfComponents=\"1\"");
  EXPECT_CONTAINS(text, "Name=\"body\"");
  // Cell types: one "24" line per tetrahedron in the types array.
  const auto types_at = text.find("Name=\"types\"");
  ASSERT_NE(types_at, std::string::npos);
  const auto types_end = text.find("</DataArray>", types_at);
  std::istringstream types(
      text.substr(text.find('\n', types_at) + 1, types_end - text.find('\n', types_at) - 1));
  std::size_t count = 0;
  int t = 0;
  while (types >> t) {
    EXPECT_EQ(t, 24);
    ++count;
  }
  EXPECT_EQ(count, cells);
  // The last offset is 10 nodes per cell.
  EXPECT_CONTAINS(text, fmt::format("\n{}\n        </DataArray>\n        <DataArray type=\"UInt8\"",
                                    10 * cells));
}

TEST(FemMeshIo, VtuRefusesBadFieldsAndWritesNothing) {
  const TempDir dir;
  const auto m = fem::read_gmsh(kData + "hex20_v41.msh");
  const auto n = m.nodes.cols();
  const auto path = dir.file("bad.vtu");
  const auto msg = [&](fem::PointField f) {
    return invalid_input_message([&] { fem::write_vtu(path, m, {f}); });
  };
  EXPECT_CONTAINS(msg({"", Eigen::MatrixXd::Zero(1, n)}),
                  "point field 0 (\"\"): the name is empty");
  EXPECT_CONTAINS(msg({"s", Eigen::MatrixXd::Zero(2, n)}), "\"s\"): 2 rows (components); 1 or 3");
  EXPECT_CONTAINS(msg({"s", Eigen::MatrixXd::Zero(1, n - 1)}), "one per node (81) is needed");
  Eigen::MatrixXd nan = Eigen::MatrixXd::Zero(3, n);
  nan(1, 5) = std::nan("");
  EXPECT_CONTAINS(msg({"u", nan}), "the value at node 5, component 1 is nan");
  const auto twice = invalid_input_message([&] {
    fem::write_vtu(path, m,
                   {{"a", Eigen::MatrixXd::Zero(1, n)}, {"a", Eigen::MatrixXd::Zero(1, n)}});
  });
  EXPECT_CONTAINS(twice, "point field 1 (\"a\"): another field has the same name");
  EXPECT_FALSE(std::filesystem::exists(path));
  // A path in a directory that does not exist: refused, nothing written.
  const auto nowhere =
      invalid_input_message([&] { fem::write_vtu(dir.file("no/dir/m.vtu"), m, {}); });
  EXPECT_CONTAINS(nowhere, "no/dir/m.vtu");
}

}  // namespace
