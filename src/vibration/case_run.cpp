#include "asperity/vibration/case.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <complex>
#include <cstring>
#include <limits>
#include <numbers>
#include <optional>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/vibration/rough_contact.hpp"

namespace asperity::vibration {

namespace {

SummaryArray array(const Eigen::VectorXd& v) {
  SummaryArray a;
  a.reserve(static_cast<std::size_t>(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) a.emplace_back(v(i));
  return a;
}

// Rows of a matrix (points x outputs) as [[...], ...].
SummaryArray rows(const Eigen::MatrixXd& m) {
  SummaryArray a;
  for (Eigen::Index i = 0; i < m.rows(); ++i) a.emplace_back(array(m.row(i).transpose()));
  return a;
}

// Hill's stability per point (stability.hpp): flags, the leading exponent and
// multiplier, and the reported Floquet exponents as [Re, Im] pairs [1/s].
SummaryObject stability_summary(const std::vector<PeriodicStability>& st) {
  SummaryArray stable, max_re, max_mu, kind, exponents;
  for (const PeriodicStability& p : st) {
    stable.emplace_back(p.stable);
    max_re.emplace_back(p.max_real_exponent);
    max_mu.emplace_back(p.max_multiplier_modulus);
    kind.emplace_back(p.instability);
    SummaryArray e;
    for (Eigen::Index k = 0; k < p.exponents.size(); ++k) {
      e.emplace_back(SummaryArray{p.exponents(k).real(), p.exponents(k).imag()});
    }
    exponents.emplace_back(std::move(e));
  }
  return {{"method", "hill"},
          {"stable", std::move(stable)},
          {"max_real_exponent_per_s", std::move(max_re)},
          {"max_multiplier_modulus", std::move(max_mu)},
          {"instability", std::move(kind)},
          {"floquet_exponents_per_s", std::move(exponents)}};
}

// First-harmonic displacement and acceleration amplitudes of each output point along a
// curve of points U (coefficients in HarmonicBalance's layout) at frequencies omega.
std::vector<OutputPointResponse> output_point_responses(const HarmonicBalance& hb,
                                                        const std::vector<OutputPoint>& points,
                                                        const std::vector<Eigen::VectorXd>& U,
                                                        const Eigen::VectorXd& omega) {
  std::vector<OutputPointResponse> out;
  const long ic = hb.basis().index_of(1, 0), is = hb.basis().index_of(1, 1);
  const auto nc = static_cast<Eigen::Index>(hb.basis().coefficients());
  const auto np = static_cast<Eigen::Index>(U.size());
  for (const OutputPoint& op : points) {
    OutputPointResponse r{.name = op.name,
                          .displacement = Eigen::MatrixXd(np, 3),
                          .acceleration = Eigen::MatrixXd(np, 3)};
    for (Eigen::Index k = 0; k < np; ++k) {
      const Eigen::Map<const Eigen::MatrixXd> X(U[static_cast<std::size_t>(k)].data(), nc,
                                                hb.dofs());
      const Eigen::MatrixXd x = X * op.rows.transpose();  // nc x 3
      for (Eigen::Index d = 0; d < 3; ++d) {
        const double a = std::hypot(x(ic, d), x(is, d));
        r.displacement(k, d) = a;
        r.acceleration(k, d) = omega(k) * omega(k) * a;
      }
    }
    out.push_back(std::move(r));
  }
  return out;
}

// The interface along a curve of points U at frequencies omega: each sited element's work
// per cycle, 2 pi mean_i f(t_i) . du/dtheta(t_i) (exact for the projected force: du/dtheta is
// a trigonometric polynomial of the kept harmonics, so the mean of the samples' product is
// the integral of its product with the force's harmonic-balance projection), over its area;
// and a rough_contact element's cycle-mean normal pressure.
std::optional<InterfaceMap> interface_map(const HarmonicBalance& hb,
                                          const std::vector<ElementSite>& sites,
                                          const std::vector<Eigen::VectorXd>& U,
                                          const Eigen::VectorXd& omega) {
  InterfaceMap m;
  for (std::size_t e = 0; e < hb.elements().size() && e < sites.size(); ++e) {
    if (sites[e].interface_element >= 0 && sites[e].area > 0.0) m.elements.push_back(e);
  }
  if (m.elements.empty()) return std::nullopt;
  const auto np = static_cast<Eigen::Index>(U.size());
  const auto ne = static_cast<Eigen::Index>(m.elements.size());
  const auto nc = static_cast<Eigen::Index>(hb.basis().coefficients());
  const auto N = static_cast<double>(hb.basis().time_points());
  m.dissipation.resize(np, ne);
  m.mean_pressure.setConstant(np, ne, std::numeric_limits<double>::quiet_NaN());
  m.slip_fraction = m.mean_pressure;
  m.open_fraction = m.mean_pressure;
  const Eigen::MatrixXd& E = hb.basis().synthesis();
  const Eigen::MatrixXd& D = hb.basis().derivative();
  PeriodicResponse resp;
  for (Eigen::Index k = 0; k < np; ++k) {
    const Eigen::Map<const Eigen::MatrixXd> X(U[static_cast<std::size_t>(k)].data(), nc, hb.dofs());
    for (Eigen::Index j = 0; j < ne; ++j) {
      const std::size_t e = m.elements[static_cast<std::size_t>(j)];
      const PlacedElement& pe = hb.elements()[e];
      const Eigen::MatrixXd Xe = X * pe.T.transpose();
      const Eigen::MatrixXd u = E * Xe;
      const Eigen::MatrixXd du = E * (D * Xe);  // du/dtheta
      Eigen::MatrixXd v;
      if (pe.element->velocity_dependent()) v = omega(k) * du;
      pe.element->periodic_response(u, v, false, resp);
      m.dissipation(k, j) =
          2.0 * std::numbers::pi * resp.f.cwiseProduct(du).sum() / N / sites[e].area;
      // The element's normal force is the change from its prestress p0 A.
      if (const auto* rc = dynamic_cast<const RoughContactElement*>(pe.element.get())) {
        m.mean_pressure(k, j) = rc->prestress_pressure() + resp.f.col(2).mean() / rc->area();
        const auto open =
            ((rc->prestress_pressure() + resp.f.col(2).array() / rc->area()) <= 0.0).count();
        m.slip_fraction(k, j) = rc->gross_slip_fraction(resp);
        m.open_fraction(k, j) = static_cast<double>(open) / N;
      }
    }
  }
  return m;
}

SummaryObject interface_map_summary(const InterfaceMap& m, const std::vector<ElementSite>& sites) {
  SummaryArray elements, centroids, areas;
  for (const std::size_t e : m.elements) {
    elements.emplace_back(static_cast<std::size_t>(sites[e].interface_element));
    const Eigen::Vector3d& x = sites[e].centroid;
    centroids.emplace_back(SummaryArray{x(0), x(1), x(2)});
    areas.emplace_back(sites[e].area);
  }
  // points x elements, NaN (an element other than rough_contact) as null.
  const auto nullable = [](const Eigen::MatrixXd& x) {
    SummaryArray out;
    for (Eigen::Index k = 0; k < x.rows(); ++k) {
      SummaryArray row;
      for (Eigen::Index j = 0; j < x.cols(); ++j) {
        if (std::isfinite(x(k, j))) {
          row.emplace_back(x(k, j));
        } else {
          row.emplace_back(nullptr);
        }
      }
      out.emplace_back(std::move(row));
    }
    return out;
  };
  return {{"interface_elements", std::move(elements)},
          {"centroid_m", std::move(centroids)},
          {"area_m2", std::move(areas)},
          {"dissipation_J_per_m2", rows(m.dissipation)},
          {"mean_pressure_Pa", nullable(m.mean_pressure)},
          {"slip_fraction", nullable(m.slip_fraction)},
          {"open_fraction", nullable(m.open_fraction)}};
}

SummaryArray output_points_summary(const std::vector<OutputPoint>& points,
                                   const std::vector<OutputPointResponse>& responses) {
  SummaryArray a;
  for (std::size_t k = 0; k < responses.size(); ++k) {
    const Eigen::Vector3d& x = points[k].point;
    SummaryValue where =
        x.allFinite() ? SummaryValue(SummaryArray{x(0), x(1), x(2)}) : SummaryValue(nullptr);
    a.emplace_back(SummaryObject{{"name", responses[k].name},
                                 {"point_m", std::move(where)},
                                 {"displacement_amplitude_m", rows(responses[k].displacement)},
                                 {"acceleration_amplitude_m_s2", rows(responses[k].acceleration)}});
  }
  return a;
}

SummaryArray matrix_summary(const Eigen::MatrixXd& m) {
  return rows(m);
}

struct Work {
  std::size_t points = 0, newton = 0, residuals = 0, jacobians = 0, rejected = 0, turning = 0;
  double wall = 0.0;
  bool complete = true;
  StopCause cause = StopCause::end;
  std::size_t max_points = 0;  ///< of the continuation that stopped first
  std::string stop_reason;
};

SummaryObject solver_summary(const Work& w) {
  return {{"points", w.points},
          {"newton_iterations", w.newton},
          {"residual_evaluations", w.residuals},
          {"jacobian_evaluations", w.jacobians},
          {"rejected_steps", w.rejected},
          {"turning_points", w.turning},
          {"wall_time_s", w.wall},
          {"complete", w.complete},
          {"stop_reason", w.stop_reason}};
}

void add_continuation(Work& w, const ContinuationResult& c, std::size_t max_points) {
  w.points += c.points.size();
  w.newton += c.newton_iterations;
  w.rejected += c.rejected_steps;
  w.turning += c.turning_points;
  if (!c.complete && w.complete) {
    w.complete = false;
    w.cause = c.cause;
    w.max_points = max_points;
    w.stop_reason = c.stop_reason;
  } else if (w.complete) {
    w.stop_reason = c.stop_reason;
  }
}

// One analysis's work into the run's total; the first analysis that stopped early gives
// the total its stop reason, prefixed with `analysis`.
void add_analysis(Work& total, const Work& w, const std::string& analysis) {
  total.points += w.points;
  total.newton += w.newton;
  total.rejected += w.rejected;
  total.turning += w.turning;
  if (!w.complete && total.complete) {
    total.complete = false;
    total.cause = w.cause;
    total.max_points = w.max_points;
    total.stop_reason = analysis + ": " + w.stop_reason;
  }
}

// What helps a continuation that stopped early, by its cause (measured on the
// hardening-contact case of issue 23: min_step, max_iterations and max_points do not
// help a stall; a finer sampling does).
std::string remedy(const Work& w, std::size_t time_points) {
  switch (w.cause) {
    case StopCause::stalled:
      return fmt::format(
          "raise harmonic_balance.time_points (now {}; try {}): contact and slip are located "
          "at the time samples, and the corners of the curve where the continuation stalls "
          "shrink as time_points grows (a smaller min_step or more iterations do not help); or "
          "end the range before the point where it stalled",
          time_points, 4 * time_points);
    case StopCause::max_points:
      return fmt::format(
          "raise the continuation's max_points (now {}): the curve was still advancing (folds at "
          "contact and slip corners take many short steps)",
          w.max_points);
    case StopCause::turned_back:
      return "the curve turned back past the start of its range: end the range before the turn "
             "or start it from the other end";
    case StopCause::end:
      break;
  }
  return {};
}

}  // namespace

VibrationResult run_case(const VibrationCase& c, const CaseProgress& progress) {
  using clock = std::chrono::steady_clock;
  VibrationResult r;
  r.warnings = c.warnings;
  const HarmonicBalance hb(c.structure, c.elements, c.harmonic_balance);
  SummaryObject& j = r.summary;
  const Eigen::Index n = c.structure.dofs();

  // The case echoed.
  j.emplace_back("case", c.source);
  {
    SummaryObject s{{"dofs", static_cast<std::size_t>(n)}, {"damping", c.damping}};
    if (c.damping == "rayleigh") {
      s.emplace_back("rayleigh",
                     SummaryObject{{"alpha_per_s", c.rayleigh.alpha}, {"beta_s", c.rayleigh.beta}});
    }
    SummaryArray od;
    for (auto d : c.output_dofs) od.emplace_back(static_cast<std::size_t>(d));
    s.emplace_back("output_dofs", std::move(od));
    const LinearModes free_modes = linear_modes(c.structure.K, c.structure.M);
    const LinearModes stuck = linear_modes(hb.stuck_stiffness(), c.structure.M);
    SummaryArray fs, fss;
    for (Eigen::Index i = 0; i < free_modes.omega.size(); ++i) {
      fs.emplace_back(free_modes.omega(i) / (2.0 * std::numbers::pi));
      fss.emplace_back(stuck.omega(i) / (2.0 * std::numbers::pi));
    }
    s.emplace_back("linear_frequencies_hz_without_elements", std::move(fs));
    s.emplace_back("linear_frequencies_hz_elements_stuck", std::move(fss));
    j.emplace_back("structure", std::move(s));
  }
  {
    SummaryArray es;
    for (const auto& pe : c.elements) {
      SummaryObject e{{"name", pe.name}, {"type", pe.element->type()}};
      e.emplace_back("T", matrix_summary(pe.T));
      for (auto& kv : pe.element->describe()) {
        if (kv.first != "type") e.push_back(kv);
      }
      es.emplace_back(std::move(e));
    }
    j.emplace_back("elements", std::move(es));
  }
  {
    SummaryArray h;
    for (int x : c.harmonic_balance.harmonics) h.emplace_back(x);
    j.emplace_back("harmonic_balance",
                   SummaryObject{{"harmonics", std::move(h)},
                                 {"time_points", c.harmonic_balance.time_points},
                                 {"unknowns", static_cast<std::size_t>(hb.unknowns())}});
  }
  if (c.joint) j.emplace_back("joint", *c.joint);

  Work total;
  SummaryArray failed;  // curves that could not start, with the reason
  const auto t_all = clock::now();
  auto counters = [&hb] { return hb.counters(); };
  auto account = [&](Work& w, const WorkCounters& before, clock::time_point t0) {
    const WorkCounters after = counters();
    w.residuals = after.residual_evaluations - before.residual_evaluations;
    w.jacobians = after.jacobian_evaluations - before.jacobian_evaluations;
    w.wall = std::chrono::duration<double>(clock::now() - t0).count();
  };
  auto cannot_start = [](const std::string& analysis, const NumericalError& e) {
    return InvalidInput(fmt::format(
        "{}: {} (change the start of the range, the force, or the continuation settings)", analysis,
        e.what()));
  };

  if (c.nonlinear_mode) {
    Work w;
    const auto before = counters();
    const auto t0 = clock::now();
    try {
      r.nonlinear_mode = nonlinear_mode(
          hb, *c.nonlinear_mode, c.output_dofs,
          progress ? ProgressFunction([&](double x) { progress("nonlinear_mode", x); })
                   : ProgressFunction{});
    } catch (const NumericalError& e) {
      throw cannot_start("nonlinear_mode", e);
    }
    const NonlinearModeResult& m = *r.nonlinear_mode;
    add_continuation(w, m.continuation, c.nonlinear_mode->continuation.max_points);
    account(w, before, t0);
    r.warnings.insert(r.warnings.end(), m.warnings.begin(), m.warnings.end());
    r.nonlinear_mode_output_points =
        output_point_responses(hb, c.output_points, m.harmonics, m.omega);
    r.nonlinear_mode_interface = interface_map(hb, c.element_sites, m.harmonics, m.omega);
    SummaryValue interface;  // null without elements on interface elements
    if (r.nonlinear_mode_interface)
      interface = interface_map_summary(*r.nonlinear_mode_interface, c.element_sites);
    j.emplace_back(
        "nonlinear_mode",
        SummaryObject{{"mode", c.nonlinear_mode->mode},
                      {"linear_omega_rad_s", m.linear_omega},
                      {"linear_damping_ratio", m.linear_damping_ratio},
                      {"log10_amplitude", array(m.log10_amplitude)},
                      {"amplitude", array(m.amplitude)},
                      {"omega_rad_s", array(m.omega)},
                      {"frequency_hz", array(m.frequency_hz)},
                      {"damping_ratio", array(m.damping_ratio)},
                      {"xi_per_s", array(m.xi)},
                      {"output_amplitude", rows(m.output_amplitude)},
                      {"output_points",
                       output_points_summary(c.output_points, r.nonlinear_mode_output_points)},
                      {"interface", interface},
                      {"solver", solver_summary(w)}});
    add_analysis(total, w, "nonlinear_mode");
  }
  // [[backbone_rom]]: forced responses from the backbone just computed (mode_rom.hpp).
  if (!c.backbone_roms.empty() && r.nonlinear_mode) {
    SummaryArray curves;
    for (std::size_t k = 0; k < c.backbone_roms.size(); ++k) {
      const BackboneRomCase& b = c.backbone_roms[k];
      for (const double scale : b.force_scales) {
        ModeRomCurve rom = nonlinear_mode_rom(hb, *r.nonlinear_mode, scale * b.force, c.output_dofs,
                                              b.subdivisions);
        for (const std::string& m : rom.warnings) {
          r.warnings.push_back(fmt::format("backbone_rom[{}] at force scale {}: {}", k + 1,
                                           core::format_value(scale), m));
        }
        // The largest first-harmonic amplitude of each output and where it lies.
        SummaryArray peaks;
        for (Eigen::Index o = 0; o < rom.output_amplitude.cols(); ++o) {
          if (rom.omega.size() == 0) break;
          Eigen::Index i = 0;
          rom.output_amplitude.col(o).maxCoeff(&i);
          peaks.emplace_back(SummaryObject{
              {"output", static_cast<std::size_t>(o)},
              {"dof", static_cast<std::size_t>(c.output_dofs[static_cast<std::size_t>(o)])},
              {"omega_rad_s", rom.omega(i)},
              {"frequency_hz", rom.omega(i) / (2.0 * std::numbers::pi)},
              {"amplitude", rom.output_amplitude(i, o)}});
        }
        curves.emplace_back(
            SummaryObject{{"table", k + 1},
                          {"force_scale", scale},
                          {"omega_rad_s", array(rom.omega)},
                          {"frequency_hz", array(rom.omega / (2.0 * std::numbers::pi))},
                          {"modal_amplitude", array(rom.amplitude)},
                          {"output_amplitude", rows(rom.output_amplitude)},
                          {"low_side_points", rom.low_side_points},
                          {"peak_modal_amplitude", rom.peak_amplitude},
                          {"peaks", std::move(peaks)}});
        r.backbone_rom.push_back(std::move(rom));
        r.backbone_rom_table.push_back(k);
        r.backbone_rom_force_scale.push_back(scale);
      }
    }
    j.emplace_back("backbone_rom", std::move(curves));
  }

  if (!c.frequency_responses.empty()) {
    SummaryArray curves;
    std::size_t total_curves = 0, done_curves = 0;
    for (const auto& fr : c.frequency_responses) total_curves += fr.options.force_scales.size();
    for (std::size_t k = 0; k < c.frequency_responses.size(); ++k) {
      const FrequencyResponseOptions& all = c.frequency_responses[k].options;
      for (const double scale : all.force_scales) {
        // One curve per call, so that each has its own counters and wall time.
        FrequencyResponseOptions one = all;
        one.force_scales = {scale};
        const std::string curve = fmt::format("frequency_response[{}] at force scale {}", k + 1,
                                              core::format_value(scale));
        const auto before = counters();
        const auto t0 = clock::now();
        std::vector<FrequencyResponseCurve> cs;
        try {
          const double nk = static_cast<double>(total_curves);
          const double d0 = static_cast<double>(done_curves);
          cs = frequency_response(hb, one, c.output_dofs,
                                  progress ? ProgressFunction([&](double x) {
                                    progress("frequency_response", (d0 + x) / nk);
                                  })
                                           : ProgressFunction{});
        } catch (const NumericalError& e) {
          // The other curves still run; this one is named with its reason.
          ++done_curves;
          r.failures.push_back(cannot_start(curve, e).what());
          r.warnings.push_back(r.failures.back());
          failed.emplace_back(SummaryObject{
              {"table", k + 1}, {"force_scale", scale}, {"reason", r.failures.back()}});
          continue;
        }
        ++done_curves;
        FrequencyResponseCurve& cv = cs.front();
        Work w;
        add_continuation(w, cv.continuation, all.continuation.max_points);
        account(w, before, t0);
        r.warnings.insert(r.warnings.end(), cv.warnings.begin(), cv.warnings.end());
        SummaryArray ha;  // per point, per output, per harmonic
        for (Eigen::Index p = 0; p < cv.omega.size(); ++p) {
          SummaryArray per_output;
          for (const auto& hm : cv.harmonic_amplitude)
            per_output.emplace_back(array(hm.row(p).transpose()));
          ha.emplace_back(std::move(per_output));
        }
        SummaryObject o{{"table", k + 1},
                        {"force_scale", cv.force_scale},
                        {"omega_rad_s", array(cv.omega)},
                        {"frequency_hz", array(cv.omega / (2.0 * std::numbers::pi))},
                        {"output_amplitude", rows(cv.output_amplitude)},
                        {"max_displacement", rows(cv.max_displacement)},
                        {"harmonic_amplitude", std::move(ha)}};
        SummaryArray peaks, folds;
        for (const ResponsePeak& pk : cv.peaks) {
          peaks.emplace_back(
              SummaryObject{{"output_dof", static_cast<std::size_t>(c.output_dofs[pk.output])},
                            {"omega_rad_s", pk.omega},
                            {"frequency_hz", pk.omega / (2.0 * std::numbers::pi)},
                            {"amplitude_m", pk.amplitude}});
        }
        for (const ResponseFold& f : cv.folds) {
          SummaryObject fo{{"omega_rad_s", f.omega},
                           {"frequency_hz", f.omega / (2.0 * std::numbers::pi)},
                           {"output_amplitude", array(f.output_amplitude)}};
          if (!cv.stability.empty()) {
            // At a fold Delta_0 is singular: a Floquet exponent at 0 (a multiplier at +1).
            const std::complex<double> l =
                hill_stability(hb, f.harmonics, f.omega, hb.structure().C, all.hill)
                    .smallest_exponent;
            fo.emplace_back("smallest_floquet_exponent_per_s", SummaryArray{l.real(), l.imag()});
          }
          folds.emplace_back(std::move(fo));
        }
        o.emplace_back("peaks", std::move(peaks));
        o.emplace_back("folds", std::move(folds));
        if (!cv.stability.empty()) o.emplace_back("stability", stability_summary(cv.stability));
        o.emplace_back("solver", solver_summary(w));
        curves.emplace_back(std::move(o));
        add_analysis(total, w, curve);
        r.frequency_response.push_back(std::move(cv));
        r.frequency_response_table.push_back(k);
      }
    }
    j.emplace_back("frequency_response", std::move(curves));
  }
  if (!c.force_responses.empty()) {
    SummaryArray curves;
    const double nk = static_cast<double>(c.force_responses.size());
    for (std::size_t k = 0; k < c.force_responses.size(); ++k) {
      const ForceResponseOptions& o = c.force_responses[k].options;
      const std::string curve = fmt::format("force_response[{}]", k + 1);
      const auto before = counters();
      const auto t0 = clock::now();
      ForceResponseCurve cv;
      try {
        const double d0 = static_cast<double>(k);
        cv = force_response(hb, o, c.output_dofs,
                            progress ? ProgressFunction([&](double x) {
                              progress("force_response", (d0 + x) / nk);
                            })
                                     : ProgressFunction{});
      } catch (const NumericalError& e) {
        r.failures.push_back(cannot_start(curve, e).what());
        r.warnings.push_back(r.failures.back());
        failed.emplace_back(SummaryObject{{"table", k + 1},
                                          {"force_scale", o.scale_from},
                                          {"analysis", std::string("force_response")},
                                          {"reason", r.failures.back()}});
        continue;
      }
      Work w;
      add_continuation(w, cv.continuation, o.continuation.max_points);
      account(w, before, t0);
      r.warnings.insert(r.warnings.end(), cv.warnings.begin(), cv.warnings.end());
      SummaryArray ha;  // per point, per output, per harmonic
      for (Eigen::Index p = 0; p < cv.force_scale.size(); ++p) {
        SummaryArray per_output;
        for (const auto& hm : cv.harmonic_amplitude)
          per_output.emplace_back(array(hm.row(p).transpose()));
        ha.emplace_back(std::move(per_output));
      }
      SummaryArray folds;
      for (const ForceResponseFold& f : cv.folds) {
        folds.emplace_back(SummaryObject{{"force_scale", f.force_scale},
                                         {"output_amplitude", array(f.output_amplitude)}});
      }
      curves.emplace_back(SummaryObject{{"table", k + 1},
                                        {"omega_rad_s", cv.omega},
                                        {"frequency_hz", cv.omega / (2.0 * std::numbers::pi)},
                                        {"force_scale", array(cv.force_scale)},
                                        {"output_amplitude", rows(cv.output_amplitude)},
                                        {"max_displacement", rows(cv.max_displacement)},
                                        {"harmonic_amplitude", std::move(ha)},
                                        {"folds", std::move(folds)},
                                        {"solver", solver_summary(w)}});
      add_analysis(total, w, curve);
      r.force_response.push_back(std::move(cv));
      r.force_response_table.push_back(k);
    }
    j.emplace_back("force_response", std::move(curves));
  }
  // [[amplitude_control]], [[phase_resonance]], [[superharmonic_resonance]]: one
  // continuation per table.
  const auto controlled = [&](const char* name, std::size_t tables, const auto& run_one) {
    if (tables == 0) return;
    SummaryArray curves;
    for (std::size_t k = 0; k < tables; ++k) {
      const std::string curve = fmt::format("{}[{}]", name, k + 1);
      const auto before = counters();
      const auto t0 = clock::now();
      Work w;
      try {
        const double d0 = static_cast<double>(k), nk = static_cast<double>(tables);
        const ProgressFunction sub =
            progress ? ProgressFunction([&](double x) { progress(name, (d0 + x) / nk); })
                     : ProgressFunction{};
        SummaryObject o = run_one(k, sub, w);
        account(w, before, t0);
        o.emplace_back("solver", solver_summary(w));
        curves.emplace_back(std::move(o));
        add_analysis(total, w, curve);
      } catch (const InvalidInput& e) {
        // The library names the analysis ("phase_resonance.mode = ..."); the case names the
        // table: "phase_resonance[2].mode = ...".
        const std::string m = e.what();
        throw InvalidInput(m.starts_with(name) ? curve + m.substr(std::strlen(name))
                                               : fmt::format("{}: {}", curve, m));
      } catch (const NumericalError& e) {
        r.failures.push_back(cannot_start(curve, e).what());
        r.warnings.push_back(r.failures.back());
        failed.emplace_back(SummaryObject{{"table", k + 1},
                                          {"force_scale", 0.0},
                                          {"analysis", std::string(name)},
                                          {"reason", r.failures.back()}});
      }
    }
    j.emplace_back(name, std::move(curves));
  };
  controlled("amplitude_control", c.amplitude_controls.size(),
             [&](std::size_t k, const ProgressFunction& sub, Work& w) {
               const AmplitudeControlOptions& o = c.amplitude_controls[k];
               AmplitudeControlResult a = amplitude_controlled_response(hb, o, c.output_dofs, sub);
               add_continuation(w, a.continuation, o.continuation.max_points);
               r.warnings.insert(r.warnings.end(), a.warnings.begin(), a.warnings.end());
               SummaryObject out{{"table", k + 1},
                                 {"dof", static_cast<std::size_t>(o.dof)},
                                 {"amplitude_m", o.amplitude},
                                 {"omega_rad_s", array(a.omega)},
                                 {"frequency_hz", array(a.omega / (2.0 * std::numbers::pi))},
                                 {"force_scale", array(a.force_scale)},
                                 {"output_amplitude", rows(a.output_amplitude)}};
               r.amplitude_control.push_back(std::move(a));
               r.amplitude_control_table.push_back(k);
               return out;
             });
  controlled("phase_resonance", c.phase_resonances.size(),
             [&](std::size_t k, const ProgressFunction& sub, Work& w) {
               const PhaseResonanceOptions& o = c.phase_resonances[k];
               PhaseResonanceResult p = phase_resonance(hb, o, c.output_dofs, sub);
               add_continuation(w, p.continuation, o.continuation.max_points);
               r.warnings.insert(r.warnings.end(), p.warnings.begin(), p.warnings.end());
               SummaryObject out{{"table", k + 1},
                                 {"dof", static_cast<std::size_t>(o.dof)},
                                 {"amplitude_m", array(p.amplitude)},
                                 {"omega_rad_s", array(p.omega)},
                                 {"frequency_hz", array(p.omega / (2.0 * std::numbers::pi))},
                                 {"force_scale", array(p.force_scale)},
                                 {"output_amplitude", rows(p.output_amplitude)}};
               r.phase_resonance.push_back(std::move(p));
               r.phase_resonance_table.push_back(k);
               return out;
             });
  controlled("superharmonic_resonance", c.superharmonic_resonances.size(),
             [&](std::size_t k, const ProgressFunction& sub, Work& w) {
               const SuperharmonicResonanceOptions& o = c.superharmonic_resonances[k];
               SuperharmonicResonanceResult p = superharmonic_resonance(hb, o, c.output_dofs, sub);
               add_continuation(w, p.continuation, o.continuation.max_points);
               r.warnings.insert(r.warnings.end(), p.warnings.begin(), p.warnings.end());
               SummaryObject out{{"table", k + 1},
                                 {"harmonic", o.harmonic},
                                 {"force_scale", array(p.force_scale)},
                                 {"omega_rad_s", array(p.omega)},
                                 {"frequency_hz", array(p.omega / (2.0 * std::numbers::pi))},
                                 {"output_amplitude", rows(p.output_amplitude)},
                                 {"output_harmonic_amplitude", rows(p.output_harmonic_amplitude)}};
               r.superharmonic_resonance.push_back(std::move(p));
               r.superharmonic_resonance_table.push_back(k);
               return out;
             });
  // Nothing computed at all: the case is bad input as a whole (exit 2).
  if (!r.failures.empty() && r.frequency_response.empty() && r.force_response.empty() &&
      r.amplitude_control.empty() && r.phase_resonance.empty() &&
      r.superharmonic_resonance.empty() && !r.nonlinear_mode && !c.quasi_static_mode) {
    throw InvalidInput(r.failures.front());
  }

  if (c.quasi_static_mode) {
    Work w;
    const auto before = counters();
    const auto t0 = clock::now();
    if (progress) progress("quasi_static_mode", 0.0);
    try {
      r.quasi_static_mode = quasi_static_mode(hb, *c.quasi_static_mode);
    } catch (const NumericalError& e) {
      throw InvalidInput(fmt::format("quasi_static_mode: {}", e.what()));
    }
    if (progress) progress("quasi_static_mode", 1.0);
    const QuasiStaticModeResult& q = *r.quasi_static_mode;
    w.points = static_cast<std::size_t>(q.amplitude.size());
    w.newton = q.newton_iterations;
    w.stop_reason = "reached the end of the amplitude range";
    account(w, before, t0);
    r.warnings.insert(r.warnings.end(), q.warnings.begin(), q.warnings.end());
    j.emplace_back("quasi_static_mode", SummaryObject{{"mode", c.quasi_static_mode->mode},
                                                      {"linear_omega_rad_s", q.linear_omega},
                                                      {"amplitude", array(q.amplitude)},
                                                      {"omega_rad_s", array(q.omega)},
                                                      {"frequency_hz", array(q.frequency_hz)},
                                                      {"damping_ratio", array(q.damping_ratio)},
                                                      {"modal_force", array(q.modal_force)},
                                                      {"dissipation_J", array(q.dissipation)},
                                                      {"solver", solver_summary(w)}});
    add_analysis(total, w, "quasi_static_mode");
  }
  {
    const WorkCounters wc = counters();
    total.residuals = wc.residual_evaluations;
    total.jacobians = wc.jacobian_evaluations;
    total.wall = std::chrono::duration<double>(clock::now() - t_all).count();
    if (!r.failures.empty()) {
      // Curves that could not start: the run is incomplete, the first of them its reason
      // unless a curve stopped early before it.
      if (total.complete) {
        total.complete = false;
        total.stop_reason =
            fmt::format("{} of {} forced response curve(s) could not start: {}", r.failures.size(),
                        r.failures.size() + r.frequency_response.size() + r.force_response.size() +
                            r.amplitude_control.size() + r.phase_resonance.size() +
                            r.superharmonic_resonance.size(),
                        r.failures.front());
      }
    }
    if (total.complete) total.stop_reason = "every analysis reached the end of its range";
    r.complete = total.complete;
    r.stop_reason = total.stop_reason;
    r.remedy = remedy(total, c.harmonic_balance.time_points);
    if (!r.failures.empty()) {
      r.remedy +=
          std::string(r.remedy.empty() ? "" : "; ") +
          "for the curves that could not start: start the range (omega.from, force_scale.from, "
          "log10_amplitude.from) where the "
          "response is small or the joint stuck, lower the force, or raise "
          "max_iterations";
    }
    j.emplace_back("solver", solver_summary(total));
  }
  j.emplace_back("failed", std::move(failed));
  SummaryArray w;
  for (const auto& s : r.warnings) w.emplace_back(s);
  j.emplace_back("warnings", std::move(w));
  return r;
}

}  // namespace asperity::vibration
