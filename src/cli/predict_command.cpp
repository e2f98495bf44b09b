// asperity predict CASE.toml [--out DIR]: friction, stiffness and energy per cycle of a
// joint from its case file (thesis ch. 5-6), with no fitted friction coefficient.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string_view>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/hysteresis/table_backbone.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/joint/predict.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace {

// Seconds between the plain progress lines when stderr is not a terminal (README, "The
// command line").
constexpr double kDefaultProgressInterval = 10.0;
constexpr const char* kProgressIntervalVariable = "ASPERITY_PROGRESS_INTERVAL";

// The environment variable ASPERITY_PROGRESS_INTERVAL when set, else the default. A value
// that is not a finite number of seconds >= 0 is refused (InvalidInput, exit 2), never
// ignored: 0 prints a line after every preload.
double progress_interval() {
  const char* env = std::getenv(kProgressIntervalVariable);
  if (env == nullptr) return kDefaultProgressInterval;
  const std::string_view s(env);
  double seconds = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), seconds);
  if (!s.empty() && ec == std::errc() && end == s.data() + s.size() && std::isfinite(seconds) &&
      seconds >= 0.0) {
    return seconds;
  }
  throw InvalidInput(fmt::format(
      "{}=\"{}\" is not allowed: give the seconds between predict's progress lines when stderr "
      "is not a terminal, a number >= 0 such as 10 (the default) or 0 (a line after every "
      "preload)",
      kProgressIntervalVariable, core::printable(s)));
}

struct PredictOptions {
  std::string case_file;
  std::optional<std::string> out;
  bool json = false;
  bool no_plots = false;
};

Json amplitude_json(const joint::AmplitudePrediction& a) {
  Json j{{"delta_max", a.delta_max},
         {"Q_peak", a.Q_peak},
         {"energy", a.energy},
         {"Q_peak_over_Q_max", a.Q_ratio},
         {"regime", a.regime}};
  if (a.imposed) j["imposed"] = *a.imposed;
  // Local energy-force exponent d ln W / d ln Q_peak; null in gross slip.
  j["exponent"] = a.exponent ? Json(*a.exponent) : Json(nullptr);
  j["gross_slip_area_fraction"] = a.gross_slip_area_fraction;
  if (a.patch_gross_slip.size() > 1) j["patch_gross_slip"] = a.patch_gross_slip;
  return j;
}

// The patches of an [interface] (joint/interface.hpp): cell, area, force, own quantities.
Json patches_json(const joint::LoadPrediction& l) {
  Json out = Json::array();
  for (const auto& p : l.patches) {
    out.push_back(Json{{"x0", p.patch.x0},
                       {"y0", p.patch.y0},
                       {"x1", p.patch.x1},
                       {"y1", p.patch.y1},
                       {"area", p.patch.area},
                       {"force", p.patch.force},
                       {"pressure", p.patch.pressure()},
                       {"d_star", p.d_star},
                       {"Q_max", p.Q_max},
                       {"stiffness", p.stiffness},
                       {"gross_slip_amplitude", p.gross_slip_amplitude}});
  }
  return out;
}

Json load_json(const joint::LoadPrediction& l) {
  Json j{{"preload", l.preload}};
  if (l.torque > 0.0) j["torque_per_bolt"] = l.torque;
  j["mean_pressure"] = l.mean_pressure;
  j["separation"] = l.separation;
  j["d_star"] = l.d_star;
  j["P_star"] = l.P_star;
  j["mu"] = l.mu;
  j["Q_max"] = l.Q_max;
  j["stiffness"] = l.stiffness;
  j["contact_area_ratio"] = l.contact_area_ratio;
  j["gross_slip_amplitude"] = l.gross_slip_amplitude;
  Json amps = Json::array();
  for (const auto& a : l.amplitudes) amps.push_back(amplitude_json(a));
  j["amplitudes"] = amps;
  if (l.patches.size() > 1) {
    j["patches"] = patches_json(l);
    j["distinct_patch_sums"] = l.distinct_patch_sums;
  }
  return j;
}

