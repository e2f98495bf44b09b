// asperity analyze DATA.csv --P 526N [--model CASE.toml] [--out DIR] [--json]:
// measured fretting data (thesis ch. 5-6): cycles, loop metrics of Fig. 6.1, mu of
// Eq. 6.1, the energy-force power law over several runs, and the comparison with a
// prediction. asperity synthesize: a synthetic experiment (Eq. 5.3, Fig. 5.7, noise).
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/fretting.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/vibration/loop_fit.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace dim = core::dim;

namespace {

struct AnalyzeOptions {
  std::vector<std::string> files;
  std::optional<std::string> P, model, out;
  double window = joint::AnalysisOptions{}.stiffness_window;
  int degree = joint::AnalysisOptions{}.stiffness_degree;
  bool stiffness_from_delta = false;
  bool json = false;
  bool no_plots = false;
  std::optional<std::string> fit, element_out;
};

// NaN is not JSON: null.
Json number(double v) {
  return std::isfinite(v) ? Json(v) : Json(nullptr);
}

Json cycle_json(const joint::CycleMetrics& c) {
  return Json{{"t_start", c.t_start},
              {"t_end", c.t_end},
              {"energy", c.energy},
              {"Q_max", c.Q_max},
              {"delta_max", c.delta_max},
              {"stiffness", number(c.stiffness)},
              {"stiffness_resolved", c.stiffness_resolved},
              {"stiffness_unloading", number(c.stiffness_unloading)},
              {"stiffness_reloading", number(c.stiffness_reloading)},
              {"sliding", c.sliding},
              {"partial_slip", c.partial_slip},
              {"Q_center", c.Q_center},
              {"delta_center", c.delta_center}};
}

// The file name without its directories, for plot legends.
std::string base_name(const std::string& path) {
  const auto name = std::filesystem::path(path).filename().string();
  return name.empty() ? path : name;
}

double rel_diff(double ours, double ref) {
  return (ours - ref) / ref;
}

struct Run {
  std::string file;
  joint::FrettingData data;
  joint::FrettingAnalysis a;
  std::optional<joint::LoadPrediction> model;
};

std::string stiffness_method(const joint::FrettingAnalysis& a, double window, int degree) {
  const std::string pooled = fmt::format(
      "over the samples after each reversal until |Q - Q_r| (smoothed) = {} x the cycle's "
      "peak-to-peak force; every branch has the same Masing shape, so the fit is pooled: an "
      "intercept per reversal, a slope per cycle, common coefficients of degree 2..{}",
      window, degree);
  return a.stiffness_from_imposed
             ? fmt::format(
                   "apparatus compliance c from Delta - delta = c Q + const over all samples "
                   "(Fig. 5.7); least-squares Q(Delta) {}; per-cycle joint compliance C_i = "
                   "dDelta/dQ - c at the reversals, k_i = 1/C_i; mean k = 1/mean(C_i) (harmonic "
                   "mean of the k_i) with the standard error from the spread of the C_i",
                   pooled)
             : fmt::format(
                   "least-squares delta(Q) {}; per-cycle joint compliance C_i = d delta/dQ at "
                   "the reversals, k_i = 1/C_i; mean k = 1/mean(C_i) (harmonic mean of the k_i) "
                   "with the standard error from the spread of the C_i",
                   pooled);
}

Json run_json(const Run& r, double window, int degree) {
  Json j;
  j["file"] = r.file;
  j["P"] = r.a.P;
  j["cycles"] = r.a.cycles.size();
  Json pc = Json::array();
  for (const auto& c : r.a.cycles) pc.push_back(cycle_json(c));
  j["per_cycle"] = pc;
  j["mean"] = cycle_json(r.a.mean);
  j["standard_error"] =
      Json{{"energy", r.a.energy_standard_error}, {"stiffness", r.a.stiffness_standard_error}};
  j["mu"] = r.a.mu;
  j["noise"] = Json{{"delta", r.a.noise_delta}, {"Q", r.a.noise_Q}};
  j["energy_noise_floor"] = r.a.energy_noise_floor;
  j["energy_resolved"] = r.a.energy_resolved;
  j["stiffness_window_motion"] = r.a.stiffness_window_motion;
  j["stiffness_noise"] = r.a.stiffness_noise;
  j["warnings"] = r.a.warnings;
  j["averaged_loop"] = Json{{"energy", r.a.loop_energy}, {"points", r.a.loop_delta.size()}};
  if (r.a.stiffness_from_imposed) {
    j["apparatus"] = Json{{"compliance", r.a.apparatus_compliance},
                          {"residual_rms", r.a.apparatus_residual_rms}};
  }
  j["method"] =
      Json{{"cycles",
            "maximum -> minimum -> maximum of the displacement (moving average over 1/50 cycle); "
            "ramps of Eq. 5.3 left out"},
           {"energy",
            "closed integral of Q d delta over the cycle (trapezoidal rule, smoothed signals), "
            "signed; mean over cycles; standard error from their spread; noise floor = sqrt(s_d^2 "
            "Sum dQ^2 + s_Q^2 Sum d delta^2)/sqrt(cycles) with the noise s_d, s_Q estimated from "
            "second differences; resolved when the mean exceeds 3 floors"},
           {"stiffness", stiffness_method(r.a, window, degree)},
           {"Q_max", "half the peak-to-peak force (smoothed)"},
           {"mu", "mean Q_max / P (Eq. 6.1)"},
           {"sliding",
            "half the loop opening at Q = Q_center (delta_s of Fig. 6.1); partial_slip = "
            "delta_max - sliding"}};
  if (r.model) {
    const auto& m = *r.model;
    const auto& amp = m.amplitudes.front();
    j["model"] =
        Json{{"delta_max", amp.delta_max},
             {"Q_peak", amp.Q_peak},
             {"energy", amp.energy},
             {"stiffness", m.stiffness},
             {"mu_static", m.mu},
             {"mu", amp.Q_peak / m.preload},
             {"regime", amp.regime},
             {"relative_difference", Json{{"Q_max", rel_diff(r.a.mean.Q_max, amp.Q_peak)},
                                          {"energy", rel_diff(r.a.mean.energy, amp.energy)},
                                          {"stiffness", rel_diff(r.a.mean.stiffness, m.stiffness)},
                                          {"mu", rel_diff(r.a.mu, amp.Q_peak / m.preload)}}}};
  }
  return j;
}

std::string run_text(const Run& r) {
  const auto& a = r.a;
  std::string s = fmt::format("{}: P = {:.4g} N, {} cycles\n", r.file, a.P, a.cycles.size());
  s += fmt::format("{:>6} {:>12} {:>10} {:>14} {:>12} {:>12} {:>12}\n", "cycle", "energy[uJ]",
                   "Q_max[N]", "delta_max[um]", "k[N/um]", "sliding[um]", "partial[um]");
  bool flagged = false;
  for (std::size_t i = 0; i < a.cycles.size(); ++i) {
    const auto& c = a.cycles[i];
    const std::string k = c.stiffness_resolved ? fmt::format("{:.4g}", c.stiffness * 1e-6)
                                               : fmt::format("{:.4g}*", c.stiffness * 1e-6);
    flagged |= !c.stiffness_resolved;
    s += fmt::format("{:>6} {:>12.5g} {:>10.4g} {:>14.4g} {:>12} {:>12.4g} {:>12.4g}\n", i + 1,
                     c.energy * 1e6, c.Q_max, c.delta_max * 1e6, k, c.sliding * 1e6,
                     c.partial_slip * 1e6);
  }
  const auto& c = a.mean;
  s += fmt::format("{:>6} {:>12.5g} {:>10.4g} {:>14.4g} {:>12.4g} {:>12.4g} {:>12.4g}\n", "mean",
                   c.energy * 1e6, c.Q_max, c.delta_max * 1e6, c.stiffness * 1e-6, c.sliding * 1e6,
                   c.partial_slip * 1e6);
  s += fmt::format("{:>6} {:>12.3g} {:>10} {:>14} {:>12.3g}\n", "+-", a.energy_standard_error * 1e6,
                   "", "", a.stiffness_standard_error * 1e-6);
  if (flagged) s += "  * not resolved: noise exceeds the joint's compliance in this cycle\n";
  s += fmt::format(
      "energy per cycle {:.5g} +- {:.3g} uJ (noise floor {:.3g} uJ{}); averaged loop {:.5g} uJ\n",
      c.energy * 1e6, a.energy_standard_error * 1e6, a.energy_noise_floor * 1e6,
      a.energy_resolved ? "" : ": NOT resolved", a.loop_energy * 1e6);
  s += fmt::format(
      "stiffness {:.4g} +- {:.3g} N/um (harmonic mean over cycles; standard error from their "
      "spread and the fit's shared shape)\n",
      c.stiffness * 1e-6, a.stiffness_standard_error * 1e-6);
  s += fmt::format("mu = Q_max/P = {:.4f} (Eq. 6.1); estimated noise {:.3g} um, {:.3g} N\n", a.mu,
                   a.noise_delta * 1e6, a.noise_Q);
  if (a.stiffness_from_imposed) {
    s += fmt::format(
        "stiffness from Q(Delta) and the apparatus compliance {:.5g} um/N ({:.4g} N/um; fit "
        "residual {:.3g} um rms)\n",
        a.apparatus_compliance * 1e6, 1e-6 / a.apparatus_compliance,
        a.apparatus_residual_rms * 1e6);
  }
  if (r.model) {
    const auto& m = *r.model;
    const auto& amp = m.amplitudes.front();
    s += fmt::format(
        "model at delta_max = {:.4g} um ({}): Q_peak {:.4g} N ({:+.1f} %), energy {:.5g} uJ "
        "({:+.1f} %), stiffness {:.4g} N/um ({:+.1f} %), mu {:.4f} ({:+.1f} %)\n",
        amp.delta_max * 1e6, amp.regime, amp.Q_peak, 100 * rel_diff(a.mean.Q_max, amp.Q_peak),
        amp.energy * 1e6, 100 * rel_diff(a.mean.energy, amp.energy), m.stiffness * 1e-6,
        100 * rel_diff(a.mean.stiffness, m.stiffness), amp.Q_peak / m.preload,
        100 * rel_diff(a.mu, amp.Q_peak / m.preload));
  }
  for (const auto& w : a.warnings) s += "warning: " + w + "\n";
  return s;
}

// The energy-force power law over the runs whose energy is resolved (the others would
// put the noise floor's slope into the exponent).
struct PowerLaw {
  std::optional<joint::PowerLawFit> fit;
  std::vector<std::size_t> used, excluded;
  std::vector<std::string> warnings;
  std::string note;  ///< how the exponent compares with the model's (not a warning)
};

// The exponent against Masing's rules on the model's backbone (docs/joints.md, "Energy
// against force"): its local exponent tends to 3 at small amplitude (Mindlin: W ~ Q^3)
// and grows above 3 as Q_max approaches the static friction force, without bound at
// gross slip. An exponent above 3 is therefore what partial slip gives near saturation,
// not a sign of gross slip by itself; the thesis's experiments gave 2-3 (section 6.3).
std::string power_law_note(double n) {
  if (n >= 3.0) {
    return fmt::format(
        "n = {:.3g}: at or above 3, the small-amplitude limit of Masing's rules (Mindlin: energy "
        "~ Q^3); on the model's backbone the local n grows above 3 as the peak force approaches "
        "the static friction force Q_s, still in partial slip (about 3.3 at 0.25 Q_s, 4 at "
        "0.55 Q_s, 5 at 0.75 Q_s, 8 at 0.9 Q_s for the thesis's steel joints), and without "
        "bound at gross slip; the thesis measured 2-3 in partial slip (Fig. 6.12-6.14)",
        n);
  }
  return fmt::format(
      "n = {:.3g}: below 3, where the model's exponent never goes (its local exponent tends to 3 "
      "from above at small amplitude, Masing/Mindlin); it lies in the 2-3 the thesis measured "
      "(Fig. 6.12-6.14), a range the model does not reproduce",
      n);
}

PowerLaw power_law(const std::vector<Run>& runs) {
  PowerLaw p;
  std::vector<double> q, e;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const auto& a = runs[k].a;
    if (a.energy_resolved && a.mean.energy > 0.0) {
      p.used.push_back(k);
      q.push_back(a.mean.Q_max);
      e.push_back(a.mean.energy);
    } else {
      p.excluded.push_back(k);
    }
  }
  if (!p.excluded.empty()) {
    std::string list;
    for (auto k : p.excluded) list += (list.empty() ? "" : ", ") + runs[k].file;
    p.warnings.push_back(fmt::format(
        "power law: {} left out (energy per cycle below 3 times its noise floor)", list));
  }
  if (q.size() >= 2) {
    try {
      p.fit = joint::fit_power_law(q, e);
      p.note = power_law_note(p.fit->exponent);
    } catch (const InvalidInput& ex) {
      p.warnings.push_back(ex.what());
    }
  } else {
    p.warnings.push_back(fmt::format(
        "power law: {} run(s) with a resolved energy; at least two are needed for the exponent",
        q.size()));
  }
  return p;
}

