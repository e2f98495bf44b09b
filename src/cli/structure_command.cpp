// asperity structure: a bolted structure of finite elements from a case file (geometry
// meshed by gmsh, or a mesh file) to a reduced model with zero-thickness interface
// elements and its linear modes at the bolt preload (format: docs/structures.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>

#include "asperity/core/error.hpp"
#include "asperity/fem/mesh_io.hpp"
#include "asperity/fem/structure.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/vibration/quasi_static_fretting.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {
namespace {

using namespace asperity::fem;

struct StructureOptionsCli {
  std::string case_file;
  std::optional<std::string> out_dir;
  bool json = false;
  bool no_plots = false;
  bool fretting = false;
  std::string gmsh = "gmsh";
};

Json vec_json(const Eigen::VectorXd& v) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

Json summary(const StructureCase& c, const StructureResult& r) {
  Json j;
  j["case"] = c.path;
  j["name"] = c.name;
  j["mesh"] = {{"nodes", r.mesh.node_count()},
               {"elements", r.mesh.element_count()},
               {"bodies", r.mesh.bodies},
               {"shared_nodes_split", r.shared_nodes_split},
               {"mass_kg", r.total_mass}};
  Json itfs = Json::array();
  for (std::size_t i = 0; i < r.interfaces.size(); ++i) {
    const auto& itf = r.interfaces[i];
    itfs.push_back({{"name", itf.name},
                    {"bodies",
                     {r.mesh.bodies[static_cast<std::size_t>(itf.body_a)],
                      r.mesh.bodies[static_cast<std::size_t>(itf.body_b)]}},
                    {"faces", itf.face_pairs.size()},
                    {"elements", itf.patches.size()},
                    {"area_m2", itf.area},
                    {"normal_stiffness_Pa_per_m", c.interfaces[i].normal_stiffness},
                    {"tangential_stiffness_Pa_per_m", c.interfaces[i].tangential_stiffness}});
  }
  j["interfaces"] = itfs;
  Json bolts = Json::array();
  for (const auto& b : r.bolts)
    bolts.push_back({{"name", b.spec.name},
                     {"preload_N", b.spec.preload},
                     {"length_m", b.length},
                     {"axial_stiffness_N_per_m", b.axial_stiffness},
                     {"head_footprint_nodes", b.head_nodes.size()},
                     {"nut_footprint_nodes", b.nut_nodes.size()}});
  j["bolts"] = bolts;
  // The rigid-body modes of the structure held by its bolts alone (interface open).
  j["rigid_body_modes"] = r.analyses.empty() ? 0 : r.analyses.front().modes.rigid_body_modes;
  Json lm;
  for (const auto& a : r.analyses)
    lm[a.name] = {{"frequency_hz", vec_json(a.modes.frequency_hz)},
                  {"rigid_body_modes", a.modes.rigid_body_modes}};
  j["linear_modes"] = lm;
  if (!r.interfaces.empty()) {
    double force = 0.0;
    for (Eigen::Index e = 0; e < r.prestress.pressure.size(); ++e)
      force += r.prestress.pressure[e] * r.model.elements[static_cast<std::size_t>(e)].area;
    j["prestress"] = {
        {"model", "linear normal penalty, frictionless, contact set by active set"},
        {"bolt_load_N", r.bolt_load_total},
        {"interface_normal_force_N", force},
        {"contact_area_m2", r.prestress.contact_area},
        {"max_pressure_Pa", r.prestress.pressure.size() ? r.prestress.pressure.maxCoeff() : 0.0},
        {"active_set_iterations", r.prestress.iterations}};
  }
  if (r.rough) {
    const RoughPrestress& q = *r.rough;
    j["rough_prestress"] = {
        {"model",
         "rough flat (thesis Eq. 4.4) per interface element, frictionless while the bolts are "
         "tightened; stiffnesses linearised about it (docs/rough_contact.md)"},
        {"asperity_model", std::string(contact::to_string(c.rough.model))},
        {"summit_heights", c.rough.heights ? fmt::format("measured table ({} points)",
                                                         c.rough.heights->z_star().size())
                                           : std::string("gaussian")},
        {"sigma_m", c.rough.sigma},
        {"bolt_load_N", q.bolt_load},
        {"interface_normal_force_N", q.interface_load},
        {"contact_area_m2", q.contact_area},
        {"real_contact_area_m2", q.real_contact_area},
        {"max_pressure_Pa", q.pressure.maxCoeff()},
        {"elements_in_contact", std::count(q.in_contact.begin(), q.in_contact.end(), char{1})},
        {"newton_iterations", q.iterations},
        {"relative_residual", q.residual},
        {"gap_map", c.rough.gap_map.empty() ? Json(nullptr) : Json(c.rough.gap_map)},
        {"max_gap_m", r.gap.size() ? r.gap.maxCoeff() : 0.0}};
  }
  j["reduced_model"] = {{"dofs", r.model.dofs()},
                        {"interface_elements", r.model.elements.size()},
                        {"fixed_interface_modes", r.model.fixed_interface_modes},
                        {"tied_rigid_body_modes", r.reduction.rigid_body_modes},
                        {"static_vectors", r.reduction.static_vectors},
                        {"outputs", r.model.output_names}};
  Json costs = Json::array();
  for (const auto& s : r.costs)
    costs.push_back({{"step", s.step}, {"seconds", s.seconds}, {"peak_rss_MiB", s.peak_rss_mib}});
  j["costs"] = costs;
  return j;
}

std::string text_summary(const StructureCase& c, const StructureResult& r) {
  std::string out =
      fmt::format("{}: {} nodes, {} quadratic elements, {} bodies, {:.4g} kg\n", c.path,
                  r.mesh.node_count(), r.mesh.element_count(), r.mesh.bodies.size(), r.total_mass);
  for (const auto& itf : r.interfaces)
    out += fmt::format("interface {}: {} face pairs, {:.4g} mm^2, {} zero-thickness elements\n",
                       itf.name, itf.face_pairs.size(), itf.area * 1e6, itf.patches.size());
  out += fmt::format("reduced model: {} DOFs ({} interface, {} fixed-interface modes)\n",
                     r.model.dofs(), r.reduction.interface_dofs,
                     r.model.dofs() - r.reduction.interface_dofs);
  if (!r.interfaces.empty()) {
    double force = 0.0;
    for (Eigen::Index e = 0; e < r.prestress.pressure.size(); ++e)
      force += r.prestress.pressure[e] * r.model.elements[static_cast<std::size_t>(e)].area;
    out += fmt::format(
        "prestress: bolts {:.6g} N, interface normal force {:.6g} N, contact area "
        "{:.4g} mm^2\n",
        r.bolt_load_total, force, r.prestress.contact_area * 1e6);
  }
  if (r.rough)
    out += fmt::format(
        "rough prestress: interface normal force {:.6g} N, {} of {} elements in contact "
        "({:.4g} mm^2), real contact area {:.4g} mm^2, largest pressure {:.4g} MPa\n",
        r.rough->interface_load,
        std::count(r.rough->in_contact.begin(), r.rough->in_contact.end(), char{1}),
        r.rough->in_contact.size(), r.rough->contact_area * 1e6, r.rough->real_contact_area * 1e6,
        r.rough->pressure.maxCoeff() * 1e-6);
  for (const auto& a : r.analyses) {
    std::string f;
    for (Eigen::Index i = 0; i < std::min<Eigen::Index>(6, a.modes.frequency_hz.size()); ++i)
      f += fmt::format("{}{:.2f}", i ? ", " : "", a.modes.frequency_hz[i]);
    out += fmt::format("{:<13} {} rigid-body modes; elastic modes [Hz]: {}\n", a.name + ":",
                       a.modes.rigid_body_modes, f);
  }
  for (const auto& s : r.costs)
    out += fmt::format("  {:<28} {:7.2f} s, peak memory {:.0f} MiB\n", s.step, s.seconds,
                       s.peak_rss_mib);
  return out;
}

// A view of the outer edges of the mesh on the axes (h, v), displaced by `u` (mesh DOFs)
// when given.
Series mesh_edges(const StructureResult& r, const std::vector<BoundaryFace>& faces,
                  const Eigen::VectorXd* u, double scale, const std::string& title,
                  const std::string& style, int h = 0, int v = 2) {
  Series s{.title = title, .style = style};
  auto at = [&](std::int32_t node) {
    Eigen::Vector3d x = r.mesh.nodes.col(node);
    if (u) x += scale * u->segment<3>(3 * Eigen::Index{node});
    return x;
  };
  for (const auto& f : faces) {
    const int nc = f.node_count == 6 ? 3 : 4;
    for (int i = 0; i <= nc; ++i) {
      const Eigen::Vector3d x = at(f.nodes[i % nc]);
      s.x.push_back(x[h] * 1e3);
      s.y.push_back(x[v] * 1e3);
    }
    s.x.push_back(std::nan(""));
    s.y.push_back(std::nan(""));
  }
  return s;
}

void write_files(const StructureCase& c, const StructureResult& r, joint::StagedDirectory& dir,
                 bool plots, std::vector<std::string>& written) {
  write_file_atomically(dir.file("summary.json"), json_output(summary(c, r)));
  written.push_back("summary.json");
  write_reduced_model(dir.file("reduced_model.mat"), r.model);
  written.push_back("reduced_model.mat");
  // Mode shapes (first 6 elastic of each analysis) and the prestress pressure on side A.
  std::vector<PointField> fields;
  const auto nn = r.mesh.node_count();
  for (const auto& a : r.analyses)
    for (Eigen::Index k = 0; k < std::min<Eigen::Index>(6, a.modes.frequency_hz.size()); ++k) {
      const Eigen::VectorXd u = r.reduction.expand(a.modes.shapes.col(k));
      fields.push_back({fmt::format("{}_mode_{}_{:.1f}Hz", a.name, k + 1, a.modes.frequency_hz[k]),
                        Eigen::Map<const Eigen::MatrixXd>(u.data(), 3, nn)});
    }
  if (!r.interfaces.empty()) {
    Eigen::MatrixXd p = Eigen::MatrixXd::Zero(1, nn), id = Eigen::MatrixXd::Constant(1, nn, -1.0);
    Eigen::Index e = 0;
    for (const auto& itf : r.interfaces)
      for (const auto& patch : itf.patches) {
        for (const auto fi : patch.faces)
          for (int i = 0; i < itf.face_pairs[static_cast<std::size_t>(fi)].side_a.node_count; ++i) {
            const auto node = itf.face_pairs[static_cast<std::size_t>(fi)].side_a.nodes[i];
            p(0, node) = r.prestress.pressure[e];
            id(0, node) = static_cast<double>(e);
          }
        ++e;
      }
    fields.push_back({"prestress_pressure_Pa", p});
    fields.push_back({"interface_element", id});
    if (r.rough) {
      Eigen::MatrixXd rp = Eigen::MatrixXd::Zero(1, nn), gp = Eigen::MatrixXd::Zero(1, nn);
      for (Eigen::Index node = 0; node < nn; ++node)
        if (id(0, node) >= 0) {
          const auto el = static_cast<Eigen::Index>(id(0, node));
          rp(0, node) = r.rough->pressure[el];
          if (r.gap.size()) gp(0, node) = r.gap[el];
        }
      fields.push_back({"rough_pressure_Pa", rp});
      if (r.gap.size()) fields.push_back({"gap_m", gp});
    }
  }
  write_vtu(dir.file("structure.vtu"), r.mesh, fields);
  written.push_back("structure.vtu");
  if (!plots) return;
  const auto faces = boundary_faces(r.mesh);
  // The longest extent horizontal; the view's vertical axis: for the mesh the shortest
  // extent, for a mode the axis it moves most along.
  const Eigen::Vector3d extent3 =
      r.mesh.nodes.rowwise().maxCoeff() - r.mesh.nodes.rowwise().minCoeff();
  int h = 0;
  extent3.maxCoeff(&h);
  auto other = [&](const Eigen::Vector3d& w) {
    int best = -1;
    for (int k = 0; k < 3; ++k)
      if (k != h && (best < 0 || w[k] > w[best])) best = k;
    return best;
  };
  const char* axis = "xyz";
  const int vm = h != 2 ? 2 : 1;  // a side view, z up, unless z is the longest
  PlotSpec m{.title = fmt::format("{}: mesh ({} nodes, {} elements)", c.name, r.mesh.node_count(),
                                  r.mesh.element_count()),
             .xlabel = fmt::format("{} [mm]", axis[h]),
             .ylabel = fmt::format("{} [mm]", axis[vm]),
             .extra = "set size ratio -1\nunset key"};
  m.series.push_back(mesh_edges(r, faces, nullptr, 0, "mesh", "lines lc rgb '#4060a0'", h, vm));
  plot_png(dir.file("mesh.png"), m);
  written.push_back("mesh.png");
  if (r.rough) {
    // The interface seen along its normal: elements by pressure class (eight equal classes
    // up to the largest pressure), those out of contact in grey.
    const RoughPrestress& q = *r.rough;
    const double pmax = q.pressure.maxCoeff();
    constexpr int kClasses = 8;
    static const char* colours[kClasses] = {"#fde725", "#a0da39", "#4ac16d", "#1fa187",
                                            "#277f8e", "#365c8d", "#46327e", "#440154"};
    PlotSpec pm{.title = fmt::format("{}: interface pressure at the bolt preloads (rough flat, "
                                     "{}), {} N",
                                     c.name, contact::to_string(c.rough.model), q.bolt_load),
                .xlabel = "x [mm]",
                .ylabel = "y [mm]",
                .extra = "set size ratio -1\nset key outside right"};
    Series open{.title = "out of contact", .style = "points pt 5 ps 1.2 lc rgb '#d0d0d0'"};
    std::vector<Series> cls(kClasses);
    for (int k = 0; k < kClasses; ++k) {
      cls[k].title = fmt::format("{:.0f}-{:.0f} MPa", pmax * k / kClasses * 1e-6,
                                 pmax * (k + 1) / kClasses * 1e-6);
      cls[k].style = fmt::format("points pt 5 ps 1.2 lc rgb '{}'", colours[k]);
    }
    for (std::size_t e = 0; e < r.model.elements.size(); ++e) {
      const Eigen::Vector3d x = r.model.elements[e].centroid * 1e3;
      const double p = q.pressure[static_cast<Eigen::Index>(e)];
      Series& target = q.in_contact[e] ? cls[static_cast<std::size_t>(std::min(
                                             kClasses - 1, static_cast<int>(p / pmax * kClasses)))]
                                       : open;
      target.x.push_back(x.x());
      target.y.push_back(x.y());
    }
    if (!open.x.empty()) pm.series.push_back(open);
    for (auto& s : cls)
      if (!s.x.empty()) pm.series.push_back(s);
    plot_png(dir.file("interface_pressure.png"), pm);
    written.push_back("interface_pressure.png");
  }
  const double extent =
      (r.mesh.nodes.rowwise().maxCoeff() - r.mesh.nodes.rowwise().minCoeff()).norm();
  for (const auto& a : r.analyses) {
    if (a.name != "stuck") continue;
    for (Eigen::Index k = 0; k < std::min<Eigen::Index>(3, a.modes.frequency_hz.size()); ++k) {
      const Eigen::VectorXd u = r.reduction.expand(a.modes.shapes.col(k));
      double umax = 0;
      Eigen::Vector3d moved = Eigen::Vector3d::Zero();
      for (Eigen::Index i = 0; i < nn; ++i) {
        umax = std::max(umax, u.segment<3>(3 * i).norm());
        moved += u.segment<3>(3 * i).cwiseAbs();
      }
      const int v = other(moved);
      const double scale = umax > 0 ? 0.08 * extent / umax : 0.0;
      PlotSpec p{.title = fmt::format("{}: mode {} of the stuck interface, {:.2f} Hz ({}-{} view, "
                                      "displacement exaggerated)",
                                      c.name, k + 1, a.modes.frequency_hz[k], axis[h], axis[v]),
                 .xlabel = fmt::format("{} [mm]", axis[h]),
                 .ylabel = fmt::format("{} [mm]", axis[v]),
                 .extra = "set size ratio -1\nset key bottom right"};
      p.series.push_back(
          mesh_edges(r, faces, nullptr, 0, "undeformed", "lines lc rgb '#c0c0c0'", h, v));
      p.series.push_back(
          mesh_edges(r, faces, &u, scale, "mode shape", "lines lc rgb '#b02020'", h, v));
      const auto name = fmt::format("mode_{}.png", k + 1);
      plot_png(dir.file(name), p);
      written.push_back(name);
    }
  }
}

// --fretting: the case's [fretting] apparatus (quasi-static cycles, no reduction).
Json fretting_summary(const StructureCase& c, const vibration::StructureFretting& r) {
  const auto& f = c.fretting;
  Json j;
  j["case"] = c.path;
  j["name"] = c.name;
  j["mesh"] = {{"nodes", r.mesh_nodes}, {"dofs", r.mesh_dofs}, {"mass_kg", r.total_mass}};
  j["apparatus"] = {
      {"model",
       "held grip: every DOF of its face held (the load cell); driven grip: its face moves by z "
       "along `direction`, other components held, a spring k from the actuator's tip to z (Fig. "
       "5.7); delta = z (the laser sensor), Q = k (Delta - z) (the load cell); the bodies "
       "condensed exactly onto the interface, drive and bolt coordinates (docs/structures.md)"},
      {"held", {{"body", f.fixture.held.body}, {"nodes", r.held_nodes}}},
      {"driven", {{"body", f.fixture.driven.body}, {"nodes", r.driven_nodes}}},
      {"drive_stiffness_N_per_m", f.fixture.drive_stiffness},
      {"interface_elements", r.interface_elements},
      {"harmonics", f.harmonics},
      {"time_points", f.time_points}};
  Json runs = Json::array();
  for (const auto& run : r.runs) {
    Json cycles = Json::array();
    const auto& cy = run.fretting.cycles;
    for (std::size_t i = 0; i < cy.size(); ++i) {
      Json e = {{"tip_amplitude_m", cy[i].tip_amplitude},
                {"force_amplitude_N", cy[i].force_amplitude},
                {"displacement_amplitude_m", cy[i].displacement_amplitude},
                {"energy_J", cy[i].energy},
                {"newton_iterations", cy[i].iterations},
                {"relative_residual", cy[i].residual}};
      const bool have = i > 0 && std::isfinite(run.exponents[i - 1]);
      e["energy_force_exponent"] = have ? Json(run.exponents[i - 1]) : Json(nullptr);
      cycles.push_back(e);
    }
    const auto& q = run.prestress;
    runs.push_back({{"total_preload_N", run.total_preload},
                    {"interface_normal_force_N", q.interface_load},
                    {"preload_through_grips_N", run.total_preload - q.interface_load},
                    {"contact_area_m2", q.contact_area},
                    {"real_contact_area_m2", q.real_contact_area},
                    {"max_pressure_Pa", q.pressure.maxCoeff()},
                    {"elements_in_contact", run.elements_in_contact},
                    {"stiffness_N_per_m", run.fretting.stiffness},
                    {"cycles", cycles}});
  }
  j["fretting"] = runs;
  Json costs = Json::array();
  for (const auto& s : r.costs)
    costs.push_back({{"step", s.step}, {"seconds", s.seconds}, {"peak_rss_MiB", s.peak_rss_mib}});
  j["costs"] = costs;
  return j;
}

std::string fretting_text(const StructureCase& c, const vibration::StructureFretting& r) {
  std::string out = fmt::format(
      "{}: {} nodes, in the apparatus: {} held and {} driven grip nodes, drive {:.4g} N/um, {} "
      "interface elements\n",
      c.path, r.mesh_nodes, r.held_nodes, r.driven_nodes, c.fretting.fixture.drive_stiffness * 1e-6,
      r.interface_elements);
  for (const auto& run : r.runs) {
    out += fmt::format(
        "bolts {:.6g} N ({:.4g} N of it through the grips): {} elements in contact, real contact "
        "area {:.4g} mm^2, stuck joint stiffness {:.4g} N/um\n",
        run.total_preload, run.total_preload - run.prestress.interface_load,
        run.elements_in_contact, run.prestress.real_contact_area * 1e6,
        run.fretting.stiffness * 1e-6);
    out += "  Delta_0 [um]   Q_0 [N]   delta_0 [um]   W [uJ]    n\n";
    const auto& cy = run.fretting.cycles;
    for (std::size_t i = 0; i < cy.size(); ++i)
      out += fmt::format(
          "  {:10.4g} {:9.4g} {:12.4g} {:10.4g} {:>6}\n", cy[i].tip_amplitude * 1e6,
          cy[i].force_amplitude, cy[i].displacement_amplitude * 1e6, cy[i].energy * 1e6,
          i > 0 && std::isfinite(run.exponents[i - 1]) ? fmt::format("{:.3f}", run.exponents[i - 1])
                                                       : std::string("-"));
  }
  for (const auto& s : r.costs)
    out += fmt::format("  {:<28} {:7.2f} s, peak memory {:.0f} MiB\n", s.step, s.seconds,
                       s.peak_rss_mib);
  return out;
}

void write_fretting_files(const StructureCase& c, const vibration::StructureFretting& r,
                          joint::StagedDirectory& dir, bool plots,
                          std::vector<std::string>& written) {
  write_file_atomically(dir.file("summary.json"), json_output(fretting_summary(c, r)));
  written.push_back("summary.json");
  std::string cyc =
      "total_preload_N,tip_amplitude_m,force_amplitude_N,displacement_amplitude_m,energy_J,"
      "stiffness_N_per_m\n";
  std::string loops = "total_preload_N,tip_amplitude_m,sample,delta_m,force_N\n";
  for (const auto& run : r.runs)
    for (const auto& cy : run.fretting.cycles) {
      cyc += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", run.total_preload,
                         cy.tip_amplitude, cy.force_amplitude, cy.displacement_amplitude, cy.energy,
                         run.fretting.stiffness);
      for (Eigen::Index i = 0; i < cy.delta.size(); ++i)
        loops += fmt::format("{:.17g},{:.17g},{},{:.17g},{:.17g}\n", run.total_preload,
                             cy.tip_amplitude, i, cy.delta[i], cy.force[i]);
    }
  write_file_atomically(dir.file("fretting_cycles.csv"), cyc);
  write_file_atomically(dir.file("fretting_loops.csv"), loops);
  written.push_back("fretting_cycles.csv");
  written.push_back("fretting_loops.csv");
  if (!plots) return;
  static const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  PlotSpec lp{.title = fmt::format("{}: fretting loops in the apparatus (largest tip amplitude "
                                   "{:.3g} um)",
                                   c.name, c.fretting.tip_amplitudes.back() * 1e6),
              .xlabel = "joint displacement delta [um]",
              .ylabel = "friction force Q [N]",
              .extra = "set key outside right"};
  PlotSpec ep{.title = fmt::format("{}: energy per cycle against force amplitude", c.name),
              .xlabel = "force amplitude Q_0 [N]",
              .ylabel = "energy per cycle W [µJ]",
              .logx = true,
              .logy = true,
              .extra = "set key inside left top box opaque\n"};
  double qmin = 1e300, qmax = 0.0, emin = 1e300, emax = 0.0;
  for (std::size_t k = 0; k < r.runs.size(); ++k) {
    const auto& run = r.runs[k];
    const char* colour = colours[k % 6];
    Series e{.title = fmt::format("{:.0f} N", run.total_preload),
             .style = fmt::format("linespoints pt 7 lc rgb '{}'", colour)};
    for (std::size_t i = 0; i < run.fretting.cycles.size(); ++i) {
      const auto& cy = run.fretting.cycles[i];
      if (cy.energy > 0.0) {
        e.x.push_back(cy.force_amplitude);
        e.y.push_back(cy.energy * 1e6);
        qmin = std::min(qmin, cy.force_amplitude);
        qmax = std::max(qmax, cy.force_amplitude);
        emin = std::min(emin, cy.energy * 1e6);
        emax = std::max(emax, cy.energy * 1e6);
      }
      Series l{.title = i + 1 == run.fretting.cycles.size()
                            ? fmt::format("{:.0f} N", run.total_preload)
                            : std::string(),
               .style = fmt::format("lines lc rgb '{}'", colour)};
      for (Eigen::Index s = 0; s <= cy.delta.size(); ++s) {
        const Eigen::Index w = s % cy.delta.size();
        l.x.push_back(cy.delta[w] * 1e6);
        l.y.push_back(cy.force[w]);
      }
      lp.series.push_back(std::move(l));
    }
    ep.series.push_back(std::move(e));
  }
  // Slope-2 and slope-3 guides (Fig. 6.12-6.14) through the first preload's smallest cycle.
  if (!ep.series.front().x.empty()) {
    add_power_guides(ep, ep.series.front().x.front(), ep.series.front().y.front(), qmin, qmax);
    set_energy_force_ranges(ep, qmin, qmax, emin, emax);
  }
  plot_png(dir.file("fretting_loops.png"), lp);
  plot_png(dir.file("fretting_energy.png"), ep);
  written.push_back("fretting_loops.png");
  written.push_back("fretting_energy.png");
}