Json interface_json(const joint::InterfaceSpec& s) {
  const char* kinds[] = {"uniform", "map", "bolted"};
  Json j{{"pressure", kinds[static_cast<int>(s.pressure)]},
         {"patches", {s.patches[0], s.patches[1]}},
         {"min_asperities_per_patch", joint::kMinAsperitiesPerPatch}};
  if (s.outline) j["size"] = {(*s.outline)[0], (*s.outline)[1]};
  if (s.pressure == joint::PressureKind::map) {
    j["map"] = Json{{"file", s.map.file},
                    {"points", s.map.p.size()},
                    {"interpolation", s.map.is_grid() ? "bilinear (grid)" : "nearest point"},
                    {"scale_to_preload", s.map.scale_to_preload}};
  }
  if (s.pressure == joint::PressureKind::bolted) {
    Json pos = Json::array();
    for (const auto& b : s.bolts.positions) pos.push_back({b[0], b[1]});
    j["bolts"] = Json{{"positions", pos},
                      {"head_diameter", s.bolts.head_diameter},
                      {"hole_diameter", s.bolts.hole_diameter},
                      {"thickness", {s.bolts.thickness[0], s.bolts.thickness[1]}},
                      {"cone_half_angle_deg", s.bolts.cone_half_angle_deg},
                      {"footprint_radius", s.bolts.footprint_radius()},
                      {"model",
                       "pressure cone (Rotscher frustum, Shigley): the bolt's force uniform over "
                       "the annulus between the hole and r_c = d_w/2 + min(t1, t2) tan(alpha)"}};
  }
  return j;
}

bool from_profiles(const joint::JointCase& c) {
  return !c.halves[0].roughness.profiles.empty() || !c.halves[1].roughness.profiles.empty();
}

// Where each half's roughness came from (parameters, or scans and their directions) and
// the resulting parameters.
Json processing_json(const joint::ProfileSettings& s);
Json halves_json(const joint::JointCase& c) {
  Json halves = Json::array();
  for (const auto& h : c.halves) {
    const auto& r = h.roughness;
    Json j{{"source", r.profiles.empty() ? "parameters" : "profiles"}};
    if (!r.profiles.empty()) {
      Json scans = Json::array();
      for (std::size_t i = 0; i < r.profiles.size(); ++i) {
        scans.push_back(Json{{"file", r.profiles[i]},
                             {"direction", i < r.directions.size() ? r.directions[i] : ""}});
      }
      j["profiles"] = scans;
      j["processing"] = processing_json(h.profile_settings);
    }
    j["sigma"] = r.moments.sigma();
    j["eta"] = r.moments.eta();
    j["R"] = r.moments.R();
    j["m0"] = r.moments.m0;
    j["m2"] = r.moments.m2;
    j["m4"] = r.moments.m4;
    halves.push_back(j);
  }
  return halves;
}

// How scans were turned into moments (the settings of [profiles], docs/roughness.md).
Json processing_json(const joint::ProfileSettings& s) {
  const auto cutoff = [](double v) { return v > 0.0 ? Json(v) : Json("none"); };
  Json j{{"level", std::string(surface::to_string(s.level))},
         {"filter", s.filter.lc > 0.0 || s.filter.ls > 0.0 ? "ISO 16610-21 Gaussian" : "none"},
         {"lc", cutoff(s.filter.lc)},
         {"ls", cutoff(s.filter.ls)},
         {"end", std::string(surface::to_string(s.filter.end))},
         {"truncation", s.filter.truncation},
         {"rule", std::string(surface::to_string(s.rule))},
         {"rule_applies_to",
          "two scans of a half (max- and min-slope directions): m2, m4 of the equivalent "
          "isotropic surface by this mean, m0 by the arithmetic mean (Eq. 5.1)"}};
  if (s.dx) j["dx"] = *s.dx;
  return j;
}

}  // namespace

Json prediction_json(const joint::JointCase& c, const joint::JointPrediction& p) {
  Json j;
  j["name"] = c.name;
  j["case"] = c.source;
  j["model"] = std::string(contact::to_string(c.model));
  j["area"] = c.area;
  j["units"] = "SI: N, m, J, N/m, Pa";
  j["roughness"] = Json{{"sigma", p.sigma},    {"eta", p.eta},       {"R", p.R},
                        {"beta", p.beta},      {"psi", p.psi},       {"m0", p.combined.m0},
                        {"m2", p.combined.m2}, {"m4", p.combined.m4}};
  j["roughness"]["halves"] = halves_json(c);
  j["roughness"]["combined_by"] = "Eq. 5.1: the halves' spectral moments m0, m2, m4 added";
  if (from_profiles(c)) j["roughness"]["processing"] = processing_json(c.profile_settings);
  j["force_scale_KHA0"] = p.force_scale;
  if (!c.interface.is_default()) j["interface"] = interface_json(c.interface);
  if (const auto& ov = c.interface.odfalk_vingsbo) {
    j["tangential"] = Json{{"law", "odfalk_vingsbo"},
                           {"equation", "thesis Eq. 3.10, in series with Masing on the backbone"},
                           {"fretting_yield_point", ov->fretting_yield_point},
                           {"hardening_coefficient", ov->hardening_coefficient},
                           {"parameters_from", "the user (measured; not physics-based)"}};
  } else {
    j["tangential"] = Json{{"law", "mindlin"}};
  }
  if (!c.imposed.empty()) {
    j["apparatus"] = Json{{"pzt_stiffness", c.apparatus.pzt_stiffness},
                          {"load_cell_stiffness", c.apparatus.load_cell_stiffness},
                          {"imposed", c.imposed}};
  }
  if (p.loads.size() == 1) {  // the single-preload keys at the top level
    const Json first = load_json(p.loads.front());
    for (auto it = first.begin(); it != first.end(); ++it) j[it.key()] = *it;
  }
  Json loads = Json::array();
  for (const auto& l : p.loads) loads.push_back(load_json(l));
  j["loads"] = loads;
  j["warnings"] = p.warnings;
  return j;
}

