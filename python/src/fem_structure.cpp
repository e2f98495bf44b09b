// asperity.fem: the steps of `asperity structure` (mesh, interfaces, bolts, reduction,
// linear modes) and reduced-model files, as dicts of numpy arrays.
#include <nanobind/eigen/dense.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <string>
#include <vector>

#include "asperity/fem/mesh_io.hpp"
#include "asperity/fem/reduced_model.hpp"
#include "asperity/fem/structure.hpp"
#include "bindings.hpp"

namespace asperity::python {
namespace {

using namespace nb::literals;
using namespace asperity::fem;

template <class Derived>
nb::object array(const Eigen::MatrixBase<Derived>& x) {
  using Plain = typename Derived::PlainObject;
  return nb::cast(Plain(x), nb::rv_policy::move);
}

nb::dict mesh_dict(const Mesh& m) {
  nb::dict d;
  d["nodes"] = array(Eigen::MatrixXd(m.nodes.transpose()));
  nb::list blocks;
  for (const auto& b : m.blocks) {
    const auto npe = nodes_per_element(b.type);
    Eigen::Matrix<std::int32_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> conn = Eigen::Map<
        const Eigen::Matrix<std::int32_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        b.connectivity.data(), static_cast<Eigen::Index>(b.size()), npe);
    nb::dict bd;
    bd["type"] = element_type_name(b.type);
    bd["connectivity"] = nb::cast(conn, nb::rv_policy::move);
    bd["body"] = nb::cast(Eigen::Matrix<std::int32_t, Eigen::Dynamic, 1>(
                              Eigen::Map<const Eigen::Matrix<std::int32_t, Eigen::Dynamic, 1>>(
                                  b.body.data(), static_cast<Eigen::Index>(b.body.size()))),
                          nb::rv_policy::move);
    blocks.append(bd);
  }
  d["blocks"] = blocks;
  d["bodies"] = m.bodies;
  return d;
}

nb::dict model_dict(const ReducedModel& m) {
  nb::dict d;
  d["M"] = array(m.M);
  d["K"] = array(m.K);
  d["Q"] = array(m.Q);
  d["T"] = array(m.T);
  const auto ne = static_cast<Eigen::Index>(m.elements.size());
  Eigen::VectorXd area(ne);
  Eigen::MatrixXd centroid(ne, 3), frame(ne, 9);
  std::vector<std::string> itf;
  for (Eigen::Index e = 0; e < ne; ++e) {
    const auto& el = m.elements[static_cast<std::size_t>(e)];
    area[e] = el.area;
    centroid.row(e) = el.centroid.transpose();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) frame(e, 3 * r + c) = el.frame(r, c);
    itf.push_back(el.interface);
  }
  d["element_area"] = array(area);
  d["element_centroid"] = array(centroid);
  d["element_frame"] = array(frame);
  d["element_interface"] = itf;
  d["Fv"] = array(m.bolt_load);
  d["bolt_elongation"] = array(m.bolt_elongation);
  d["bolt_axial_stiffness"] = array(m.bolt_axial_stiffness);
  d["bolt_preload"] = array(m.bolt_preload);
  d["bolt_names"] = m.bolt_names;
  d["R"] = array(m.recovery);
  d["output_names"] = m.output_names;
  d["output_points"] = array(m.output_points);
  d["source"] = m.source;
  return d;
}

nb::dict run(const std::string& path, const std::string& gmsh) {
  const StructureCase c = read_structure_case(path);
  StructureOptions o;
  o.meshing.gmsh = gmsh;
  const StructureResult r = [&] {
    nb::gil_scoped_release release;
    return run_structure(c, o);
  }();
  nb::dict d;
  d["mesh"] = mesh_dict(r.mesh);
  d["model"] = model_dict(r.model);
  nb::dict modes;
  for (const auto& a : r.analyses) {
    nb::dict ad;
    ad["frequency_hz"] = array(a.modes.frequency_hz);
    ad["shapes"] = array(a.modes.shapes);
    ad["rigid_body_modes"] = a.modes.rigid_body_modes;
    modes[a.name.c_str()] = ad;
  }
  d["linear_modes"] = modes;
  d["prestress_pressure"] = array(r.prestress.pressure);
  d["contact_area"] = r.prestress.contact_area;
  d["bolt_load"] = r.bolt_load_total;
  d["mass"] = r.total_mass;
  nb::list costs;
  for (const auto& s : r.costs) costs.append(nb::make_tuple(s.step, s.seconds, s.peak_rss_mib));
  d["costs"] = costs;
  return d;
}

}  // namespace

void bind_fem_structure(nb::module_& m) {
  m.def("fem_run_structure", &run, "path"_a, "gmsh"_a = "gmsh",
        "Runs a structure case file (asperity structure): mesh, reduced model, linear modes.");
  m.def(
      "fem_read_reduced_model",
      [](const std::string& path) { return model_dict(read_reduced_model(path)); }, "path"_a,
      "Reads a reduced model (.mat: asperity's or the published BRB layout).");
  m.def(
      "fem_read_mesh",
      [](const std::string& path) {
        const bool inp = path.size() > 4 && path.substr(path.size() - 4) == ".inp";
        return mesh_dict(inp ? read_abaqus_inp(path) : read_gmsh(path));
      },
      "path"_a, "Reads a gmsh .msh or an Abaqus .inp mesh of quadratic solid elements.");
  m.def(
      "fem_reduced_linear_modes",
      [](const std::string& path, const Eigen::VectorXd& element_stiffness, int count) {
        const auto r =
            reduced_linear_modes(read_reduced_model(path), element_stiffness, count, "modes");
        nb::dict d;
        d["frequency_hz"] = array(r.frequency_hz);
        d["shapes"] = array(r.shapes);
        d["rigid_body_modes"] = r.rigid_body_modes;
        return d;
      },
      "path"_a, "element_stiffness"_a, "count"_a = 10,
      "Elastic modes of a reduced model file with a linear stiffness per interface element "
      "direction [Pa/m] (3 per element: t1, t2, n).");
}

}  // namespace asperity::python