void run_fretting_cli(const StructureOptionsCli& o, const StructureCase& c,
                      const StructureOptions& options, std::string& out) {
  if (!c.fretting.given) {
    throw InvalidInput(fmt::format(
        "{}: --fretting needs a [fretting] table (the apparatus: held and driven grips, "
        "drive_stiffness, tip_amplitudes; docs/structures.md)",
        c.path));
  }
  const auto r = vibration::structure_fretting(c, options);
  std::vector<std::string> written;
  if (o.out_dir) {
    joint::StagedDirectory dir(*o.out_dir, "asperity structure");
    write_fretting_files(c, r, dir, !o.no_plots, written);
    dir.commit();
  }
  out = o.json ? json_output(fretting_summary(c, r)) : fretting_text(c, r);
  if (!o.json && o.out_dir) {
    std::string list;
    for (const auto& f : written) list += (list.empty() ? "" : ", ") + f;
    out += fmt::format("wrote {}/ ({})\n", *o.out_dir, list);
  }
}

void run_structure_cli(const StructureOptionsCli& o, std::string& out) {
  if (o.out_dir) require_case_output_directory(*o.out_dir, o.case_file);
  const StructureCase c = read_structure_case(o.case_file);
  StructureOptions options;
  options.meshing.gmsh = o.gmsh;
  options.progress = [](const std::string& step) {
    fmt::print(stderr, "asperity structure: {}\n", step);
    std::fflush(stderr);
  };
  if (o.fretting) {
    run_fretting_cli(o, c, options, out);
    return;
  }
  const StructureResult r = run_structure(c, options);
  std::vector<std::string> written;
  if (o.out_dir) {
    joint::StagedDirectory dir(*o.out_dir, "asperity structure");
    write_files(c, r, dir, !o.no_plots, written);
    dir.commit();
  }
  out = o.json ? json_output(summary(c, r)) : text_summary(c, r);
  if (!o.json && o.out_dir) {
    std::string list;
    for (const auto& f : written) list += (list.empty() ? "" : ", ") + f;
    out += fmt::format("wrote {}/ ({})\n", *o.out_dir, list);
  }
}

}  // namespace