std::string prediction_summary(const joint::JointCase& c, const joint::JointPrediction& p) {
  std::string s;
  s += fmt::format("joint: {} ({})\n", c.name.empty() ? "(unnamed)" : c.name, c.source);
  s += fmt::format(
      "model {}, A0 = {:.4g} mm^2; combined roughness sigma = {:.4g} um, eta = {:.4g} um^-2, "
      "R = {:.4g} um, beta = {:.4f}, psi = {:.4g}\n",
      contact::to_string(c.model), c.area * 1e6, p.sigma * 1e6, p.eta * 1e-12, p.R * 1e6, p.beta,
      p.psi);
  if (const auto& ov = c.interface.odfalk_vingsbo) {
    s += fmt::format(
        "tangential law: Odfalk-Vingsbo (Eq. 3.10, phenomenological), fretting yield point Q_ty "
        "= {:.4g} N, hardening coefficient k_p = {:.4g} N/um, as given (measured, not predicted); "
        "backbones.csv holds the elastic (Mindlin) part only\n",
        ov->fretting_yield_point, ov->hardening_coefficient * 1e-6);
  }
  if (from_profiles(c)) {
    const auto cut = [](double v, double scale, const char* unit) {
      return v > 0.0 ? fmt::format("{:.4g} {}", v * scale, unit) : std::string("none");
    };
    const auto settings = [&](const joint::ProfileSettings& ps) {
      return fmt::format(
          "level {}, Gaussian filter lc = {}, ls = {} (end effects {}), rule {} (Eq. 5.1)",
          surface::to_string(ps.level), cut(ps.filter.lc, 1e3, "mm"), cut(ps.filter.ls, 1e6, "um"),
          surface::to_string(ps.filter.end), surface::to_string(ps.rule));
    };
    // One line for the scans when both halves were processed alike, else one per half.
    const bool alike =
        settings(c.halves[0].profile_settings) == settings(c.halves[1].profile_settings) ||
        c.halves[0].roughness.profiles.empty() || c.halves[1].roughness.profiles.empty();
    for (std::size_t i = 0; i < 2; ++i) {
      const auto& r = c.halves[i].roughness;
      std::string files;
      for (const auto& f : r.profiles) files += (files.empty() ? "" : ", ") + f;
      s += fmt::format("half {}: sigma = {:.4g} um, eta = {:.4g} um^-2, R = {:.4g} um ({})\n",
                       i + 1, r.moments.sigma() * 1e6, r.moments.eta() * 1e-12, r.moments.R() * 1e6,
                       files.empty() ? "given as parameters" : files);
      if (!alike) s += fmt::format("  its scans: {}\n", settings(c.halves[i].profile_settings));
    }
    if (alike) {
      const auto& h = c.halves[0].roughness.profiles.empty() ? c.halves[1] : c.halves[0];
      s += fmt::format("scans: {}\n", settings(h.profile_settings));
    }
  }
  const bool torques = c.bolts.has_value();
  s += fmt::format("\n{:>11} {}{:>10} {:>10} {:>8} {:>10} {:>10} {:>9}\n", "preload[N]",
                   torques ? fmt::format("{:>14} ", "torque/bolt[Nm]") : "", "p[MPa]", "d[um]",
                   "mu", "Q_max[N]", "k[N/um]", "Ar/A0");
  for (const auto& l : p.loads) {
    s += fmt::format("{:>11.4g} {}{:>10.3g} {:>10.4g} {:>8.4f} {:>10.4g} {:>10.4g} {:>9.3g}\n",
                     l.preload, torques ? fmt::format("{:>15.4g} ", l.torque) : "",
                     l.mean_pressure * 1e-6, l.separation * 1e6, l.mu, l.Q_max, l.stiffness * 1e-6,
                     l.contact_area_ratio);
  }
  if (c.amplitudes.empty() && c.imposed.empty()) {
    s += "\nno [excitation] in the case: no fretting loops or energies (give amplitudes = "
         "[...] or imposed = [...])\n";
  }
  for (const auto& l : p.loads) {
    if (l.amplitudes.empty()) continue;
    const bool imposed = std::any_of(l.amplitudes.begin(), l.amplitudes.end(),
                                     [](const auto& a) { return a.imposed.has_value(); });
    s += fmt::format("\nP = {:.4g} N (gross slip from delta_max = {:.3g} um{}):\n", l.preload,
                     l.gross_slip_amplitude * 1e6,
                     l.patches.size() > 1
                         ? fmt::format("; {} loaded patches, the first slips fully at {:.3g} um",
                                       l.patches.size(),
                                       std::min_element(
                                           l.patches.begin(), l.patches.end(),
                                           [](const auto& a, const auto& b) {
                                             return a.gross_slip_amplitude < b.gross_slip_amplitude;
                                           })->gross_slip_amplitude *
                                           1e6)
                         : "");
    // With patches: the share of the loaded area in gross slip and the local exponent.
    const bool patched = l.patches.size() > 1;
    s += fmt::format("{:>14}{}{:>14} {:>10} {:>14} {:>9}  {}{}\n", "",
                     imposed ? fmt::format("{:>13} ", "imposed[um]") : "", "delta_max[um]",
                     "Q_peak[N]", "energy[uJ]", "Q/Q_max",
                     patched ? fmt::format("{:>9} {:>6}  ", "slip[%]", "n") : "", "regime");
    for (const auto& a : l.amplitudes) {
      s += fmt::format("{:>14}{}{:>14.4g} {:>10.4g} {:>14.5g} {:>9.5f}  {}{}\n", "",
                       imposed ? (a.imposed ? fmt::format("{:>13.4g} ", *a.imposed * 1e6)
                                            : fmt::format("{:>13} ", "-"))
                               : "",
                       a.delta_max * 1e6, a.Q_peak, a.energy * 1e6, a.Q_ratio,
                       patched ? fmt::format("{:>9.1f} {:>6}  ", 100.0 * a.gross_slip_area_fraction,
                                             a.exponent ? fmt::format("{:.4g}", *a.exponent) : "-")
                               : "",
                       a.regime);
    }
  }
  return s;
}

