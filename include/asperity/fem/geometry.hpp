#pragma once
// Bodies described by constructive solid geometry (unions of primitives minus unions of
// primitives), and their meshing by the gmsh program. gmsh is GPL: it is never linked
// into the library; mesh_geometry() writes a .geo script, runs `gmsh` as a separate
// process and reads the .msh it writes. The bodies are fragmented together
// (BooleanFragments) so that the mesh is conforming across the faces two bodies share:
// one node there for both (the interface layer duplicates them afterwards).
// SI units: m.
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Dense>

#include "asperity/fem/mesh.hpp"

namespace asperity::fem {

/// An axis-aligned box: `corner` is its lowest corner, `size` its edge lengths (> 0).
struct Box {
  Eigen::Vector3d corner = Eigen::Vector3d::Zero();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
};

/// A circular cylinder: its base disc centred at `base_centre`, `axis` from the base to
/// the top (its length is the height), `radius` > 0.
struct Cylinder {
  Eigen::Vector3d base_centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// A prism: a simple polygon (>= 3 vertices in one plane, closed implicitly: the last
/// vertex joins the first) swept along `extrusion` (not parallel to its plane).
struct Prism {
  std::vector<Eigen::Vector3d> polygon;
  Eigen::Vector3d extrusion = Eigen::Vector3d::Zero();
};

using Primitive = std::variant<Box, Cylinder, Prism>;

/// A body: the union of `add` minus the union of `cut`.
struct Body {
  std::string name;
  std::vector<Primitive> add;
  std::vector<Primitive> cut;
};

/// Element sizes [m]: `global` everywhere, `interface` where the bounding boxes of two
/// bodies meet (the region of their shared faces), `hole` around each cylinder cut.
struct MeshSize {
  double global = 0.0;
  double interface = 0.0;
  double hole = 0.0;
};

struct Geometry {
  std::vector<Body> bodies;
  MeshSize size;

  /// Throws InvalidInput naming the item ("bodies[1] \"half B\": cut[2] (cylinder)"):
  /// no body; a body name empty or repeated; a body with nothing to add; a size not
  /// finite and > 0; a coordinate not finite; a degenerate primitive (a box edge <= 0, a
  /// cylinder of radius or height <= 0); a prism whose polygon does not close (fewer
  /// than 3 distinct vertices, zero area), is not planar, is self-intersecting, or whose
  /// extrusion is parallel to its plane; a cut that misses its body's bounding box; sizes
  /// so small that the mesh would have more than about 10 million elements.
  void validate() const;
};

/// Whether `point` lies in `body` (in one of its `add` primitives and in none of its
/// `cut` primitives), with `tolerance` [m] (>= 0): points within about `tolerance`
/// outside an added primitive count as inside it, points less than `tolerance` inside a
/// cut count as outside the cut.
[[nodiscard]] bool contains(const Body& body, const Eigen::Vector3d& point, double tolerance);

/// The gmsh script (.geo, OpenCASCADE kernel) of `geometry`: the primitives, the
/// BooleanUnion / BooleanDifference of each body, BooleanFragments of all bodies, the
/// size fields (`interface` size on the faces two bodies share, found after the fragments,
/// growing to `global` from 0.5 to 2.5 interface sizes away: Distance and Threshold
/// fields; Cylinder fields with `hole` size around each cylinder cut, `global` elsewhere), second
/// order (Mesh.ElementOrder = 2), 3-D tetrahedra, one physical volume per resulting
/// volume (tag = the volume's tag). Body names do not enter the script.
/// Calls geometry.validate().
[[nodiscard]] std::string gmsh_script(const Geometry& geometry);

struct MeshOptions {
  /// The gmsh program: a name looked up on PATH, or a path.
  std::string gmsh = "gmsh";
  /// Wall-clock limit of the gmsh run [s] (> 0); gmsh is killed when it is exceeded.
  double time_limit = 600.0;
  /// Directory to keep geometry.geo and geometry.msh in (created if missing); empty: a
  /// private temporary directory, removed afterwards.
  std::string work_dir;
  /// Threads gmsh may use (>= 1).
  int threads = 1;

  void validate() const;
};

/// Meshes `geometry` with gmsh (`gmsh geometry.geo -3 -format msh41 -o geometry.msh`)
/// into 10-node tetrahedra: one body per Body, in the same order and with the same
/// names (each gmsh volume is given to the body that contains its elements' centroids),
/// nodes shared across faces two bodies share. Throws InvalidInput: gmsh not installed
/// ("install the gmsh program: apt-get install gmsh"), gmsh failing (the last lines of
/// its messages), two bodies overlapping in volume, a body that vanished (its cuts
/// remove all of it), a gmsh volume in no body; NumericalError when gmsh exceeds the
/// time limit.
[[nodiscard]] Mesh mesh_geometry(const Geometry& geometry, const MeshOptions& options = {});

}  // namespace asperity::fem
