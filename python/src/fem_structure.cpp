// asperity.fem: the steps of `asperity structure` (mesh, interfaces, bolts, reduction,
// linear modes) and reduced-model files, as dicts of numpy arrays.
#include <nanobind/eigen/dense.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <string>
#include <vector>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/fem/mesh_io.hpp"
#include "asperity/fem/reduced_model.hpp"
#include "asperity/fem/rough_prestress.hpp"
#include "asperity/fem/structure.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "asperity/vibration/quasi_static_fretting.hpp"
#include "bindings.hpp"
#include "summit_table.hpp"

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
  // [rough_contact]: the rough surface (combined values, SI) and each element's prestress.
  if (m.rough) {
    const RoughInterfaceRecord& r = *m.rough;
    nb::dict rd;
    rd["E_star"] = r.E_star;
    rd["G_star"] = r.G_star;
    rd["H"] = r.H;
    rd["nu"] = r.nu;
    rd["sigma"] = r.sigma;
    rd["R"] = r.R;
    rd["eta"] = r.eta;
    rd["summit_sigma"] = r.summit_sigma;
    if (r.summit_heights)
      rd["summit_heights"] = summit_table_array(*r.summit_heights, r.sigma);
    else
      rd["summit_heights"] = nb::none();
    rd["model"] = r.model;
    rd["pressure"] = array(r.pressure);
    Eigen::Matrix<bool, Eigen::Dynamic, 1> touching(static_cast<Eigen::Index>(r.in_contact.size()));
    for (std::size_t e = 0; e < r.in_contact.size(); ++e)
      touching[static_cast<Eigen::Index>(e)] = r.in_contact[e] != 0;
    rd["in_contact"] = nb::cast(touching, nb::rv_policy::move);
    d["rough"] = rd;
  } else {
    d["rough"] = nb::none();
  }
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

// --fretting's run (vibration::structure_fretting) with the C++ result's names; each cycle
// with its loop (delta, force samples).
nb::dict fretting(const std::string& path, const std::string& gmsh) {
  const StructureCase c = read_structure_case(path);
  StructureOptions o;
  o.meshing.gmsh = gmsh;
  const vibration::StructureFretting r = [&] {
    nb::gil_scoped_release release;
    return vibration::structure_fretting(c, o);
  }();
  nb::dict d;
  d["mesh_nodes"] = r.mesh_nodes;
  d["mesh_dofs"] = r.mesh_dofs;
  d["interface_elements"] = r.interface_elements;
  d["held_nodes"] = r.held_nodes;
  d["driven_nodes"] = r.driven_nodes;
  d["drive_stiffness"] = c.fretting.fixture.drive_stiffness;
  d["mass"] = r.total_mass;
  nb::list runs;
  for (const auto& run : r.runs) {
    nb::dict rd;
    rd["total_preload"] = run.total_preload;
    rd["interface_load"] = run.prestress.interface_load;
    rd["preload_through_grips"] = run.total_preload - run.prestress.interface_load;
    rd["contact_area"] = run.prestress.contact_area;
    rd["real_contact_area"] = run.prestress.real_contact_area;
    rd["pressure"] = array(run.prestress.pressure);
    rd["elements_in_contact"] = run.elements_in_contact;
    rd["stiffness"] = run.fretting.stiffness;
    nb::list cycles;
    for (const auto& cy : run.fretting.cycles) {
      nb::dict cd;
      cd["tip_amplitude"] = cy.tip_amplitude;
      cd["force_amplitude"] = cy.force_amplitude;
      cd["displacement_amplitude"] = cy.displacement_amplitude;
      cd["energy"] = cy.energy;
      cd["delta"] = array(cy.delta);
      cd["force"] = array(cy.force);
      cd["iterations"] = cy.iterations;
      cd["residual"] = cy.residual;
      cycles.append(cd);
    }
    rd["cycles"] = cycles;
    rd["exponents"] = array(Eigen::Map<const Eigen::VectorXd>(
        run.exponents.data(), static_cast<Eigen::Index>(run.exponents.size())));
    runs.append(rd);
  }
  d["runs"] = runs;
  nb::list costs;
  for (const auto& s : r.costs) costs.append(nb::make_tuple(s.step, s.seconds, s.peak_rss_mib));
  d["costs"] = costs;
  return d;
}

}  // namespace

void bind_fem_structure(nb::module_& m) {
  m.def("fem_run_structure", &run, "path"_a, "gmsh"_a = "gmsh",
        "Runs a structure case file (asperity structure): mesh, reduced model, linear modes.");
  m.def("fem_structure_fretting", &fretting, "path"_a, "gmsh"_a = "gmsh",
        "Runs a structure case file's [fretting] apparatus (asperity structure --fretting): "
        "quasi-static cycles per total bolt preload.");
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
  m.def(
      "fem_rough_prestress",
      [](const std::string& path, double E_star, double G_star, double H, double nu,
         std::optional<double> sigma_given, double R, double eta, const std::string& model,
         bool summit_sigma, const Eigen::VectorXd& gap,
         const std::optional<Eigen::MatrixXd>& summit_heights) {
        const ReducedModel rm = read_reduced_model(path);
        double sigma = 0.0;
        auto table = summit_table_from(summit_heights, sigma_given, sigma, summit_sigma);
        // The rough flat per unit nominal area (A0 = 1 m^2): its force scale is K H [Pa].
        const auto flat = surface::RoughFlat::from_combined(E_star, G_star, H, nu, sigma, R, eta,
                                                            contact::parse_model_name(model), {},
                                                            summit_sigma, std::move(table));
        const RoughSurfaceScales scales{
            .sigma = sigma, .pressure_scale = contact::hardness_factor(nu) * H, .eta = eta};
        const RoughPrestress r = [&] {
          nb::gil_scoped_release release;
          return rough_prestress(rm, flat, scales, gap);
        }();
        nb::dict d;
        d["x"] = array(r.x);
        d["pressure"] = array(r.pressure);
        d["separation_star"] = array(r.separation_star);
        d["real_area_ratio"] = array(r.real_area_ratio);
        d["normal_stiffness"] = array(r.normal_stiffness);
        d["tangential_stiffness"] = array(r.tangential_stiffness);
        Eigen::Matrix<bool, Eigen::Dynamic, 1> touching(
            static_cast<Eigen::Index>(r.in_contact.size()));
        for (std::size_t e = 0; e < r.in_contact.size(); ++e)
          touching[static_cast<Eigen::Index>(e)] = r.in_contact[e] != 0;
        d["in_contact"] = nb::cast(touching, nb::rv_policy::move);
        d["interface_load"] = r.interface_load;
        d["bolt_load"] = r.bolt_load;
        d["contact_area"] = r.contact_area;
        d["real_contact_area"] = r.real_contact_area;
        d["iterations"] = r.iterations;
        d["residual"] = r.residual;
        return d;
      },
      "path"_a, "E_star"_a, "G_star"_a, "H"_a, "nu"_a, "sigma"_a.none(), "R"_a, "eta"_a, "model"_a,
      "summit_sigma"_a, "gap"_a, "summit_heights"_a.none() = nb::none(),
      "The bolt preloads of a reduced model file on its interface with the rough flat's normal "
      "law (fem::rough_prestress): pressures, contact area, linearised stiffnesses.");
}

}  // namespace asperity::python