void add_structure_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<StructureOptionsCli>();
  auto* cmd = app.add_subcommand(
      "structure",
      "A bolted structure of finite elements: mesh (gmsh), assemble (10-node tetrahedra), bolts "
      "(beam shanks on distributing couplings, pretension), contact interfaces as zero-thickness "
      "elements, Craig-Bampton reduction, linear modes with the interface open, in frictionless "
      "contact and stuck. Writes summary.json, reduced_model.mat, structure.vtu and PNG pictures "
      "(format: docs/structures.md, examples/brb).");
  cmd->add_option("case", o->case_file, "TOML structure case file")->required();
  cmd->add_option("--out", o->out_dir,
                  "output directory, written whole (created; an existing one is replaced only if "
                  "asperity wrote it); without it only the summary is printed");
  cmd->add_flag("--json", o->json, "print summary.json instead of the text summary");
  cmd->add_flag("--no-plots", o->no_plots, "skip the PNG pictures (no gnuplot needed)");
  cmd->add_flag(
      "--fretting", o->fretting,
      "instead of the reduction and modes: the case's [fretting] apparatus (thesis ch. "
      "5: one end held, the other driven through the actuator's compliance), quasi-static "
      "fretting cycles at each tip amplitude and bolt preload with the rough interface; "
      "writes summary.json, fretting_cycles.csv, fretting_loops.csv and PNG pictures");
  cmd->add_option("--gmsh", o->gmsh, "the gmsh program (a separate program: GPL) (default: gmsh)");
  cmd->callback([o, &action] {
    action = [o] { return run_guarded([o](std::string& out) { run_structure_cli(*o, out); }); };
  });
}

}  // namespace asperity::cli
