// Constructive solid geometry of bodies and their meshing by the gmsh program, run as a
// separate process (gmsh is GPL; the library is MIT and never links it). Script syntax:
// gmsh reference manual, "Gmsh scripting language" (OpenCASCADE kernel: Box, Cylinder,
// Extrude, BooleanUnion/Difference/Fragments; mesh size fields Box, Cylinder, Min).
#include "asperity/fem/geometry.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/process.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/fem/mesh_io.hpp"

namespace asperity::fem {
namespace {

using Eigen::Vector3d;
using Box3 = Eigen::AlignedBox3d;

const char* kind(const Primitive& p) {
  return std::visit(
      [](const auto& q) -> const char* {
        using T = std::decay_t<decltype(q)>;
        if constexpr (std::is_same_v<T, Box>) return "box";
        if constexpr (std::is_same_v<T, Cylinder>) return "cylinder";
        return "prism";
      },
      p);
}

// ---- prisms: the plane of the polygon and its 2-D coordinates ------------------------

struct PolygonFrame {
  Vector3d origin;                      // first vertex
  Vector3d normal;                      // unit, by Newell's method (right-hand rule)
  Vector3d e1, e2;                      // unit, in the plane
  std::vector<Eigen::Vector2d> points;  // vertices in (e1, e2)
  double area = 0.0;
  double diameter = 0.0;
};

// The polygon's vertices without a repeated closing vertex.
std::vector<Vector3d> open_polygon(const Prism& p) {
  std::vector<Vector3d> v = p.polygon;
  if (v.size() > 1 && v.front() == v.back()) v.pop_back();
  return v;
}

PolygonFrame frame_of(const std::vector<Vector3d>& v) {
  PolygonFrame f;
  f.origin = v.front();
  Vector3d n = Vector3d::Zero();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vector3d& a = v[i];
    const Vector3d& b = v[(i + 1) % v.size()];
    n += a.cross(b);  // Newell: twice the vector area
  }
  f.area = 0.5 * n.norm();
  for (const auto& a : v) {
    for (const auto& b : v) f.diameter = std::max(f.diameter, (a - b).norm());
  }
  if (f.area <= 0.0) return f;
  f.normal = n.normalized();
  // e1 along the longest vertex offset from the origin, projected into the plane.
  Vector3d far = Vector3d::Zero();
  for (const auto& a : v) {
    if ((a - f.origin).norm() > far.norm()) far = a - f.origin;
  }
  f.e1 = (far - far.dot(f.normal) * f.normal).normalized();
  f.e2 = f.normal.cross(f.e1);
  for (const auto& a : v) f.points.emplace_back((a - f.origin).dot(f.e1), (a - f.origin).dot(f.e2));
  return f;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Whether closed segments ab and cd share a point (within `eps`).
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d, double eps) {
  const auto point_on = [eps](const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                              const Eigen::Vector2d& r) {
    // distance from r to segment pq
    const Eigen::Vector2d pq = q - p;
    const double t = std::clamp((r - p).dot(pq) / pq.squaredNorm(), 0.0, 1.0);
    return (p + t * pq - r).norm() <= eps;
  };
  const double d1 = cross2(b - a, c - a);
  const double d2 = cross2(b - a, d - a);
  const double d3 = cross2(d - c, a - c);
  const double d4 = cross2(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;
  }
  return point_on(a, b, c) || point_on(a, b, d) || point_on(c, d, a) || point_on(c, d, b);
}

// Signed distance in the plane from q to the polygon: > 0 inside.
double polygon_depth(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& q) {
  double dist = std::numeric_limits<double>::infinity();
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[j];
    const auto& b = poly[i];
    const Eigen::Vector2d ab = b - a;
    const double t = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    dist = std::min(dist, (a + t * ab - q).norm());
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) {
      inside = !inside;  // crossing number
    }
  }
  return inside ? dist : -dist;
}

// ---- depth of a point in a primitive (> 0 inside, < 0 outside; |value| <= distance) --