void add_power_guides(PlotSpec& spec, double q0, double e0, double qmin, double qmax) {
  // Dark, distinct dash patterns: the guides must read on white and in grey print.
  const std::pair<int, const char*> guides[] = {{2, "lines dt 2 lc rgb '#555555'"},
                                                {3, "lines dt 4 lc rgb '#000000'"}};
  for (const auto& [n, style] : guides) {
    Series g{fmt::format("slope {} (energy ~ Q^{})", n, n), {}, {}, style};
    for (int i = 0; i <= 20; ++i) {
      const double q = qmin * std::pow(qmax / qmin, i / 20.0);
      g.x.push_back(q);
      g.y.push_back(e0 * std::pow(q / q0, n));
    }
    spec.series.push_back(g);
  }
}

void set_energy_force_ranges(PlotSpec& spec, double qmin, double qmax, double emin, double emax) {
  if (!(qmin > 0.0 && qmax >= qmin && emin > 0.0 && emax >= emin)) return;
  spec.extra += fmt::format("set xrange [{:.10g}:{:.10g}]\nset yrange [{:.10g}:{:.10g}]\n",
                            qmin / 1.25, qmax * 1.25, emin / 2.0, emax * 2.0);
  std::string tics;
  for (double decade = std::pow(10.0, std::floor(std::log10(qmin / 1.25))); decade <= qmax * 1.25;
       decade *= 10.0) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double t = m * decade;
      if (t >= qmin / 1.25 && t <= qmax * 1.25)
        tics += fmt::format("{}{:.10g}", tics.empty() ? "" : ", ", t);
    }
  }
  if (!tics.empty()) spec.extra += fmt::format("set format x '%g'\nset xtics ({})\n", tics);
}

