#pragma once
// Reading solid meshes made elsewhere (gmsh .msh, Abaqus .inp) and writing meshes with
// nodal fields for ParaView (VTU) or gmsh (.msh). Only quadratic solid elements are read
// (10-node tetrahedra, 20-node hexahedra); their nodes are put into the canonical order
// of mesh.hpp whatever the file's order. Nodes are renumbered densely from 0 in the order
// of the file, leaving out nodes that no volume element uses (also from the node sets).
// Every refusal is an InvalidInput naming the file, the line and what is wrong.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/fem/mesh.hpp"

namespace asperity::fem {

/// Cap of a mesh file: 1 GiB (a mesh of about 5 million quadratic tetrahedra in text).
inline constexpr std::size_t kMaxMeshFileBytes = std::size_t{1} << 30;

/// A gmsh MSH file, version 4.1 or 2.2, ASCII (what `gmsh -3 -order 2 -format msh41`
/// writes). Volume elements: gmsh types 11 (10-node tetrahedron) and 17 (20-node
/// hexahedron, Mesh.SecondOrderIncomplete = 1); any other volume type is refused (linear
/// ones with "mesh with -order 2"). Bodies: the physical volumes (their $PhysicalNames
/// name, else "volume <physical tag>"), in ascending tag order; when the file has no
/// physical volume, one body per geometric volume ("volume <entity tag>"). Each body is
/// also an element set. Physical surfaces, curves and points become node sets (the nodes
/// of their elements; name from $PhysicalNames, else "surface <tag>", "curve <tag>",
/// "point <tag>"). Refused: binary files, versions other than 4.1 and 2.2, a volume
/// entity in two physical volumes, volume elements outside every physical volume when
/// others are inside one, node tags that are not defined, truncated sections.
[[nodiscard]] Mesh read_gmsh(const std::string& path);

/// An Abaqus input file, flat (no *PART) or with a single part and at most one
/// instance of it (its translation and rotation are applied). Read: *NODE (NSET=),
/// *ELEMENT with TYPE=C3D10 (also C3D10H/M/MH/I, same nodes) or C3D20/C3D20R (also the
/// H variants), *NSET and *ELSET (GENERATE, and names of other sets in the data), keywords
/// in any case, parameters continued on the next line after a trailing comma, element
/// nodes continued over several lines, comments (**). Bodies: one per distinct ELSET= of
/// the *ELEMENT keywords (also element sets), in order of appearance; elements without
/// ELSET= form the body named after the part (*PART, NAME=), else "PART-1". Keywords
/// that do not describe the mesh (materials, steps, sections...) are skipped. Refused:
/// linear (C3D4, C3D8, C3D8R...) and other element types (named), *INCLUDE, several
/// parts or instances, undefined node or element labels, duplicated labels.
[[nodiscard]] Mesh read_abaqus_inp(const std::string& path);

/// A nodal field to write with a mesh: `values` has 1 (scalar) or 3 (vector) rows and
/// one column per node of the mesh.
struct PointField {
  std::string name;
  Eigen::MatrixXd values;
};

/// Writes `mesh` as an ASCII VTK XML unstructured grid (.vtu, VTK_QUADRATIC_TETRA = 24,
/// VTK_QUADRATIC_HEXAHEDRON = 25, whose node orders are the canonical ones) with the
/// point fields and a cell field "body" (the index into mesh.bodies). Written whole or
/// not at all (core::OutputSet). Throws InvalidInput naming the field: an empty or
/// repeated name, a row count other than 1 or 3, a column count other than the node
/// count, a non-finite value.
void write_vtu(const std::string& path, const Mesh& mesh, const std::vector<PointField>& fields);

/// Writes the volume mesh as gmsh MSH 4.1 ASCII: one geometric and physical volume per
/// body (named), gmsh's node order. Node and element sets are not written (MSH keeps
/// sets as physical groups of elements, which a volume mesh alone does not have).
/// Written whole or not at all. Throws InvalidInput for a body name with a double quote
/// or a line break (MSH cannot store them).
void write_gmsh(const std::string& path, const Mesh& mesh);

}  // namespace asperity::fem