double depth(const Box& b, const Vector3d& p) {
  const Vector3d lo = p - b.corner;
  const Vector3d hi = b.corner + b.size - p;
  return std::min(lo.minCoeff(), hi.minCoeff());
}

double depth(const Cylinder& c, const Vector3d& p) {
  const double h = c.axis.norm();
  const Vector3d u = c.axis / h;
  const Vector3d d = p - c.base_centre;
  const double t = d.dot(u);
  const double r = (d - t * u).norm();
  return std::min({t, h - t, c.radius - r});
}

double depth(const Prism& prism, const Vector3d& p) {
  const auto f = frame_of(open_polygon(prism));
  const double en = prism.extrusion.dot(f.normal);     // height, signed
  const double s = (p - f.origin).dot(f.normal) / en;  // fraction along the extrusion
  const Vector3d q = p - s * prism.extrusion - f.origin;
  const double in_plane = polygon_depth(f.points, {q.dot(f.e1), q.dot(f.e2)});
  const double h = std::abs(en);
  return std::min({in_plane, s * h, (1.0 - s) * h});
}

double depth(const Primitive& prim, const Vector3d& p) {
  return std::visit([&](const auto& q) { return depth(q, p); }, prim);
}

Box3 bounds(const Box& b) {
  return Box3(b.corner, b.corner + b.size);
}

Box3 bounds(const Cylinder& c) {
  const Vector3d u = c.axis.normalized();
  Vector3d ext;
  for (int i = 0; i < 3; ++i) ext[i] = c.radius * std::sqrt(std::max(0.0, 1.0 - u[i] * u[i]));
  Box3 box;
  for (const Vector3d& end : {Vector3d(c.base_centre), Vector3d(c.base_centre + c.axis)}) {
    box.extend(Vector3d(end - ext));
    box.extend(Vector3d(end + ext));
  }
  return box;
}

Box3 bounds(const Prism& p) {
  Box3 box;
  for (const auto& v : p.polygon) {
    box.extend(v);
    box.extend(Vector3d(v + p.extrusion));
  }
  return box;
}

Box3 bounds(const Primitive& prim) {
  return std::visit([](const auto& q) { return bounds(q); }, prim);
}

Box3 body_bounds(const Body& body) {
  Box3 box;
  for (const auto& p : body.add) box.extend(bounds(p));
  return box;
}

// ---- validation ---------------------------------------------------------------------

void require_finite_vector(const std::string& item, const char* field, const Vector3d& v) {
  if (!v.allFinite()) {
    throw InvalidInput(fmt::format("{}: {} = ({}, {}, {}) is not finite", item, field,
                                   core::format_value(v.x()), core::format_value(v.y()),
                                   core::format_value(v.z())));
  }
}

void validate_primitive(const std::string& item, const Box& b) {
  require_finite_vector(item, "corner", b.corner);
  require_finite_vector(item, "size", b.size);
  if (b.size.minCoeff() <= 0.0) {
    throw InvalidInput(
        fmt::format("{}: size = ({}, {}, {}) m is degenerate: every edge must be > 0", item,
                    core::format_value(b.size.x()), core::format_value(b.size.y()),
                    core::format_value(b.size.z())));
  }
}

void validate_primitive(const std::string& item, const Cylinder& c) {
  require_finite_vector(item, "base_centre", c.base_centre);
  require_finite_vector(item, "axis", c.axis);
  core::require_positive(item + ": radius", c.radius);
  if (c.axis.norm() <= 0.0) {
    throw InvalidInput(
        fmt::format("{}: axis = (0, 0, 0) is degenerate: its length is the height "
                    "and must be > 0",
                    item));
  }
}

