// Structured box meshes (structured.hpp).
#include "asperity/fem/structured.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/fem/elasticity.hpp"
#include "element_detail.hpp"

namespace asperity::fem {

namespace {

// Kuhn's 6 tetrahedra of the unit cube: vertex paths 0 -> e_p0 -> e_p0 + e_p1 -> (1,1,1)
// for the permutations p, with the sign of p (an odd one has its vertices 1 and 2
// swapped for a positive volume).
constexpr int kPermutations[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                     {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};

}  // namespace

Mesh structured_box_mesh(const Eigen::Vector3d& corner, const Eigen::Vector3d& size,
                         std::array<int, 3> divisions, ElementType type, std::string body) {
  for (int c = 0; c < 3; ++c) {
    core::require_finite(fmt::format("corner[{}]", c), corner[c]);
    core::require_positive(fmt::format("size[{}]", c), size[c]);
    if (divisions[static_cast<std::size_t>(c)] < 1 ||
        divisions[static_cast<std::size_t>(c)] > 2000) {
      throw InvalidInput(
          fmt::format("divisions[{}] = {} is not allowed: it must be an integer "
                      "from 1 to 2000",
                      c, divisions[static_cast<std::size_t>(c)]));
    }
  }
  // Points of the grid of half cells: g = (i, j, k), 0 <= i <= 2 divisions[0], ...
  const std::array<std::int64_t, 3> points = {2 * std::int64_t{divisions[0]} + 1,
                                              2 * std::int64_t{divisions[1]} + 1,
                                              2 * std::int64_t{divisions[2]} + 1};
  const std::int64_t grid_size = points[0] * points[1] * points[2];
  if (grid_size > std::int64_t{1} << 30) {
    throw InvalidInput(fmt::format("divisions {} x {} x {} make too many nodes for 32-bit indices",
                                   divisions[0], divisions[1], divisions[2]));
  }
  const auto grid = [&](std::array<std::int64_t, 3> g) {
    return g[0] + points[0] * (g[1] + points[1] * g[2]);
  };

  Mesh mesh;
  mesh.bodies.push_back(std::move(body));
  ElementBlock block;
  block.type = type;
  std::vector<std::int64_t> element_grid_nodes;
  const Eigen::Matrix3Xd natural = natural_node_coordinates(type);
  for (std::int64_t iz = 0; iz < divisions[2]; ++iz) {
    for (std::int64_t iy = 0; iy < divisions[1]; ++iy) {
      for (std::int64_t ix = 0; ix < divisions[0]; ++ix) {
        const std::array<std::int64_t, 3> base = {2 * ix, 2 * iy, 2 * iz};
        if (type == ElementType::hex20) {
          for (Eigen::Index a = 0; a < natural.cols(); ++a) {
            std::array<std::int64_t, 3> g{};
            for (int c = 0; c < 3; ++c) {
              g[static_cast<std::size_t>(c)] =
                  base[static_cast<std::size_t>(c)] + 1 + std::llround(natural(c, a));
            }
            element_grid_nodes.push_back(grid(g));
          }
          block.body.push_back(0);
          continue;
        }
        for (const auto& p : kPermutations) {
          std::array<std::array<std::int64_t, 3>, 4> v{};
          v[0] = base;
          v[1] = v[0];
          v[1][static_cast<std::size_t>(p[0])] += 2;
          v[2] = v[1];
          v[2][static_cast<std::size_t>(p[1])] += 2;
          v[3] = v[2];
          v[3][static_cast<std::size_t>(p[2])] += 2;
          const bool odd = (&p - &kPermutations[0]) >= 3;
          if (odd) std::swap(v[1], v[2]);
          for (const auto& vertex : v) element_grid_nodes.push_back(grid(vertex));
          for (const auto& edge : detail::kTetEdges) {
            std::array<std::int64_t, 3> mid{};
            for (std::size_t c = 0; c < 3; ++c) {
              mid[c] = (v[static_cast<std::size_t>(edge[0])][c] +
                        v[static_cast<std::size_t>(edge[1])][c]) /
                       2;
            }
            element_grid_nodes.push_back(grid(mid));
          }
          block.body.push_back(0);
        }
      }
    }
  }
  // Number the grid points the elements use, in grid order.
  std::vector<std::int32_t> number(static_cast<std::size_t>(grid_size), -1);
  for (const auto g : element_grid_nodes) number[static_cast<std::size_t>(g)] = 0;
  std::int32_t count = 0;
  for (auto& id : number) {
    if (id == 0) id = count++;
  }
  mesh.nodes.resize(3, count);
  static const char* kFaces[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  for (std::int64_t k = 0; k < points[2]; ++k) {
    for (std::int64_t j = 0; j < points[1]; ++j) {
      for (std::int64_t i = 0; i < points[0]; ++i) {
        const std::int32_t id = number[static_cast<std::size_t>(grid({i, j, k}))];
        if (id < 0) continue;
        const std::array<std::int64_t, 3> g = {i, j, k};
        for (std::size_t c = 0; c < 3; ++c) {
          const auto ci = static_cast<Eigen::Index>(c);
          const double fraction = static_cast<double>(g[c]) / static_cast<double>(points[c] - 1);
          // The far face exactly at corner + size.
          mesh.nodes(ci, id) =
              g[c] == points[c] - 1 ? corner[ci] + size[ci] : corner[ci] + size[ci] * fraction;
          if (g[c] == 0) mesh.node_sets[kFaces[c][0]].push_back(id);
          if (g[c] == points[c] - 1) mesh.node_sets[kFaces[c][1]].push_back(id);
        }
      }
    }
  }
  block.connectivity.reserve(element_grid_nodes.size());
  for (const auto g : element_grid_nodes) {
    block.connectivity.push_back(number[static_cast<std::size_t>(g)]);
  }
  mesh.blocks.push_back(std::move(block));
  return mesh;
}

}  // namespace asperity::fem