// The averaged loops of the runs, as the loop fit takes them (unloading branch first).
std::vector<vibration::MeasuredLoop> measured_loops(const std::vector<Run>& runs) {
  std::vector<vibration::MeasuredLoop> loops;
  for (const auto& r : runs) {
    loops.push_back({.delta = r.a.loop_delta,
                     .Q = r.a.loop_Q,
                     .unloading = r.a.loop_delta.size() / 2,
                     .source = r.file});
  }
  return loops;
}

// What the sensors' noise leaves in the averaged loops' forces, and the warnings of a fit.
struct FitChecks {
  double noise_floor = 0.0;  ///< rms over runs of sqrt(s_Q^2 + (k s_d)^2)/sqrt(cycles) [N]
  std::vector<std::string> warnings;
};

FitChecks fit_checks(const vibration::LoopFit& f, const std::vector<Run>& runs) {
  FitChecks c;
  // The stiffness at the reversals: k_t or K_T.
  const double k = f.model == vibration::LoopModel::jenkins ? f.value("k_t") : f.value("K_T");
  double ss = 0.0, worst = 0.0;
  for (const auto& r : runs) {
    const double n = static_cast<double>(r.a.cycles.size());
    const double sx = k * r.a.noise_delta;  // displacement noise as force
    ss += (r.a.noise_Q * r.a.noise_Q + sx * sx) / n;
    worst = std::max(worst, sx / std::max(r.a.noise_Q, 1e-300));
  }
  c.noise_floor = std::sqrt(ss / static_cast<double>(runs.size()));
  std::string undetermined;
  for (const auto& p : f.parameters) {
    if (!std::isfinite(p.standard_error))
      undetermined += (undetermined.empty() ? "" : ", ") + p.name;
  }
  if (!undetermined.empty()) {
    c.warnings.push_back(fmt::format(
        "fit: {} not determined by these loops (a parameter at its bound, or F_S of loops that "
        "never reach macro-slip): fit loops over a wider range of amplitudes, or a model with "
        "fewer parameters",
        undetermined));
  }
  // Warned when the displacement noise dominates the force noise and is a sizeable part
  // (a third) of the residual: then it, not the model, limits the fit.
  if (worst > 1.0 && c.noise_floor > f.residual_rms / 3.0) {
    c.warnings.push_back(fmt::format(
        "fit: the displacement noise times the fitted stiffness ({:.3g} N/um) is up to {:.3g} "
        "times the force noise: the loops' displacements are the noisier signal, which biases "
        "the fitted stiffness low (errors in the regressor near the reversals; docs/joints.md); "
        "a finer displacement sensor or more cycles reduce it",
        k * 1e-6, worst));
  }
  return c;
}

