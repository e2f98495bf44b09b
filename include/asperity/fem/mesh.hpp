#pragma once
// A solid finite-element mesh of one or more elastic bodies (SI: m). Node indices are
// 0-based everywhere in the library (readers convert from the 1-based files). Element
// nodes follow one canonical order per type, whatever the file's order:
//   tet10: corners 0-3, then the mid-edge nodes 4 (0-1), 5 (1-2), 6 (2-0), 7 (0-3),
//          8 (1-3), 9 (2-3)  (Abaqus C3D10 and VTK_QUADRATIC_TETRA order);
//   hex20: Abaqus C3D20 / VTK_QUADRATIC_HEXAHEDRON order (corners 0-7, mid-edges of the
//          bottom face 8-11, of the top face 12-15, vertical edges 16-19).
#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace asperity::fem {

enum class ElementType { tet10, hex20 };

/// Nodes of one element of `type` (10 or 20).
[[nodiscard]] constexpr int nodes_per_element(ElementType type) {
  return type == ElementType::tet10 ? 10 : 20;
}
[[nodiscard]] const char* element_type_name(ElementType type);

/// Quadratic solid elements of one type.
struct ElementBlock {
  ElementType type = ElementType::tet10;
  /// nodes_per_element(type) node indices per element, element after element.
  std::vector<std::int32_t> connectivity;
  /// The body (index into Mesh::bodies) of each element.
  std::vector<std::int32_t> body;

  [[nodiscard]] std::size_t size() const { return body.size(); }
  [[nodiscard]] std::span<const std::int32_t> element(std::size_t e) const {
    const auto n = static_cast<std::size_t>(nodes_per_element(type));
    return {connectivity.data() + e * n, n};
  }
};

struct Mesh {
  Eigen::Matrix3Xd nodes;            ///< [m], one column per node
  std::vector<ElementBlock> blocks;  ///< at most one block per element type
  std::vector<std::string> bodies;   ///< names; each element belongs to one
  /// Named node sets (0-based node indices) and element sets (pairs block, element),
  /// from the file's physical groups (gmsh) or *NSET / *ELSET (Abaqus).
  std::map<std::string, std::vector<std::int32_t>> node_sets;
  std::map<std::string, std::vector<std::array<std::int32_t, 2>>> element_sets;

  [[nodiscard]] Eigen::Index node_count() const { return nodes.cols(); }
  [[nodiscard]] std::size_t element_count() const;
  /// Throws InvalidInput naming the item: a node index out of range, a body index out of
  /// range, a non-finite coordinate, an element whose Jacobian determinant is <= 0 or
  /// whose volume is below 1e-12 of the cube of its largest extent (inverted or degenerate), a
  /// node used by no element.
  void validate() const;
};

}  // namespace asperity::fem