void validate_primitive(const std::string& item, const Prism& p) {
  for (std::size_t i = 0; i < p.polygon.size(); ++i) {
    require_finite_vector(item, fmt::format("polygon[{}]", i + 1).c_str(), p.polygon[i]);
  }
  require_finite_vector(item, "extrusion", p.extrusion);
  const auto v = open_polygon(p);
  if (v.size() < 3) {
    throw InvalidInput(
        fmt::format("{}: the polygon does not close: {} distinct vertices, at "
                    "least 3 are needed",
                    item, v.size()));
  }
  const auto f = frame_of(v);
  const double eps = 1e-9 * f.diameter;  // rounding of coordinates given in m
  for (std::size_t i = 0; i < v.size(); ++i) {
    if ((v[i] - v[(i + 1) % v.size()]).norm() <= eps) {
      throw InvalidInput(fmt::format("{}: the polygon does not close: vertices {} and {} coincide",
                                     item, i + 1, (i + 1) % v.size() + 1));
    }
  }
  if (f.area <= eps * f.diameter) {
    throw InvalidInput(fmt::format(
        "{}: the polygon does not close: its area is zero (its vertices are on one line)", item));
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double off = (v[i] - f.origin).dot(f.normal);
    if (std::abs(off) > eps) {
      throw InvalidInput(
          fmt::format("{}: the polygon is not planar: vertex {} is {} m off the "
                      "plane of the others",
                      item, i + 1, core::format_value(off)));
    }
  }
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      const auto& a = f.points[i];
      const auto& b = f.points[(i + 1) % n];
      const auto& c = f.points[j];
      const auto& d = f.points[(j + 1) % n];
      bool meet = false;
      if (adjacent) {
        // Adjacent edges share one vertex; they must not fold back onto each other.
        const auto shared = j == i + 1 ? b : a;
        const auto other1 = j == i + 1 ? a : b;
        const auto other2 = j == i + 1 ? d : c;
        const Eigen::Vector2d u = other1 - shared;
        const Eigen::Vector2d w = other2 - shared;
        meet = std::abs(cross2(u, w)) <= eps * (u.norm() + w.norm()) && u.dot(w) > 0.0;
      } else {
        meet = segments_meet(a, b, c, d, eps);
      }
      if (meet) {
        throw InvalidInput(
            fmt::format("{}: the polygon is self-intersecting: edges {}-{} and "
                        "{}-{} meet",
                        item, i + 1, (i + 1) % n + 1, j + 1, (j + 1) % n + 1));
      }
    }
  }
  const double len = p.extrusion.norm();
  if (len <= 0.0 || std::abs(p.extrusion.dot(f.normal)) <= 1e-9 * len) {
    throw InvalidInput(fmt::format("{}: the extrusion is {}: it must leave the polygon's plane",
                                   item, len <= 0.0 ? "zero" : "parallel to the polygon's plane"));
  }
}

std::string body_item(const Geometry& g, std::size_t b) {
  return fmt::format("bodies[{}] \"{}\"", b + 1, core::printable(g.bodies[b].name));
}

// Pairs of bodies whose bounding boxes meet: an upper bound of the refined region, for the
// element-count estimate of validate().
struct InterfaceRegion {
  std::size_t a, b;
  Box3 box;  // the overlap of the two bounding boxes, grown by the interface size
};

std::vector<InterfaceRegion> interface_regions(const Geometry& g) {
  std::vector<InterfaceRegion> regions;
  for (std::size_t a = 0; a < g.bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < g.bodies.size(); ++b) {
      const Box3 ba = body_bounds(g.bodies[a]);
      const Box3 bb = body_bounds(g.bodies[b]);
      const double gap = 1e-9 * (ba.diagonal().norm() + bb.diagonal().norm());
      Box3 meet = ba.intersection(bb);
      if ((meet.max() - meet.min()).minCoeff() < -gap) continue;
      const Vector3d grow = Vector3d::Constant(g.size.interface);
      regions.push_back({a, b,
                         Box3(Vector3d(meet.min().cwiseMin(meet.max()) - grow),
                              Vector3d(meet.max().cwiseMax(meet.min()) + grow))});
    }
  }
  return regions;
}

// Points of the region refined around a cylinder cut: radius + this many hole sizes.
constexpr double kHoleRing = 2.0;

}  // namespace