Json fit_json(const vibration::LoopFit& f, const std::vector<Run>& runs) {
  Json params = Json::object(), element = Json::object();
  element["type"] = std::string(vibration::to_string(f.model));
  for (const auto& p : f.parameters) {
    params[p.name] =
        Json{{"value", p.value}, {"standard_error", number(p.standard_error)}, {"unit", p.unit}};
    element[p.name] = p.value;
  }
  Json offsets = Json::array(), files = Json::array();
  for (std::size_t k = 0; k < f.Q_offsets.size(); ++k) {
    offsets.push_back(f.Q_offsets[k]);
    files.push_back(runs[k].file);
  }
  return Json{
      {"model", std::string(vibration::to_string(f.model))},
      {"parameters", params},
      {"residual_rms", f.residual_rms},
      {"relative_residual", f.relative_residual},
      {"points", f.points},
      {"loops", files},
      {"Q_offsets", offsets},
      {"element", element},
      {"element_toml", f.case_toml()},
      {"noise_floor", fit_checks(f, runs).noise_floor},
      {"warnings", fit_checks(f, runs).warnings},
      {"method",
       "least squares (Levenberg-Marquardt, several starts) of the averaged loops of all runs "
       "at once by the element's steady Masing loop, Q = Q_c +- B(a) -+ 2 B(|x - x_rev|/2), "
       "with shared parameters and a force offset Q_c per loop; standard errors s^2 (J^T J)^-1 "
       "treating the points as independent (a lower bound: neighbouring points are "
       "correlated), null when the loops do not determine the parameter"}};
}