namespace {

// More load cases than this: colour by preload (a colour scale) instead of a legend entry
// per preload.
constexpr std::size_t kMaxLegendLoads = 8;

// Distinct colours that stay apart in print (Okabe and Ito's palette, black last).
constexpr std::array<const char*, 8> kColours{"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                              "#e69f00", "#56b4e9", "#7f7f7f", "#000000"};

std::string palette_commands(const joint::JointPrediction& p) {
  if (p.loads.size() <= kMaxLegendLoads) return "";
  double lo = 1e300, hi = 0.0;
  for (const auto& l : p.loads) {
    lo = std::min(lo, l.preload);
    hi = std::max(hi, l.preload);
  }
  return fmt::format(
      "set palette defined (0 '#1f4e9a', 1 '#2ca02c', 2 '#e6a100', 3 '#c0392b')\n"
      "set cbrange [{:.10g}:{:.10g}]\nset cblabel 'preload [N]'\nset colorbox\n",
      lo, hi > lo ? hi : lo * 1.001);
}

// patches.csv: every load case's patches (long format).
void write_patch_table(const std::string& path, const joint::JointPrediction& p) {
  std::vector<std::vector<double>> t(11);
  for (const auto& l : p.loads) {
    for (const auto& q : l.patches) {
      const double row[] = {l.preload,
                            q.patch.x0 * 1e3,
                            q.patch.y0 * 1e3,
                            q.patch.x1 * 1e3,
                            q.patch.y1 * 1e3,
                            q.patch.area * 1e6,
                            q.patch.force,
                            q.patch.pressure() * 1e-6,
                            q.Q_max,
                            q.stiffness * 1e-6,
                            q.gross_slip_amplitude * 1e6};
      for (std::size_t k = 0; k < t.size(); ++k) t[k].push_back(row[k]);
    }
  }
  core::write_csv_table(
      path,
      {"preload[N]", "x0[mm]", "y0[mm]", "x1[mm]", "y1[mm]", "area[mm^2]", "force[N]",
       "pressure[MPa]", "Q_max[N]", "stiffness[N/um]", "gross_slip_amplitude[um]"},
      t);
}

// The patches of the first load case as coloured rectangles (gnuplot objects) with the
// bolts' holes and cone footprints: by pressure, and by the amplitude from which each
// patch is in gross slip (a patch coloured below an amplitude slips fully at it).
void plot_patch_maps(const joint::JointCase& c, const joint::JointPrediction& p,
                     const std::string& pressure_png, const std::string& slip_png) {
  const auto& l = p.loads.front();
  const auto map = [&](const std::string& png, const std::string& title, const std::string& label,
                       const auto& value) {
    double lo = 1e300, hi = -1e300;
    for (const auto& q : l.patches) {
      lo = std::min(lo, value(q));
      hi = std::max(hi, value(q));
    }
    std::string extra = fmt::format(
        "set palette defined (0 '#1f4e9a', 1 '#2ca02c', 2 '#e6a100', 3 '#c0392b')\n"
        "set cbrange [{:.10g}:{:.10g}]\nset cblabel {}\nset colorbox\nset size ratio -1\n"
        "set key below\n",
        lo, hi > lo ? hi : lo * 1.001 + 1e-30, gnuplot_string(label));
    int id = 1;
    for (const auto& q : l.patches) {
      extra += fmt::format(
          "set object {} rect from {:.10g},{:.10g} to {:.10g},{:.10g} fc palette cb {:.10g} fs "
          "solid border lc rgb '#ffffff' behind\n",
          id++, q.patch.x0 * 1e3, q.patch.y0 * 1e3, q.patch.x1 * 1e3, q.patch.y1 * 1e3, value(q));
    }
    PlotSpec spec{title, "x [mm] (fretting direction)", "y [mm]", false, false, {}, extra};
    const auto circle = [](double x0, double y0, double r) {
      Series s{"", {}, {}, "lines lc rgb '#000000'"};
      for (int i = 0; i <= 72; ++i) {
        s.x.push_back((x0 + r * std::cos(i * M_PI / 36.0)) * 1e3);
        s.y.push_back((y0 + r * std::sin(i * M_PI / 36.0)) * 1e3);
      }
      return s;
    };
    if (c.interface.pressure == joint::PressureKind::bolted) {
      const auto& b = c.interface.bolts;
      for (std::size_t k = 0; k < b.positions.size(); ++k) {
        auto hole = circle(b.positions[k][0], b.positions[k][1], 0.5 * b.hole_diameter);
        if (k == 0) hole.title = "bolt holes";
        spec.series.push_back(hole);
        auto cone = circle(b.positions[k][0], b.positions[k][1], b.footprint_radius());
        cone.style = "lines dt 2 lc rgb '#000000'";
        if (k == 0) cone.title = "pressure cones (r_c)";
        spec.series.push_back(cone);
      }
    }
    // A palette-coloured point so that gnuplot draws the colour box.
    Series dot{"",
               {l.patches.front().patch.x0 * 1e3},
               {l.patches.front().patch.y0 * 1e3},
               fmt::format("points pt 5 ps 0 lc palette cb {:.10g}", lo)};
    spec.series.push_back(dot);
    plot_png(png, spec);
  };
  map(pressure_png,
      fmt::format("Interface pressure at P = {:.0f} N ({} patches): {}", l.preload,
                  l.patches.size(), c.name),
      "pressure [MPa]", [](const joint::PatchPrediction& q) { return q.patch.pressure() * 1e-6; });
  map(slip_png,
      fmt::format("Slip map at P = {:.0f} N: delta_max from which each patch slips fully",
                  l.preload),
      "gross-slip amplitude [um]",
      [](const joint::PatchPrediction& q) { return q.gross_slip_amplitude * 1e6; });
}

}  // namespace

std::vector<std::string> write_prediction_files(const joint::JointCase& c,
                                                const joint::JointPrediction& p,
                                                joint::StagedDirectory& dir, bool plots, bool data,
                                                const std::string& prefix) {
  std::vector<std::string> written;
  const auto file = [&](const std::string& name) {
    written.push_back(prefix + name);
    return dir.file(prefix + name);
  };
  if (data) write_file_atomically(file("summary.json"), json_output(prediction_json(c, p)));
  // loops.csv: steady loops for every preload and amplitude (long format).
  std::vector<std::vector<double>> lc(4);
  // energy.csv: numbers with 12 digits, and an empty imposed[um] field where the joint
  // amplitude was given directly (no PZT amplitude to report).
  // Energy in uJ, as in the table and the plots (one unit per output).
  std::string energy_csv =
      "preload[N],delta_max[um],Q_peak[N],energy[uJ],Q_peak_over_Q_max,gross_slip,imposed[um]\n";
  for (const auto& l : p.loads) {
    for (const auto& a : l.amplitudes) {
      const auto [x, Q] = joint::steady_loop(l, a.delta_max, 100);
      for (std::size_t i = 0; i < x.size(); ++i) {
        lc[0].push_back(l.preload);
        lc[1].push_back(a.delta_max * 1e6);
        lc[2].push_back(x[i] * 1e6);
        lc[3].push_back(Q[i]);
      }
      energy_csv += fmt::format("{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{},{}\n", l.preload,
                                a.delta_max * 1e6, a.Q_peak, a.energy * 1e6, a.Q_ratio,
                                a.regime == "gross slip" ? 1 : 0,
                                a.imposed ? fmt::format("{:.12g}", *a.imposed * 1e6) : "");
    }
  }
  const bool amplitudes = !lc[0].empty();
  if (data && amplitudes) {
    core::write_csv_table(file("loops.csv"), {"preload[N]", "delta_max[um]", "delta[um]", "Q[N]"},
                          lc);
    write_file_atomically(file("energy.csv"), energy_csv);
  }
  // backbones.csv: each preload's virgin curve, for a masing_table vibration element.
  if (data) {
    std::vector<std::vector<double>> bc(3);
    for (const auto& l : p.loads) {
      const auto [x, Q] = hysteresis::tabulate(*l.backbone);
      for (std::size_t i = 0; i < x.size(); ++i) {
        bc[0].push_back(l.preload);
        bc[1].push_back(x[i] * 1e6);
        bc[2].push_back(Q[i]);
      }
    }
    core::write_csv_table(file("backbones.csv"), {"preload[N]", "delta[um]", "Q[N]"}, bc);
  }
  const bool patched = !p.loads.empty() && p.loads.front().patches.size() > 1;
  if (data && patched) write_patch_table(file("patches.csv"), p);
  if (plots && patched) plot_patch_maps(c, p, file("pressure_map.png"), file("slip_map.png"));
  if (!plots) return written;
  const bool sweep = p.loads.size() > 1;
  const std::size_t nl = p.loads.size();
  const bool legend = nl <= kMaxLegendLoads;
  const std::string title_name = c.name.empty() ? std::string("(unnamed joint)") : c.name;
  // Colour of load case i (legend mode); palette mode colours by preload instead.
  const auto colour = [&](const joint::LoadPrediction& l, std::size_t i) {
    return legend ? fmt::format("lc rgb '{}'", kColours[i % kColours.size()])
                  : fmt::format("lc palette cb {:.10g}", l.preload);
  };
  const auto partial = [](const joint::AmplitudePrediction& a) { return a.regime != "gross slip"; };
  if (amplitudes) {
    // Sweeps: per preload the largest amplitude visibly in partial slip (Q_peak <= 0.9
    // Q_max; above, the loop looks saturated although not every asperity slips) and the
    // smallest gross-slip amplitude, solid and dashed, one colour per preload; one
    // preload: every amplitude.
    PlotSpec loops{
        fmt::format("Fretting loops (solid: partial slip, dashed: gross slip): {}", title_name),
        "delta [µm]",
        "Q [N]",
        false,
        false,
        {},
        palette_commands(p) +
            "set offsets graph 0.04, graph 0.04, graph 0.08, graph 0.08\n"
            "set key below center horizontal maxcols 2\n"};
    for (std::size_t i = 0; i < nl; ++i) {
      const auto& l = p.loads[i];
      std::vector<std::size_t> shown;
      if (sweep) {
        std::optional<std::size_t> last_partial, first_gross;
        for (std::size_t k = 0; k < l.amplitudes.size(); ++k) {
          if (partial(l.amplitudes[k])) {
            if (!last_partial || l.amplitudes[k].Q_ratio <= 0.9) last_partial = k;
          } else if (!first_gross) {
            first_gross = k;
          }
        }
        if (last_partial) shown.push_back(*last_partial);
        if (first_gross) shown.push_back(*first_gross);
      } else {
        for (std::size_t k = 0; k < l.amplitudes.size(); ++k) shown.push_back(k);
      }
      for (std::size_t j = 0; j < shown.size(); ++j) {
        const auto& a = l.amplitudes[shown[j]];
        auto [x, Q] = joint::steady_loop(l, a.delta_max, 400);
        for (double& v : x) v *= 1e6;
        const bool ps = partial(a);
        std::string title =
            sweep ? fmt::format("P = {:.0f} N, {:.3g} µm{}", l.preload, a.delta_max * 1e6,
                                ps ? fmt::format(" (Q/Q_max = {:.2f})", a.Q_ratio)
                                   : std::string(" (gross slip)"))
                  : fmt::format("{:.3g} µm ({}, Q/Q_max = {:.2f})", a.delta_max * 1e6, a.regime,
                                a.Q_ratio);
        if (!legend) title = i == 0 ? (ps ? "partial slip" : "gross slip") : "";
        // One preload: a colour per amplitude; a sweep: a colour per preload.
        const std::string col =
            sweep ? colour(l, i) : fmt::format("lc rgb '{}'", kColours[shown[j] % kColours.size()]);
        loops.series.push_back(Series{title, x, Q, fmt::format("lines {} dt {}", col, ps ? 1 : 2)});
      }
    }
    plot_png(file("loops.png"), loops);
    // Energy per cycle in µJ, as in the table and energy.csv.
    PlotSpec e{fmt::format("Energy per cycle against peak force: {}", title_name),
               "peak force Q_peak [N]",
               "energy per cycle [µJ]",
               true,
               true,
               {},
               palette_commands(p)};
    double qmin = 1e300, qmax = 0.0, emin = 1e300, emax = 0.0;
    Series gross{"gross slip", {}, {}, "points pt 6 ps 2.4 lc rgb 'black'"};
    for (std::size_t i = 0; i < nl; ++i) {
      const auto& l = p.loads[i];
      Series sr{legend ? fmt::format("P = {:.0f} N", l.preload) : "", {}, {}, ""};
      sr.style = fmt::format("{} {}", legend ? "linespoints pt 7 ps 1.2" : "lines", colour(l, i));
      for (const auto& a : l.amplitudes) {
        sr.x.push_back(a.Q_peak);
        sr.y.push_back(a.energy * 1e6);
        if (!partial(a)) {
          gross.x.push_back(a.Q_peak);
          gross.y.push_back(a.energy * 1e6);
        }
        qmin = std::min(qmin, a.Q_peak);
        qmax = std::max(qmax, a.Q_peak);
        if (a.energy > 0.0) emin = std::min(emin, a.energy * 1e6);
        emax = std::max(emax, a.energy * 1e6);
      }
      e.series.push_back(sr);
    }
    if (!gross.x.empty()) e.series.push_back(gross);
    // Guides through the smallest-force point of the first preload.
    const auto& a0 = p.loads.front().amplitudes.front();
    add_power_guides(e, a0.Q_peak, a0.energy * 1e6, qmin, qmax);
    if (emin < 1e300) set_energy_force_ranges(e, qmin, qmax, emin, emax);
    plot_png(file("energy_vs_force.png"), e);
  }
  if (sweep) {
    Series mu{"asperity (predicted)", {}, {}, "linespoints pt 7 ps 1.3 lc rgb '#0072b2'"},
        k{"stiffness", {}, {}, "linespoints pt 7 ps 1.3 lc rgb '#0072b2'"};
    for (const auto& l : p.loads) {
      mu.x.push_back(l.preload);
      mu.y.push_back(l.mu);
      k.x.push_back(l.preload);
      k.y.push_back(l.stiffness * 1e-6);
    }
    PlotSpec mu_plot{fmt::format("Friction coefficient against preload: {}", title_name),
                     "preload P [N]",
                     "friction coefficient mu = Q_max/P",
                     false,
                     false,
                     {mu},
                     // The range follows the data (not from 0, which hides the trend), with
                     // room so that no point sits on the frame.
                     "set offsets graph 0.05, graph 0.05, graph 0.15, graph 0.15\n"
                     "set key inside top right box opaque\n"};
    if (c.reference) {
      Series ref{c.reference->source, c.reference->preloads, c.reference->mu,
                 "points pt 5 ps 1.5 lc rgb '#d55e00'"};
      mu_plot.series.push_back(ref);
    } else {
      mu_plot.extra += "set key off\n";
    }
    plot_png(file("mu_vs_preload.png"), mu_plot);
    plot_png(file("stiffness_vs_preload.png"),
             {fmt::format("Tangential stiffness against preload: {}", title_name),
              "preload P [N]",
              "tangential stiffness [N/µm]",
              false,
              false,
              {k},
              "set yrange [0:*]\nset offsets graph 0.05, graph 0.05, graph 0.1, 0\nset key off"});
  }
  return written;
}

std::vector<joint::NamedInput> profile_inputs(const joint::JointCase& c) {
  std::vector<joint::NamedInput> in;
  for (std::size_t h = 0; h < 2; ++h) {
    for (const auto& f : c.halves[h].roughness.profiles)
      in.push_back({fmt::format("a profile of half {} of the case", h + 1), f});
  }
  if (!c.interface.map.file.empty())
    in.push_back({"the pressure map of the case", c.interface.map.file});
  return in;
}

void add_predict_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<PredictOptions>();
  auto* cmd = app.add_subcommand(
      "predict",
      "Friction coefficient, tangential stiffness, fretting loops and energy per cycle of a joint "
      "described by a TOML case file (thesis ch. 5-6; see docs/joints.md and examples/joints).");
  cmd->add_option("case", o->case_file, "the case file (TOML)")->required();
  cmd->add_option(
      "--out", o->out,
      "write summary.json, loops.csv, energy.csv and plots into DIR (a new directory, or "
      "one asperity wrote before); a name ending in .json writes only that JSON file, - prints "
      "it");
  cmd->add_flag("--json", o->json, "print summary.json instead of the table");
  cmd->add_flag("--no-plots", o->no_plots, "do not draw PNG plots (no gnuplot needed)");
  cmd->footer(fmt::format(
      "Environment: {}, the seconds between the progress lines of a sweep when stderr is not "
      "a terminal (default: {:g}; 0: a line after every preload).",
      kProgressIntervalVariable, kDefaultProgressInterval));
  cmd->callback([o, &action] {
    action = [o] {
      return run_guarded([o](std::string& out) {
        const double interval_seconds = progress_interval();  // refused before any work
        const OutKind kind = out_kind(o->out, ".json");
        const bool to_dir = kind == OutKind::directory;
        if (kind == OutKind::standard_output && o->json)
          throw InvalidInput("--json and --out - both print the JSON: give one of them");
        // Refuse an --out that is or holds an input, or a foreign directory, before the work.
        if (to_dir) {
          joint::require_output_apart_from_inputs(*o->out, {{"the case file", o->case_file}});
          joint::require_replaceable_output(*o->out, *o->out);
        } else if (kind == OutKind::file) {
          require_distinct_outputs({{"the case file", o->case_file}, {"--out", *o->out}});
        }
        const auto c = joint::read_case_file(o->case_file);
        if (to_dir) joint::require_output_apart_from_inputs(*o->out, profile_inputs(c));
        if (kind == OutKind::file) {
          for (const auto& in : profile_inputs(c))
            require_distinct_outputs({{in.what, in.path}, {"--out", *o->out}});
        }
        std::vector<std::string> written;
        const bool bar = c.preloads.size() > 1 && isatty(STDERR_FILENO);
        // Not a terminal (a log, a pipe): a plain line at most every `interval` seconds
        // (10, or ASPERITY_PROGRESS_INTERVAL), so a long sweep shows that it runs without
        // flooding the log; nothing for a sweep shorter than the interval.
        using Clock = std::chrono::steady_clock;
        const std::chrono::duration<double> interval(interval_seconds);
        auto last_line = Clock::now();
        bool any_line = false;
        const auto progress = [&](std::size_t i, std::size_t n) {
          if (!bar) {
            const auto now = Clock::now();
            if (n > 1 && (now - last_line >= interval || (any_line && i == n))) {
              // Whole per cent rounded down: 100 % only when every preload is done.
              std::cerr << fmt::format("asperity predict: {}/{} preloads ({} %)\n", i, n,
                                       100 * i / n)
                        << std::flush;
              last_line = now;
              any_line = true;
            }
            return;
          }
          const std::size_t width = 30, done = width * i / n;
          std::cerr << fmt::format("\r[{}{}] {}/{} preloads", std::string(done, '#'),
                                   std::string(width - done, ' '), i, n)
                    << (i == n ? "\n" : "") << std::flush;
        };
        const auto p = joint::predict(c, progress);
        const bool stdout_is_data = o->json || kind == OutKind::standard_output;
        if (to_dir) {
          joint::StagedDirectory dir(*o->out, "asperity predict");
          written = write_prediction_files(c, p, dir, !o->no_plots, true, "");
          dir.commit();
        }
        out = stdout_is_data ? json_output(prediction_json(c, p)) : prediction_summary(c, p);
        if (kind == OutKind::file) {
          write_file_atomically(*o->out, json_output(prediction_json(c, p)));
          report_written({*o->out}, stdout_is_data, out);
        }
        if (to_dir) {
          if (!stdout_is_data) out += "\n";
          report_written_directory(*o->out, written, stdout_is_data, out);
        }
        for (const auto& w : p.warnings) fmt::print(stderr, "warning: {}\n", w);
      });
    };
  });
}

}  // namespace asperity::cli
