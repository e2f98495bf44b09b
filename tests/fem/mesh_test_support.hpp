#pragma once
// Geometric checks of quadratic meshes shared by the fem mesh tests.
#include <gtest/gtest.h>

#include <unistd.h>
#include <array>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include <Eigen/Dense>

#include "asperity/core/error.hpp"
#include "asperity/fem/mesh.hpp"

namespace asperity::testing {

/// The canonical edges (corner pairs) of mesh.hpp: mid-edge node 4 + i (tet10) or 8 + i
/// (hex20) lies on edge i.
inline constexpr std::array<std::array<int, 2>, 6> kTet10Edges = {
    {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};
inline constexpr std::array<std::array<int, 2>, 12> kHex20Edges = {{{0, 1},
                                                                    {1, 2},
                                                                    {2, 3},
                                                                    {3, 0},
                                                                    {4, 5},
                                                                    {5, 6},
                                                                    {6, 7},
                                                                    {7, 4},
                                                                    {0, 4},
                                                                    {1, 5},
                                                                    {2, 6},
                                                                    {3, 7}}};

inline Eigen::Vector3d node(const fem::Mesh& m, std::int32_t i) {
  return m.nodes.col(i);
}

/// Largest |mid-edge node - mean of its corners| over the elements of `m` whose edges are
/// straight (all of them for a mesh of plane faces).
inline double max_mid_edge_offset(const fem::Mesh& m) {
  double worst = 0.0;
  for (const auto& block : m.blocks) {
    const bool tet = block.type == fem::ElementType::tet10;
    for (std::size_t e = 0; e < block.size(); ++e) {
      const auto el = block.element(e);
      const std::size_t edges = tet ? 6 : 12;
      for (std::size_t i = 0; i < edges; ++i) {
        const auto [a, b] = tet ? kTet10Edges[i] : kHex20Edges[i];
        const auto mid = el[(tet ? 4 : 8) + i];
        const Eigen::Vector3d mean = 0.5 * (node(m, el[static_cast<std::size_t>(a)]) +
                                            node(m, el[static_cast<std::size_t>(b)]));
        worst = std::max(worst, (node(m, mid) - mean).norm());
      }
    }
  }
  return worst;
}

/// Signed volume of the straight-sided tetrahedron of corners a, b, c, d.
inline double tet_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

/// Signed volume of element e from its corners (straight-sided; a hexahedron with plane
/// faces split into six tetrahedra around its diagonal 0-6). Positive when the corners
/// follow the canonical orientation (VTK: face 0-1-2(-3) seen from node 3 (4) anticlockwise).
inline double element_volume(const fem::Mesh& m, const fem::ElementBlock& block, std::size_t e) {
  const auto el = block.element(e);
  const auto p = [&](std::size_t k) { return node(m, el[k]); };
  if (block.type == fem::ElementType::tet10) return tet_volume(p(0), p(1), p(2), p(3));
  return tet_volume(p(0), p(1), p(2), p(6)) + tet_volume(p(0), p(2), p(3), p(6)) +
         tet_volume(p(0), p(3), p(7), p(6)) + tet_volume(p(0), p(7), p(4), p(6)) +
         tet_volume(p(0), p(4), p(5), p(6)) + tet_volume(p(0), p(5), p(1), p(6));
}

/// Volume of the elements of body `body` (-1: all) and the smallest element volume.
inline std::pair<double, double> body_volume(const fem::Mesh& m, int body = -1) {
  double total = 0.0;
  double smallest = 1e300;
  for (const auto& block : m.blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      if (body >= 0 && block.body[e] != body) continue;
      const double v = element_volume(m, block, e);
      total += v;
      smallest = std::min(smallest, v);
    }
  }
  return {total, smallest};
}

inline std::size_t element_total(const fem::Mesh& m) {
  std::size_t n = 0;
  for (const auto& block : m.blocks) n += block.size();
  return n;
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A file in a private temporary directory, removed with it.
class TempDir {
 public:
  TempDir() {
    std::string templ = (std::filesystem::temp_directory_path() / "asperity-fem-XXXXXX").string();
    if (mkdtemp(templ.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = templ;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  /// Writes `text` to `name` and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const auto p = file(name);
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace asperity::testing