std::string fit_text(const vibration::LoopFit& f, const std::vector<Run>& runs) {
  std::string s = fmt::format("{} fit of the averaged loop{}:\n", vibration::to_string(f.model),
                              f.loops == 1 ? "" : "s");
  for (const auto& p : f.parameters) {
    s += fmt::format("  {:<5} = {:.6g}{} +- {}\n", p.name, p.value,
                     p.unit.empty() ? "" : " " + p.unit,
                     std::isfinite(p.standard_error) ? fmt::format("{:.3g}", p.standard_error)
                                                     : std::string("(not determined)"));
  }
  s += fmt::format(
      "  rms residual {:.4g} N ({:.3g} % of the mean half peak-to-peak force), {} points; the "
      "sensors' noise leaves {:.3g} N in the averaged loops\n",
      f.residual_rms, 100.0 * f.relative_residual, f.points, fit_checks(f, runs).noise_floor);
  for (const auto& w : fit_checks(f, runs).warnings) s += "warning: " + w + "\n";
  return s + "as a vibration case element:\n" + f.case_toml();
}

// energy_vs_force.png of several runs: the runs (left-out ones marked), the fitted power
// law and the slope-2 and slope-3 guides of Fig. 6.12-6.14.
PlotSpec energy_plot(const std::vector<Run>& runs, const PowerLaw& law) {
  PlotSpec e{fmt::format("Energy per cycle against peak force: {} runs at P = {:.4g} N",
                         runs.size(), runs.front().a.P),
             "peak force [N]",
             "energy per cycle [µJ]",
             true,
             true,
             {},
             "set key inside left top box opaque\n"};
  Series used{"runs", {}, {}, "points pt 7 ps 1.5 lc rgb '#1f4e9a'"};
  Series excl{
      "runs below the noise floor (left out)", {}, {}, "points pt 6 ps 1.5 lc rgb '#c0392b'"};
  double qmin = 1e300, qmax = 0.0, lq = 0.0, le = 0.0;
  std::size_t nlog = 0;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const auto& a = runs[k].a;
    const bool in = std::find(law.used.begin(), law.used.end(), k) != law.used.end();
    // A non-positive energy has no place on a log axis: it is noise, drawn at the floor.
    const double energy = a.mean.energy > 0.0 ? a.mean.energy : a.energy_noise_floor;
    auto& sr = in ? used : excl;
    sr.x.push_back(a.mean.Q_max);
    sr.y.push_back(energy);
    qmin = std::min(qmin, a.mean.Q_max);
    qmax = std::max(qmax, a.mean.Q_max);
    if (in || law.used.empty()) {
      lq += std::log(a.mean.Q_max);
      le += std::log(energy);
      ++nlog;
    }
  }
  if (!used.x.empty()) e.series.push_back(used);
  if (!excl.x.empty()) e.series.push_back(excl);
  const double q0 = std::exp(lq / static_cast<double>(nlog));
  const double e0 = std::exp(le / static_cast<double>(nlog));
  if (law.fit) {
    const auto& f = *law.fit;
    Series fit{std::isfinite(f.ci_low) ? fmt::format("fit: n = {:.2f} (95 %: {:.2f} to {:.2f})",
                                                     f.exponent, f.ci_low, f.ci_high)
                                       : fmt::format("fit: n = {:.2f}", f.exponent),
               {},
               {},
               "lines lc rgb '#1f4e9a'"};
    double lqu = 0.0, leu = 0.0, qlo = 1e300, qhi = 0.0;
    for (auto k : law.used) {
      lqu += std::log(runs[k].a.mean.Q_max);
      leu += std::log(runs[k].a.mean.energy);
      qlo = std::min(qlo, runs[k].a.mean.Q_max);
      qhi = std::max(qhi, runs[k].a.mean.Q_max);
    }
    const double nu = static_cast<double>(law.used.size());
    for (int i = 0; i <= 20; ++i) {  // over the runs it was fitted to
      const double q = qlo * std::pow(qhi / qlo, i / 20.0);
      fit.x.push_back(q);
      fit.y.push_back(std::exp(leu / nu + f.exponent * (std::log(q) - lqu / nu)));
    }
    e.series.push_back(fit);
  }
  // Runs the --model prediction puts in gross slip, ringed (their Q_max is the static
  // friction force).
  Series gross{"gross slip (--model)", {}, {}, "points pt 6 ps 2.4 lc rgb 'black'"};
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const auto& m = runs[k].model;
    if (m && m->amplitudes.front().regime == "gross slip") {
      gross.x.push_back(runs[k].a.mean.Q_max);
      gross.y.push_back(runs[k].a.mean.energy > 0.0 ? runs[k].a.mean.energy
                                                    : runs[k].a.energy_noise_floor);
    }
  }
  if (!gross.x.empty()) e.series.push_back(gross);
  add_power_guides(e, q0, e0, qmin, qmax);
  double emin = 1e300, emax = 0.0;
  for (auto& sr : e.series) {
    for (double& y : sr.y) y *= 1e6;  // J -> µJ, the unit of the table
  }
  for (const auto* sr : {&used, &excl}) {
    for (double y : sr->y) {
      if (y > 0.0) {
        emin = std::min(emin, y * 1e6);
        emax = std::max(emax, y * 1e6);
      }
    }
  }
  if (emin < 1e300) set_energy_force_ranges(e, qmin, qmax, emin, emax);
  return e;
}

}  // namespace