void Geometry::validate() const {
  if (bodies.empty()) throw InvalidInput("geometry: no body; at least one is needed");
  core::require_positive("size.global", size.global);
  core::require_positive("size.interface", size.interface);
  core::require_positive("size.hole", size.hole);
  std::set<std::string> names;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto& body = bodies[b];
    const auto item = fmt::format("bodies[{}]", b + 1);
    if (body.name.empty()) throw InvalidInput(fmt::format("{}: the name is empty", item));
    if (!names.insert(body.name).second) {
      throw InvalidInput(fmt::format("{} \"{}\": another body has the same name", item,
                                     core::printable(body.name)));
    }
    const auto named = body_item(*this, b);
    if (body.add.empty()) {
      throw InvalidInput(
          fmt::format("{}: nothing to add (add is empty): the body does not close", named));
    }
    for (const auto* list : {&body.add, &body.cut}) {
      const char* which = list == &body.add ? "add" : "cut";
      for (std::size_t i = 0; i < list->size(); ++i) {
        const auto& prim = (*list)[i];
        const auto pitem = fmt::format("{}: {}[{}] ({})", named, which, i + 1, kind(prim));
        std::visit([&](const auto& q) { validate_primitive(pitem, q); }, prim);
      }
    }
    const Box3 box = body_bounds(body);
    for (std::size_t i = 0; i < body.cut.size(); ++i) {
      const Box3 cut = bounds(body.cut[i]);
      if (std::holds_alternative<Box>(body.cut[i]) && cut.contains(box)) {
        throw InvalidInput(
            fmt::format("{}: cut[{}] (box) holds the whole body: nothing of it "
                        "would be left (the body vanishes)",
                        named, i + 1));
      }
      const Box3 meet = box.intersection(cut);
      if ((meet.max() - meet.min()).minCoeff() <= 0.0) {
        throw InvalidInput(
            fmt::format("{}: cut[{}] ({}) misses the body (it does not meet the "
                        "bounding box of the added primitives)",
                        named, i + 1, kind(body.cut[i])));
      }
    }
  }
  // About 6 tetrahedra per cube of the element size.
  double elements = 0.0;
  for (const auto& body : bodies)
    elements += 6.0 * body_bounds(body).volume() / std::pow(size.global, 3);
  for (const auto& r : interface_regions(*this)) {
    elements += 6.0 * r.box.volume() / std::pow(size.interface, 3);
  }
  for (const auto& body : bodies) {
    for (const auto& cut : body.cut) {
      if (const auto* c = std::get_if<Cylinder>(&cut)) {
        const double ring = c->radius + kHoleRing * size.hole;
        elements += 6.0 * std::numbers::pi * ring * ring * c->axis.norm() / std::pow(size.hole, 3);
      }
    }
  }
  if (elements > 1e7) {
    throw InvalidInput(
        fmt::format("size: global {} m, interface {} m, hole {} m would give about {:.2g} elements "
                    "(more than 10 million): choose larger sizes",
                    core::format_value(size.global), core::format_value(size.interface),
                    core::format_value(size.hole), elements));
  }
}

bool contains(const Body& body, const Vector3d& point, double tolerance) {
  bool in = false;
  for (const auto& p : body.add) {
    if (depth(p, point) >= -tolerance) {
      in = true;
      break;
    }
  }
  if (!in) return false;
  for (const auto& p : body.cut) {
    if (depth(p, point) > tolerance) return false;
  }
  return true;
}

