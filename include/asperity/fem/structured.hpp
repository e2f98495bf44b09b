#pragma once
// Structured meshes of a rectangular box, for tests and examples that need no mesher.
#include <array>
#include <string>

#include <Eigen/Dense>

#include "asperity/fem/mesh.hpp"

namespace asperity::fem {

/// The box [corner, corner + size] (SI: m) cut into divisions[0] x [1] x [2] equal
/// cells along x, y, z, one body named `body`. hex20: one element per cell. tet10: each
/// cell split into 6 tetrahedra around its diagonal from the (min x, min y, min z)
/// corner to the opposite one (Kuhn / Freudenthal), the same way in every cell, so that
/// neighbouring cells' faces match. Straight-sided elements; nodes numbered x fastest,
/// then y, then z (only those the elements use). Node sets "xmin", "xmax", "ymin",
/// "ymax", "zmin", "zmax": the nodes on each face of the box. Throws InvalidInput for a
/// size that is not finite and > 0, a non-finite corner or a count of divisions < 1 (or
/// large enough to overflow 32-bit node indices).
[[nodiscard]] Mesh structured_box_mesh(const Eigen::Vector3d& corner, const Eigen::Vector3d& size,
                                       std::array<int, 3> divisions, ElementType type,
                                       std::string body = "box");

}  // namespace asperity::fem