void add_analyze_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<AnalyzeOptions>();
  auto* cmd = app.add_subcommand(
      "analyze",
      "Measured fretting data (CSV columns t, delta, Q with units in the header, optionally the "
      "imposed Delta): cycles, energy per cycle, stiffness at reversals, peak force, mu = Q_max/P "
      "(Eq. 6.1), slip displacements (Fig. 6.1), standard errors and noise checks; several files "
      "give the energy-force power law.");
  cmd->add_option("data", o->files, "fretting data files (CSV)")->required();
  cmd->add_option("--P,--preload", o->P, "normal load (preload) of the runs, e.g. 526N")
      ->required();
  cmd->add_option("--model", o->model,
                  "a case file: overlay its prediction and quantify the differences");
  cmd->add_option("--out", o->out,
                  "write analysis.json, cycles.csv, cycle_traces.csv, averaged_loop.csv and plots "
                  "into DIR (a new directory, or one asperity wrote before); a name ending in "
                  ".json writes only analysis.json there, - prints it");
  cmd->add_option(
      "--window", o->window,
      fmt::format(
          "stiffness fit window, fraction of the peak-to-peak force, in (0, 0.5] (default: {})",
          o->window));
  cmd->add_option(
      "--degree", o->degree,
      fmt::format("polynomial degree of the stiffness fit, 1-4 (default: {})", o->degree));
  cmd->add_flag("--stiffness-from-delta", o->stiffness_from_delta,
                "fit the stiffness on the measured delta even when the imposed Delta is given "
                "(without it, when Delta is given: Q(Delta) and the fitted apparatus compliance)");
  cmd->add_flag("--json", o->json, "print JSON instead of tables");
  cmd->add_flag("--no-plots", o->no_plots, "do not draw PNG plots");
  cmd->add_option("--fit", o->fit,
                  "fit the averaged loops of all runs by a vibration element: jenkins (k_t, F_s) "
                  "or iwan4 (Segalman's F_S, K_T, chi, beta); least squares with standard errors "
                  "and the residual, printed as a vibration case's [[element]] (element.toml "
                  "with --out DIR)");
  cmd->add_option("--element-out", o->element_out,
                  "write the fitted [[element]] table (TOML) to this file (- for standard output)");
  cmd->callback([o, &action] {
    action = [o] {
      return run_guarded([o](std::string& out) {
        const double P = required_quantity(o->P, dim::force, "--P");
        if (!(P > 0.0)) throw InvalidInput(fmt::format("--P = {}: must be > 0", *o->P));
        if (!(o->window > 0.0 && o->window <= 0.5)) {
          throw InvalidInput(fmt::format("--window = {}: must be in (0, 0.5]", o->window));
        }
        if (o->degree < 1 || o->degree > 4) {
          throw InvalidInput(fmt::format("--degree = {}: must be 1, 2, 3 or 4", o->degree));
        }
        std::optional<vibration::LoopModel> fit_model;
        if (o->fit) fit_model = vibration::parse_loop_model(lowercase(*o->fit), "--fit");
        if (o->element_out && !o->fit)
          throw InvalidInput("--element-out writes the fitted element: give --fit jenkins|iwan4");
        const OutKind kind = out_kind(o->out, ".json");
        const bool to_dir = kind == OutKind::directory;
        if (kind == OutKind::standard_output && o->json)
          throw InvalidInput("--json and --out - both print the JSON: give one of them");
        const bool stdout_is_data = o->json || kind == OutKind::standard_output;
        // Refuse an --out that is or holds an input, or a foreign directory, before the work.
        if (to_dir || kind == OutKind::file) {
          std::vector<joint::NamedInput> inputs;
          for (const auto& f : o->files) inputs.push_back({"the data file", f});
          if (o->model) inputs.push_back({"the --model case file", *o->model});
          if (to_dir) {
            joint::require_output_apart_from_inputs(*o->out, inputs);
            joint::require_replaceable_output(*o->out, *o->out);
          } else {
            for (const auto& in : inputs)
              require_distinct_outputs({{in.what, in.path}, {"--out", *o->out}});
          }
        }
        if (o->element_out) {
          if (is_standard_output(*o->element_out) && stdout_is_data)
            throw InvalidInput(
                "--element-out - and the JSON both print to standard output: give "
                "--element-out a file name");
          if (!is_standard_output(*o->element_out)) {
            for (const auto& f : o->files)
              require_distinct_outputs({{"the data file", f}, {"--element-out", *o->element_out}});
            if (o->model)
              require_distinct_outputs(
                  {{"the --model case file", *o->model}, {"--element-out", *o->element_out}});
            if (o->out)
              require_distinct_outputs({{"--out", *o->out}, {"--element-out", *o->element_out}});
          }
        }
        std::optional<joint::JointCase> model_case;  // its [interface], if any, applies
        if (o->model) {
          model_case = joint::read_case_file(*o->model);
          if (to_dir) joint::require_output_apart_from_inputs(*o->out, profile_inputs(*model_case));
        }
        std::vector<Run> runs;
        for (const auto& f : o->files) {
          Run r;
          r.file = f;
          r.data = joint::read_fretting_csv(f);
          r.a = joint::analyze_fretting(r.data, P,
                                        {.stiffness_window = o->window,
                                         .stiffness_degree = o->degree,
                                         .stiffness_from_imposed = !o->stiffness_from_delta});
          if (model_case) r.model = joint::predict_case_load(*model_case, P, {r.a.mean.delta_max});
          runs.push_back(std::move(r));
        }
        std::optional<vibration::LoopFit> fit;
        if (o->fit) fit = vibration::fit_loops(measured_loops(runs), *fit_model);
        std::optional<PowerLaw> law;
        if (runs.size() >= 2) law = power_law(runs);
        if (law && law->fit) {
          // With --model: name the fitted runs the model puts in gross slip (the exponent
          // alone cannot tell, see power_law_note).
          std::string gross;
          for (auto k : law->used) {
            const auto& m = runs[k].model;
            if (m && m->amplitudes.front().regime == "gross slip")
              gross += (gross.empty() ? "" : ", ") + runs[k].file;
          }
          if (!gross.empty()) {
            law->warnings.push_back(fmt::format(
                "power law: {} in gross slip by the --model prediction (Q_max there is the "
                "static friction force, the energy grows without it): the exponent is not a "
                "partial-slip one",
                gross));
          }
        }
        Json j;
        if (runs.size() == 1) {
          j = run_json(runs.front(), o->window, o->degree);
        } else {
          Json rs = Json::array();
          for (const auto& r : runs) rs.push_back(run_json(r, o->window, o->degree));
          j["runs"] = rs;
          const auto& f = law->fit;
          j["power_law_exponent"] = f ? Json(f->exponent) : Json(nullptr);
          Json used = Json::array(), excl = Json::array();
          for (auto k : law->used) used.push_back(runs[k].file);
          for (auto k : law->excluded) excl.push_back(runs[k].file);
          j["power_law"] =
              Json{{"exponent", f ? Json(f->exponent) : Json(nullptr)},
                   {"standard_error", f ? number(f->standard_error) : Json(nullptr)},
                   {"ci95", f && std::isfinite(f->ci_low) ? Json::array({f->ci_low, f->ci_high})
                                                          : Json(nullptr)},
                   {"runs_used", used},
                   {"runs_excluded", excl},
                   {"note", f ? Json(law->note) : Json(nullptr)},
                   {"method",
                    "least squares of log(energy) on log(Q_max) over the runs whose energy per "
                    "cycle exceeds 3 times its noise floor; 95 % interval from Student's t"}};
          j["warnings"] = law->warnings;
        }
        if (fit) j["fit"] = fit_json(*fit, runs);
        // Warnings go to stderr (and into the JSON).
        for (const auto& r : runs) {
          for (const auto& w : r.a.warnings)
            std::cerr << fmt::format("asperity: warning: {}: {}\n", r.file, w);
        }
        if (law) {
          for (const auto& w : law->warnings) std::cerr << "asperity: warning: " << w << "\n";
        }
        if (fit) {
          for (const auto& w : fit_checks(*fit, runs).warnings)
            std::cerr << "asperity: warning: " << w << "\n";
        }
        std::vector<std::string> written;
        if (kind == OutKind::file) write_file_atomically(*o->out, json_output(j));
        if (to_dir) {
          joint::StagedDirectory dir(*o->out, "asperity analyze");
          written = {"analysis.json", "cycles.csv", "cycle_traces.csv", "averaged_loop.csv"};
          write_file_atomically(dir.file("analysis.json"), json_output(j));
          if (fit) {
            write_file_atomically(dir.file("element.toml"), fit->case_toml());
            written.emplace_back("element.toml");
          }
          std::vector<std::vector<double>> cc(9), lc(4), tc(6);
          for (std::size_t k = 0; k < runs.size(); ++k) {
            const auto& d = runs[k].data;
            for (std::size_t i = 0; i < runs[k].a.cycles.size(); ++i) {
              const auto& c = runs[k].a.cycles[i];
              const double row[] = {double(k + 1),
                                    double(i + 1),
                                    c.energy * 1e6,
                                    c.Q_max,
                                    c.delta_max * 1e6,
                                    c.stiffness * 1e-6,
                                    c.stiffness_resolved ? 1.0 : 0.0,
                                    c.sliding * 1e6,
                                    c.partial_slip * 1e6};
              for (std::size_t col = 0; col < cc.size(); ++col) cc[col].push_back(row[col]);
              for (std::size_t s = c.first_sample; s <= c.last_sample; ++s) {
                const double tr[] = {double(k + 1), double(i + 1),
                                     d.t[s],        d.delta[s] * 1e6,
                                     d.Q[s],        d.Delta.empty() ? 0.0 : d.Delta[s] * 1e6};
                for (std::size_t col = 0; col < tc.size(); ++col) tc[col].push_back(tr[col]);
              }
            }
            const auto& a = runs[k].a;
            for (std::size_t i = 0; i < a.loop_delta.size(); ++i) {
              lc[0].push_back(double(k + 1));
              lc[1].push_back(double(i));
              lc[2].push_back(a.loop_delta[i] * 1e6);
              lc[3].push_back(a.loop_Q[i]);
            }
          }
          // Non-finite per-cycle stiffness: the CSV writer wants numbers; 0 with the flag.
          for (double& v : cc[5]) {
            if (!std::isfinite(v)) v = 0.0;
          }
          core::write_csv_table(
              dir.file("cycles.csv"),
              {"run", "cycle", "energy[uJ]", "Q_max[N]", "delta_max[um]", "stiffness[N/um]",
               "stiffness_resolved", "sliding[um]", "partial_slip[um]"},
              cc);
          bool all_imposed = true;
          for (const auto& r : runs) all_imposed &= !r.data.Delta.empty();
          if (!all_imposed) tc.pop_back();
          std::vector<std::string> th{"run", "cycle", "t[s]", "delta[um]", "Q[N]"};
          if (all_imposed) th.emplace_back("Delta[um]");
          core::write_csv_table(dir.file("cycle_traces.csv"), th, tc);
          core::write_csv_table(dir.file("averaged_loop.csv"),
                                {"run", "index", "delta[um]", "Q[N]"}, lc);
          if (!o->no_plots) {
            // Legend: the files' base names (their directories would take half the width);
            // one run: its name in the title, a key only to tell measured from model.
            const bool single = runs.size() == 1;
            PlotSpec loops{
                single ? fmt::format("Averaged fretting loop: {}", base_name(runs.front().file))
                       : "Averaged fretting loops",
                "delta [µm]",
                "Q [N]",
                false,
                false,
                {},
                single && !runs.front().model && !fit ? "set key off"
                                                      : "set key inside left top box opaque"};
            for (const auto& r : runs) {
              Series s{single ? "measured" : fmt::format("{} (measured)", base_name(r.file)),
                       {},
                       r.a.loop_Q,
                       "lines"};
              for (double x : r.a.loop_delta) s.x.push_back(x * 1e6);
              s.x.push_back(s.x.front());
              s.y.push_back(s.y.front());
              loops.series.push_back(s);
              if (fit) {
                const std::size_t k = static_cast<std::size_t>(&r - runs.data());
                Series fs{single ? fmt::format("{} fit", vibration::to_string(fit->model))
                                 : fmt::format("{} ({} fit)", base_name(r.file),
                                               vibration::to_string(fit->model)),
                          {},
                          fit->Q_model[k],
                          "lines dt 3"};
                for (double x : r.a.loop_delta) fs.x.push_back(x * 1e6);
                loops.series.push_back(fs);
              }
              if (r.model) {
                auto [x, Q] = joint::steady_loop(*r.model, r.a.mean.delta_max, 100);
                Series m{single ? "model" : fmt::format("{} (model)", base_name(r.file)),
                         {},
                         {},
                         "lines dt 2"};
                for (std::size_t i = 0; i < x.size(); ++i) {
                  m.x.push_back((x[i] + r.a.mean.delta_center) * 1e6);
                  m.y.push_back(Q[i] + r.a.mean.Q_center);
                }
                loops.series.push_back(m);
              }
            }
            plot_png(dir.file("loops.png"), loops);
            written.emplace_back("loops.png");
            if (runs.size() >= 2) {
              plot_png(dir.file("energy_vs_force.png"), energy_plot(runs, *law));
              written.emplace_back("energy_vs_force.png");
            }
          }
          dir.commit();
        }
        if (stdout_is_data) {
          out = json_output(j);
        } else {
          for (const auto& r : runs) out += run_text(r) + "\n";
          if (law) {
            if (law->fit) {
              const auto& f = *law->fit;
              out += fmt::format(
                  "energy ~ Q_max^n over {} of {} runs: n = {:.3f}{}\n", f.runs, runs.size(),
                  f.exponent,
                  std::isfinite(f.ci_low)
                      ? fmt::format(" (95 % interval {:.3f} to {:.3f})", f.ci_low, f.ci_high)
                      : std::string(" (two runs: no interval)"));
              out += "note: " + law->note + "\n";
            }
            for (const auto& w : law->warnings) out += "warning: " + w + "\n";
          }
          if (fit) out += fit_text(*fit, runs);
        }
        if (fit && o->element_out) {
          write_output(*o->element_out, fit->case_toml(), out);
          if (!is_standard_output(*o->element_out))
            report_written({*o->element_out}, stdout_is_data, out);
        }
        if (kind == OutKind::file) report_written({*o->out}, stdout_is_data, out);
        if (to_dir) report_written_directory(*o->out, written, stdout_is_data, out);
      });
    };
  });
}