std::string gmsh_script(const Geometry& g) {
  g.validate();
  std::string s;
  const auto num = [](double x) { return fmt::format("{:.17g}", x); };
  const auto vec = [&](const Vector3d& v) {
    return fmt::format("{}, {}, {}", num(v.x()), num(v.y()), num(v.z()));
  };
  s += "// Written by asperity (fem::gmsh_script): the bodies of a structure as constructive\n";
  s += "// solid geometry, fragmented so that the mesh is conforming across shared faces.\n";
  s += "SetFactory(\"OpenCASCADE\");\n";
  s += "General.AbortOnError = 1;\n";
  s += "Mesh.ElementOrder = 2;\n";
  s += "Mesh.MeshSizeFromPoints = 0;\n";
  s += "Mesh.MeshSizeFromCurvature = 0;\n";
  s += "Mesh.MeshSizeExtendFromBoundary = 0;\n";
  s += fmt::format("Mesh.MeshSizeMax = {};\n", num(g.size.global));
  std::vector<std::string> body_lists;
  for (std::size_t b = 0; b < g.bodies.size(); ++b) {
    const auto& body = g.bodies[b];
    s += fmt::format("// bodies[{}]\n", b + 1);
    const auto emit = [&](const Primitive& prim, const std::string& var) {
      if (const auto* box = std::get_if<Box>(&prim)) {
        s += fmt::format("{} = newv; Box({}) = {{{}, {}}};\n", var, var, vec(box->corner),
                         vec(box->size));
      } else if (const auto* c = std::get_if<Cylinder>(&prim)) {
        s += fmt::format("{} = newv; Cylinder({}) = {{{}, {}, {}}};\n", var, var,
                         vec(c->base_centre), vec(c->axis), num(c->radius));
      } else {
        const auto& p = std::get<Prism>(prim);
        const auto v = open_polygon(p);
        std::vector<std::string> points;
        std::vector<std::string> lines;
        for (std::size_t i = 0; i < v.size(); ++i) {
          points.push_back(fmt::format("{}_p{}", var, i));
          s += fmt::format("{} = newp; Point({}) = {{{}}};\n", points.back(), points.back(),
                           vec(v[i]));
        }
        for (std::size_t i = 0; i < v.size(); ++i) {
          lines.push_back(fmt::format("{}_l{}", var, i));
          s += fmt::format("{} = newl; Line({}) = {{{}, {}}};\n", lines.back(), lines.back(),
                           points[i], points[(i + 1) % v.size()]);
        }
        s += fmt::format("{}_cl = newll; Curve Loop({}_cl) = {{{}}};\n", var, var,
                         fmt::join(lines, ", "));
        s += fmt::format("{}_s = news; Plane Surface({}_s) = {{{}_cl}};\n", var, var, var);
        s += fmt::format("{}_e[] = Extrude{{{}}}{{ Surface{{{}_s}}; }};\n", var, vec(p.extrusion),
                         var);
        s += fmt::format("{} = {}_e[1];\n", var, var);
      }
    };
    std::vector<std::string> adds;
    for (std::size_t i = 0; i < body.add.size(); ++i) {
      adds.push_back(fmt::format("a{}_{}", b, i));
      emit(body.add[i], adds.back());
    }
    const auto list = fmt::format("b{}", b);
    if (adds.size() == 1) {
      s += fmt::format("{}[] = {{{}}};\n", list, adds[0]);
    } else {
      s += fmt::format(
          "{}[] = BooleanUnion{{ Volume{{{}}}; Delete; }}{{ Volume{{{}}}; Delete; }};\n", list,
          adds[0], fmt::join(std::vector<std::string>(adds.begin() + 1, adds.end()), ", "));
    }
    std::vector<std::string> cuts;
    for (std::size_t i = 0; i < body.cut.size(); ++i) {
      cuts.push_back(fmt::format("c{}_{}", b, i));
      emit(body.cut[i], cuts.back());
    }
    if (!cuts.empty()) {
      s += fmt::format(
          "{}[] = BooleanDifference{{ Volume{{{}[]}}; Delete; }}{{ Volume{{{}}}; Delete; }};\n",
          list, list, fmt::join(cuts, ", "));
    }
    body_lists.push_back(list + "[]");
  }
  if (g.bodies.size() > 1) {
    s += "// One geometry for all bodies: the faces they share become one face each.\n";
    // A body whose cuts removed all of it leaves an empty list: mesh_geometry names it.
    s += fmt::format("all[] = {{{}}};\n", fmt::join(body_lists, ", "));
    s += "If (#all[] > 1)\n  fragments[] = BooleanFragments{ Volume{all[]}; Delete; }{};\nEndIf\n";
  }
  // Size fields.
  std::vector<int> fields;
  int next = 1;
  if (g.bodies.size() > 1) {
    // Interface size on the faces two bodies share (found after the fragments: a surface
    // bounding two volumes), growing linearly to the global size from half an interface
    // size to 2.5 interface sizes away (gmsh Distance + Threshold fields).
    s += "// interface size near the faces that two bodies share\n";
    s += "shared_volumes[] = Volume{:};\nshared[] = {};\n"
         "For i In {0:#shared_volumes[]-1}\n"
         "  bi[] = Boundary{ Volume{shared_volumes[i]}; };\n"
         "  For j In {0:#shared_volumes[]-1}\n"
         "    If (j > i)\n"
         "      bj[] = Boundary{ Volume{shared_volumes[j]}; };\n"
         "      For k In {0:#bi[]-1}\n"
         "        For l In {0:#bj[]-1}\n"
         "          If (Abs(bi[k]) == Abs(bj[l]))\n"
         "            shared[] += Abs(bi[k]);\n"
         "          EndIf\n"
         "        EndFor\n"
         "      EndFor\n"
         "    EndIf\n"
         "  EndFor\n"
         "EndFor\n";
    s += "If (#shared[] > 0)\n";
    s += fmt::format(
        "  Field[{0}] = Distance;\n  Field[{0}].FacesList = {{shared[]}};\n"
        "  Field[{0}].NumPointsPerCurve = 200;\n",
        next);
    s += fmt::format(
        "  Field[{0}] = Threshold;\n  Field[{0}].InField = {1};\n  Field[{0}].SizeMin = {2};\n"
        "  Field[{0}].SizeMax = {3};\n  Field[{0}].DistMin = {4};\n  Field[{0}].DistMax = {5};\n",
        next + 1, next, num(g.size.interface), num(g.size.global), num(0.5 * g.size.interface),
        num(2.5 * g.size.interface));
    s += "Else\n";
    s += fmt::format("  Field[{0}] = MathEval;\n  Field[{0}].F = \"{1}\";\n", next + 1,
                     num(g.size.global));
    s += "EndIf\n";
    fields.push_back(next + 1);
    next += 2;
  }
  for (std::size_t b = 0; b < g.bodies.size(); ++b) {
    for (std::size_t i = 0; i < g.bodies[b].cut.size(); ++i) {
      const auto* c = std::get_if<Cylinder>(&g.bodies[b].cut[i]);
      if (c == nullptr) continue;
      // gmsh's Cylinder field: centre in the middle, axis = half the length.
      const double h = c->axis.norm();
      const Vector3d centre = c->base_centre + 0.5 * c->axis;
      const Vector3d half = c->axis / h * (0.5 * h + g.size.hole);
      s += fmt::format("// hole size around bodies[{}] cut[{}]\n", b + 1, i + 1);
      s += fmt::format("Field[{}] = Cylinder;\n", next);
      s += fmt::format("Field[{0}].VIn = {1}; Field[{0}].VOut = {2}; Field[{0}].Radius = {3};\n",
                       next, num(g.size.hole), num(g.size.global),
                       num(c->radius + kHoleRing * g.size.hole));
      s += fmt::format(
          "Field[{0}].XCenter = {1}; Field[{0}].YCenter = {2}; Field[{0}].ZCenter = {3};\n"
          "Field[{0}].XAxis = {4}; Field[{0}].YAxis = {5}; Field[{0}].ZAxis = {6};\n",
          next, num(centre.x()), num(centre.y()), num(centre.z()), num(half.x()), num(half.y()),
          num(half.z()));
      fields.push_back(next++);
    }
  }
  if (!fields.empty()) {
    s += fmt::format("Field[{}] = Min;\nField[{}].FieldsList = {{{}}};\n", next, next,
                     fmt::join(fields, ", "));
    s += fmt::format("Background Field = {};\n", next);
  }
  s += "// One physical volume per volume (its tag), so that only volume elements are saved.\n";
  s += "volumes[] = Volume{:};\n";
  s += "For i In {0:#volumes[]-1}\n  Physical Volume(volumes[i]) = {volumes[i]};\nEndFor\n";
  return s;
}