namespace {
struct SynthOptions {
  std::string case_file;
  std::optional<std::string> imposed, preload,
      frequency = "1Hz", rate = "1000Hz", noise_delta = "0.1um", noise_Q = "1N", k_pzt = "38N/um",
      k_lc = "1462N/um";
  std::string out;
  int cycles = 10;
  std::uint64_t seed = 1;
  bool no_imposed = false;
  bool json = false;
};
}  // namespace

void add_synthesize_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<SynthOptions>();
  auto* cmd = app.add_subcommand(
      "synthesize",
      "A synthetic fretting experiment with a known answer: the PZT tip follows Eq. 5.3, the joint "
      "of CASE (Masing on its rough-flat backbone) sits in series with the apparatus springs of "
      "Fig. 5.7, and sensor noise is added (seeded). Writes t, delta, Q, Delta as CSV.");
  cmd->add_option("case", o->case_file, "the case file (TOML)")->required();
  cmd->add_option("--imposed", o->imposed,
                  "half peak-to-peak PZT tip motion (0.5 A of Eq. 5.3), e.g. 6.75um")
      ->required();
  cmd->add_option("--P,--preload", o->preload, "preload (default: the case's first load case)");
  cmd->add_option("--cycles", o->cycles, "harmonic cycles (default: 10)");
  cmd->add_option("--frequency", o->frequency, "frequency f of Eq. 5.3 (default: 1Hz)");
  cmd->add_option("--rate", o->rate, "sample rate (default: 1000Hz)");
  cmd->add_option("--noise-delta", o->noise_delta,
                  "rms noise of the displacement sensor (default: 0.1um)");
  cmd->add_option("--noise-Q", o->noise_Q, "rms noise of the load cell (default: 1N)");
  cmd->add_option("--k-pzt", o->k_pzt,
                  "stiffness of the PZT side of the apparatus (default: 38N/um)");
  cmd->add_option("--k-lc", o->k_lc, "stiffness of the load-cell side (default: 1462N/um)");
  // Checked on the text: CLI11 would read "-1" as 2^64 - 1.
  cmd->add_option("--seed", o->seed, "random seed (default: 1)")
      ->check(whole_number_in(0, std::numeric_limits<std::size_t>::max()));
  cmd->add_flag("--no-imposed", o->no_imposed, "leave out the Delta column");
  cmd->add_option("--out", o->out, "output CSV file (- for standard output)")->required();
  cmd->add_flag("--json", o->json,
                "print what was written (file, samples, preload, mu, stiffness, settings) as "
                "JSON instead of a line");
  cmd->callback([o, &action] {
    action = [o] {
      return run_guarded([o](std::string& out) {
        // The CSV must not replace the case file it is made from.
        require_distinct_outputs({{"the case file", o->case_file}, {"--out", o->out}});
        require_one_stdout(o->json, {{"--out", o->out}});
        if (o->cycles < 1)
          throw InvalidInput(fmt::format("--cycles = {}: must be >= 1", o->cycles));
        joint::SyntheticOptions s;
        s.excitation.amplitude = required_quantity(o->imposed, dim::length, "--imposed");
        s.excitation.frequency = required_quantity(o->frequency, dim::frequency, "--frequency");
        s.excitation.cycles = o->cycles;
        s.sample_rate = required_quantity(o->rate, dim::frequency, "--rate");
        if (!(s.excitation.amplitude > 0.0) || !std::isfinite(s.excitation.amplitude))
          throw InvalidInput(fmt::format("--imposed = {}: must be > 0", *o->imposed));
        if (s.excitation.amplitude > joint::kMaxImposedAmplitude) {
          throw InvalidInput(fmt::format(
              "--imposed = {} is not allowed: at most 1 mm, beyond the stroke of fretting PZT "
              "stacks (the thesis's 2.25-18 um, section 6.2); check the unit",
              *o->imposed));
        }
        if (!(s.excitation.frequency > 0.0) || !std::isfinite(s.excitation.frequency))
          throw InvalidInput(fmt::format("--frequency = {}: must be > 0", *o->frequency));
        if (!(s.sample_rate > 0.0) || !std::isfinite(s.sample_rate))
          throw InvalidInput(fmt::format("--rate = {}: must be > 0", *o->rate));
        // Limits of joint::synthetic_experiment (fretting.hpp says why), named by flag.
        const double per_period = s.sample_rate / s.excitation.frequency;
        if (per_period < joint::kMinSamplesPerPeriod) {
          throw InvalidInput(fmt::format(
              "--rate = {} gives {:.3g} samples per period at --frequency = {}; analyze needs at "
              "least {:.0f} per period to resolve the loop (its stiffness fit takes about 1/5 "
              "period after each reversal): give --rate >= {:.6g} Hz",
              *o->rate, per_period, *o->frequency, joint::kMinSamplesPerPeriod,
              joint::kMinSamplesPerPeriod * s.excitation.frequency));
        }
        const double samples = std::floor(s.excitation.duration() * s.sample_rate) + 1.0;
        if (samples > joint::kMaxSyntheticSamples) {
          throw InvalidInput(fmt::format(
              "--rate = {} over --cycles = {} (+1 for the ramps of Eq. 5.3) at --frequency = {} "
              "is {:.4g} samples, above the limit of {:.0e} (about 500 MB of CSV, 1 GB of "
              "memory): lower --rate or --cycles",
              *o->rate, o->cycles, *o->frequency, samples, joint::kMaxSyntheticSamples));
        }
        const auto c = joint::read_case_file(o->case_file);
        for (const auto& in : profile_inputs(c))  // nor a scan the case reads
          require_distinct_outputs({{in.what, in.path}, {"--out", o->out}});
        const double P =
            o->preload ? required_quantity(o->preload, dim::force, "--P") : c.preloads.front();
        if (!(P > 0.0) || !std::isfinite(P))
          throw InvalidInput(fmt::format("--P = {}: must be > 0", o->preload.value_or("")));
        s.noise_delta = required_quantity(o->noise_delta, dim::length, "--noise-delta");
        s.noise_Q = required_quantity(o->noise_Q, dim::force, "--noise-Q");
        s.pzt_stiffness = required_quantity(o->k_pzt, dim::stiffness, "--k-pzt");
        s.load_cell_stiffness = required_quantity(o->k_lc, dim::stiffness, "--k-lc");
        // Under the flags' names (the library says "sample rate and stiffnesses").
        core::require_non_negative("--noise-delta", s.noise_delta);
        core::require_non_negative("--noise-Q", s.noise_Q);
        core::require_positive("--k-pzt", s.pzt_stiffness);
        core::require_positive("--k-lc", s.load_cell_stiffness);
        s.seed = o->seed;
        const auto lp = joint::predict_case_load(c, P);  // with the case's [interface]
        if (lp.odfalk_vingsbo) {
          throw InvalidInput(
              fmt::format("{}: interface.tangential = \"odfalk_vingsbo\": synthesize simulates the "
                          "apparatus on a Masing backbone only; use tangential = \"mindlin\"",
                          c.interface.origin));
        }
        const auto d = joint::synthetic_experiment(lp.backbone, s);
        std::vector<std::vector<double>> cols(o->no_imposed ? 3 : 4);
        cols[0] = d.t;
        for (double x : d.delta) cols[1].push_back(x * 1e6);
        cols[2] = d.Q;
        if (!o->no_imposed) {
          for (double x : d.Delta) cols[3].push_back(x * 1e6);
        }
        std::vector<std::string> header{"t[s]", "delta[um]", "Q[N]"};
        if (!o->no_imposed) header.emplace_back("Delta[um]");
        write_output(o->out, csv_text(header, cols), out);
        if (o->json) {
          Json j{{"out", o->out},
                 {"samples", d.t.size()},
                 {"P", P},
                 {"mu", lp.mu},
                 {"stiffness", lp.stiffness},
                 {"imposed", s.excitation.amplitude},
                 {"frequency", s.excitation.frequency},
                 {"cycles", o->cycles},
                 {"sample_rate", s.sample_rate},
                 {"noise_delta", s.noise_delta},
                 {"noise_Q", s.noise_Q},
                 {"pzt_stiffness", s.pzt_stiffness},
                 {"load_cell_stiffness", s.load_cell_stiffness},
                 {"seed", s.seed},
                 {"columns", header}};
          out += json_output(j);
        } else if (is_standard_output(o->out)) {
          std::cerr << fmt::format("{} samples; P = {:.4g} N, mu = {:.4f}, stiffness {:.4g} N/um\n",
                                   d.t.size(), P, lp.mu, lp.stiffness * 1e-6);
        } else {
          out = fmt::format(
              "wrote {} ({} samples; P = {:.4g} N, mu = {:.4f}, stiffness {:.4g} N/um)\n", o->out,
              d.t.size(), P, lp.mu, lp.stiffness * 1e-6);
        }
      });
    };
  });
}

}  // namespace asperity::cli