void MeshOptions::validate() const {
  if (gmsh.empty()) throw InvalidInput("mesh options: gmsh (the program) is empty");
  core::require_positive("mesh options: time_limit", time_limit);
  if (threads < 1 || threads > 1024) {
    throw InvalidInput(fmt::format(
        "mesh options: threads = {} is not allowed: it must be a whole number in [1, 1024]",
        threads));
  }
}

namespace {

/// A directory for the gmsh files: the user's, or a private temporary one removed on
/// destruction (and on SIGINT/SIGTERM through the registry of core/file_io.hpp).
class WorkDir {
 public:
  explicit WorkDir(const std::string& keep) {
    if (!keep.empty()) {
      path_ = keep;
      std::error_code ec;
      std::filesystem::create_directories(path_, ec);
      if (ec || !std::filesystem::is_directory(path_)) {
        throw InvalidInput(fmt::format("mesh options: work_dir \"{}\" cannot be created: {}",
                                       core::printable(keep),
                                       ec ? ec.message() : "not a directory"));
      }
      return;
    }
    path_ = core::create_registered_temporary_directory("asperity-gmsh", "gmsh", &slot_);
    temporary_ = true;
  }
  ~WorkDir() {
    if (!temporary_) return;
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
    core::unregister_temporary(slot_);
  }
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  bool temporary_ = false;
  int slot_ = -1;
};

// The last `n` lines of `text` that are not blank, joined by " | ".
std::string last_lines(const std::string& text, std::size_t n) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos) lines.push_back(core::printable(line));
  }
  if (lines.size() > n) lines.erase(lines.begin(), lines.end() - static_cast<std::ptrdiff_t>(n));
  return fmt::format("{}", fmt::join(lines, " | "));
}

}  // namespace

Mesh mesh_geometry(const Geometry& geometry, const MeshOptions& options) {
  options.validate();
  const std::string script = gmsh_script(geometry);  // validates the geometry
  const WorkDir dir(options.work_dir);
  const auto geo = (dir.path() / "geometry.geo").string();
  const auto msh = (dir.path() / "geometry.msh").string();
  {
    std::ofstream out(geo, std::ios::binary);
    out << script;
    out.close();
    if (out.fail()) {
      throw InvalidInput(fmt::format("cannot write the gmsh script {}", core::printable(geo)));
    }
  }
  std::error_code ec;
  std::filesystem::remove(msh, ec);  // a mesh of an earlier run is never read
  const auto run = core::run_program({options.gmsh, geo, "-3", "-format", "msh41", "-o", msh, "-nt",
                                      std::to_string(options.threads), "-v", "2"},
                                     options.time_limit);
  if (run.spawn_error == ENOENT) {
    throw InvalidInput(fmt::format(
        "cannot mesh: the gmsh program \"{}\" is not found{}: install the gmsh program: apt-get "
        "install gmsh (or give its path)",
        core::printable(options.gmsh),
        options.gmsh.find('/') == std::string::npos ? " on PATH" : ""));
  }
  if (run.spawn_error != 0) {
    throw InvalidInput(fmt::format("cannot run the gmsh program \"{}\": {}",
                                   core::printable(options.gmsh), std::strerror(run.spawn_error)));
  }
  if (run.timed_out) {
    throw NumericalError(fmt::format(
        "gmsh did not finish meshing within the time limit of {} s (global size {} m, interface "
        "{} m, hole {} m): choose larger sizes or a longer limit",
        core::format_value(options.time_limit), core::format_value(geometry.size.global),
        core::format_value(geometry.size.interface), core::format_value(geometry.size.hole)));
  }
  if (!run.exited_zero || !std::filesystem::exists(msh)) {
    throw InvalidInput(fmt::format("gmsh failed to mesh the geometry ({}): {}", run.status,
                                   last_lines(run.output, 8)));
  }
  Mesh mesh = read_gmsh(msh);
  // Each gmsh volume (a body of `mesh`) goes to the geometry body that contains the
  // centroids of its elements' corners. Centroids are inside their volume by about a
  // quarter of an element height; the tolerance only absorbs rounding.
  const double tol =
      1e-6 * std::min({geometry.size.global, geometry.size.interface, geometry.size.hole});
  const std::size_t nv = mesh.bodies.size();
  const std::size_t nb = geometry.bodies.size();
  std::vector<std::vector<std::size_t>> hits(nv, std::vector<std::size_t>(nb, 0));
  std::vector<std::size_t> elements(nv, 0);
  std::vector<Vector3d> sample(nv, Vector3d::Zero());
  std::vector<double> volume(nv, 0.0);
  for (const auto& block : mesh.blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      const auto el = block.element(e);
      const auto v = static_cast<std::size_t>(block.body[e]);
      const Vector3d p0 = mesh.nodes.col(el[0]);
      const Vector3d p1 = mesh.nodes.col(el[1]);
      const Vector3d p2 = mesh.nodes.col(el[2]);
      const Vector3d p3 = mesh.nodes.col(el[3]);
      const Vector3d c = 0.25 * (p0 + p1 + p2 + p3);
      volume[v] += std::abs((p1 - p0).cross(p2 - p0).dot(p3 - p0)) / 6.0;
      if (elements[v]++ == 0) sample[v] = c;
      for (std::size_t b = 0; b < nb; ++b) hits[v][b] += contains(geometry.bodies[b], c, tol);
    }
  }
  std::vector<std::int32_t> body_of(nv, -1);
  for (std::size_t v = 0; v < nv; ++v) {
    const auto& h = hits[v];
    const auto best = static_cast<std::size_t>(std::max_element(h.begin(), h.end()) - h.begin());
    const auto near =
        fmt::format("gmsh {} (near ({}, {}, {}) m, {} m^3)", mesh.bodies[v],
                    core::format_value(sample[v].x()), core::format_value(sample[v].y()),
                    core::format_value(sample[v].z()), core::format_value(volume[v]));
    for (std::size_t b = 0; b < nb; ++b) {
      if (b != best && 2 * h[b] >= elements[v]) {
        throw InvalidInput(fmt::format(
            "{} and {} overlap in volume ({} is in both): bodies may share faces, not volume",
            body_item(geometry, std::min(b, best)), body_item(geometry, std::max(b, best)), near));
      }
    }
    // Curved faces (holes) are approximated by chords: a few centroids of elements along
    // them may fall just outside; nine in ten inside is a clear majority.
    if (10 * h[best] < 9 * elements[v]) {
      throw InvalidInput(
          fmt::format("{} is in no body (gmsh made a volume the geometry does not "
                      "describe)",
                      near));
    }
    body_of[v] = static_cast<std::int32_t>(best);
  }
  for (std::size_t b = 0; b < nb; ++b) {
    if (std::find(body_of.begin(), body_of.end(), static_cast<std::int32_t>(b)) == body_of.end()) {
      throw InvalidInput(
          fmt::format("{} vanished: nothing of it is left to mesh (its cuts remove "
                      "all of it)",
                      body_item(geometry, b)));
    }
  }
  mesh.element_sets.clear();
  mesh.bodies.clear();
  for (const auto& body : geometry.bodies) mesh.bodies.push_back(body.name);
  for (std::int32_t k = 0; k < static_cast<std::int32_t>(mesh.blocks.size()); ++k) {
    auto& block = mesh.blocks[static_cast<std::size_t>(k)];
    for (std::size_t e = 0; e < block.size(); ++e) {
      block.body[e] = body_of[static_cast<std::size_t>(block.body[e])];
      mesh.element_sets[mesh.bodies[static_cast<std::size_t>(block.body[e])]].push_back(
          {k, static_cast<std::int32_t>(e)});
    }
  }
  return mesh;
}

}  // namespace asperity::fem
