// asperity analyze DATA.csv --P 526N [--model CASE.toml] [--out DIR] [--json]:
// measured fretting data (thesis ch. 5-6): cycles, loop metrics of Fig. 6.1, mu of
// Eq. 6.1, the energy-force power law over several runs, and the comparison with a
// prediction. asperity synthesize: a synthetic experiment (Eq. 5.3, Fig. 5.7, noise).
#include <fmt/format.h>

#include <cmath>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/fretting.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/joint/predict.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace dim = core::dim;

namespace {

struct AnalyzeOptions {
  std::vector<std::string> files;
  std::optional<std::string> P, model, out;
  double window = 0.3;
  bool stiffness_from_delta = false;
  bool json = false;
  bool no_plots = false;
};

Json cycle_json(const joint::CycleMetrics& c) {
  return Json{{"t_start", c.t_start},
              {"t_end", c.t_end},
              {"energy", c.energy},
              {"Q_max", c.Q_max},
              {"delta_max", c.delta_max},
              {"stiffness", c.stiffness},
              {"stiffness_unloading", c.stiffness_unloading},
              {"stiffness_reloading", c.stiffness_reloading},
              {"sliding", c.sliding},
              {"partial_slip", c.partial_slip},
              {"Q_center", c.Q_center},
              {"delta_center", c.delta_center}};
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

Json run_json(const Run& r, double window) {
  Json j;
  j["file"] = r.file;
  j["P"] = r.a.P;
  j["cycles"] = r.a.cycles.size();
  Json pc = Json::array();
  for (const auto& c : r.a.cycles) pc.push_back(cycle_json(c));
  j["per_cycle"] = pc;
  j["mean"] = cycle_json(r.a.mean);
  j["mu"] = r.a.mu;
  j["averaged_loop"] = Json{{"energy", r.a.loop_energy}, {"points", r.a.loop_delta.size()}};
  if (r.a.stiffness_from_imposed) {
    j["apparatus"] = Json{{"compliance", r.a.apparatus_compliance},
                          {"residual_rms", r.a.apparatus_residual_rms}};
  }
  j["method"] = Json{
      {"cycles",
       "maximum -> minimum -> maximum of the displacement (moving average over 1/50 cycle); "
       "ramps of Eq. 5.3 left out"},
      {"energy", "trapezoidal loop area of the cycle (smoothed signals), closed"},
      {"stiffness",
       r.a.stiffness_from_imposed
           ? fmt::format(
                 "apparatus compliance c from Delta - delta = c Q + const over all samples; "
                 "least-squares Q(Delta) over the samples after each reversal until |Q - Q_r| "
                 "= {} x the cycle's peak-to-peak force (per cycle: quadratic; mean: cubic "
                 "pooled over all reversals, one intercept each); stiffness = 1/(dDelta/dQ - c) "
                 "at the reversal",
                 window)
           : fmt::format(
                 "least-squares delta(Q) over the samples after each reversal until |Q - Q_r| "
                 "= {} x the cycle's peak-to-peak force (per cycle: quadratic; mean: cubic "
                 "pooled over all reversals, one intercept each); slope dQ/ddelta at the "
                 "reversal",
                 window)},
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
  for (std::size_t i = 0; i < a.cycles.size(); ++i) {
    const auto& c = a.cycles[i];
    s += fmt::format("{:>6} {:>12.5g} {:>10.4g} {:>14.4g} {:>12.4g} {:>12.4g} {:>12.4g}\n", i + 1,
                     c.energy * 1e6, c.Q_max, c.delta_max * 1e6, c.stiffness * 1e-6,
                     c.sliding * 1e6, c.partial_slip * 1e6);
  }
  const auto& c = a.mean;
  s += fmt::format("{:>6} {:>12.5g} {:>10.4g} {:>14.4g} {:>12.4g} {:>12.4g} {:>12.4g}\n", "mean",
                   c.energy * 1e6, c.Q_max, c.delta_max * 1e6, c.stiffness * 1e-6, c.sliding * 1e6,
                   c.partial_slip * 1e6);
  s += fmt::format("mu = Q_max/P = {:.4f} (Eq. 6.1); averaged loop energy {:.5g} uJ\n", a.mu,
                   a.loop_energy * 1e6);
  if (a.stiffness_from_imposed) {
    s += fmt::format(
        "stiffness from Q(Delta) and the apparatus compliance {:.5g} um/N ({:.4g} N/um; fit "
        "residual "
        "{:.3g} um rms)\n",
        a.apparatus_compliance * 1e6, 1e-6 / a.apparatus_compliance,
        a.apparatus_residual_rms * 1e6);
  }
  if (r.model) {
    const auto& m = *r.model;
    const auto& amp = m.amplitudes.front();
    s += fmt::format(
        "model at delta_max = {:.4g} um: Q_peak {:.4g} N ({:+.1f} %), energy {:.5g} uJ ({:+.1f} "
        "%), "
        "stiffness {:.4g} N/um ({:+.1f} %), mu {:.4f} ({:+.1f} %)\n",
        amp.delta_max * 1e6, amp.Q_peak, 100 * rel_diff(a.mean.Q_max, amp.Q_peak), amp.energy * 1e6,
        100 * rel_diff(a.mean.energy, amp.energy), m.stiffness * 1e-6,
        100 * rel_diff(a.mean.stiffness, m.stiffness), amp.Q_peak / m.preload,
        100 * rel_diff(a.mu, amp.Q_peak / m.preload));
  }
  return s;
}

}  // namespace

void add_analyze_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<AnalyzeOptions>();
  auto* cmd = app.add_subcommand(
      "analyze",
      "Measured fretting data (CSV columns t, delta, Q with units in the header, optionally the "
      "imposed Delta): cycles, energy per cycle, stiffness at reversals, peak force, mu = Q_max/P "
      "(Eq. 6.1), slip displacements (Fig. 6.1); several files give the energy-force power law.");
  cmd->add_option("data", o->files, "fretting data files (CSV)")->required();
  cmd->add_option("--P", o->P, "normal load (preload) of the runs, e.g. 526N")->required();
  cmd->add_option("--model", o->model,
                  "a case file: overlay its prediction and quantify the differences");
  cmd->add_option("--out", o->out,
                  "write analysis.json, cycles.csv, averaged_loop.csv and plots into DIR");
  cmd->add_option("--window", o->window,
                  "stiffness fit window, fraction of the peak-to-peak force (0.3)");
  cmd->add_flag("--stiffness-from-delta", o->stiffness_from_delta,
                "fit the stiffness on the measured delta even when the imposed Delta is given "
                "(default with Delta: Q(Delta) and the fitted apparatus compliance)");
  cmd->add_flag("--json", o->json, "print JSON instead of tables");
  cmd->add_flag("--no-plots", o->no_plots, "do not draw PNG plots");
  cmd->callback([o, &action] {
    action = [o] {
      return run_guarded([o](std::string& out) {
        const double P = required_quantity(o->P, dim::force, "--P");
        if (!(P > 0.0)) throw InvalidInput(fmt::format("--P = {}: must be > 0", *o->P));
        if (!(o->window > 0.0 && o->window <= 0.5)) {
          throw InvalidInput(fmt::format("--window = {}: must be in (0, 0.5]", o->window));
        }
        std::optional<surface::RoughFlat> flat;
        if (o->model) flat = joint::read_case_file(*o->model).rough_flat();
        std::vector<Run> runs;
        for (const auto& f : o->files) {
          Run r;
          r.file = f;
          r.data = joint::read_fretting_csv(f);
          r.a = joint::analyze_fretting(
              r.data, P,
              {.stiffness_window = o->window, .stiffness_from_imposed = !o->stiffness_from_delta});
          if (flat) r.model = joint::predict_load(*flat, P, {r.a.mean.delta_max});
          runs.push_back(std::move(r));
        }
        std::optional<double> exponent;
        if (runs.size() >= 2) {
          std::vector<double> q, e;
          for (const auto& r : runs) {
            q.push_back(r.a.mean.Q_max);
            e.push_back(r.a.mean.energy);
          }
          exponent = joint::power_law_exponent(q, e);
        }
        Json j;
        if (runs.size() == 1) {
          j = run_json(runs.front(), o->window);
        } else {
          Json rs = Json::array();
          for (const auto& r : runs) rs.push_back(run_json(r, o->window));
          j["runs"] = rs;
          j["power_law_exponent"] = *exponent;
        }
        if (o->out) {
          joint::StagedDirectory dir(*o->out);
          write_file_atomically(dir.file("analysis.json"), j.dump(2) + "\n");
          std::vector<std::vector<double>> cc(8), lc(4);
          for (std::size_t k = 0; k < runs.size(); ++k) {
            for (std::size_t i = 0; i < runs[k].a.cycles.size(); ++i) {
              const auto& c = runs[k].a.cycles[i];
              for (auto [col, v] :
                   std::vector<std::pair<std::size_t, double>>{{0, double(k + 1)},
                                                               {1, double(i + 1)},
                                                               {2, c.energy},
                                                               {3, c.Q_max},
                                                               {4, c.delta_max * 1e6},
                                                               {5, c.stiffness * 1e-6},
                                                               {6, c.sliding * 1e6},
                                                               {7, c.partial_slip * 1e6}}) {
                cc[col].push_back(v);
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
          core::write_csv_table(dir.file("cycles.csv"),
                                {"run", "cycle", "energy[J]", "Q_max[N]", "delta_max[um]",
                                 "stiffness[N/um]", "sliding[um]", "partial_slip[um]"},
                                cc);
          core::write_csv_table(dir.file("averaged_loop.csv"),
                                {"run", "index", "delta[um]", "Q[N]"}, lc);
          if (!o->no_plots) {
            PlotSpec loops{"Averaged fretting loops", "delta [um]", "Q [N]", false, false, {}, ""};
            for (const auto& r : runs) {
              Series s{fmt::format("{} (measured)", r.file), {}, r.a.loop_Q, "lines"};
              for (double x : r.a.loop_delta) s.x.push_back(x * 1e6);
              s.x.push_back(s.x.front());
              s.y.push_back(s.y.front());
              loops.series.push_back(s);
              if (r.model) {
                auto [x, Q] = joint::steady_loop(*r.model->backbone, r.a.mean.delta_max, 100);
                Series m{"model", {}, {}, "lines dt 2"};
                for (std::size_t i = 0; i < x.size(); ++i) {
                  m.x.push_back((x[i] + r.a.mean.delta_center) * 1e6);
                  m.y.push_back(Q[i] + r.a.mean.Q_center);
                }
                loops.series.push_back(m);
              }
            }
            plot_png(dir.file("loops.png"), loops);
            if (runs.size() >= 2) {
              Series pts{
                  fmt::format("runs (exponent {:.2f})", *exponent), {}, {}, "points pt 7 ps 1.5"};
              for (const auto& r : runs) {
                pts.x.push_back(r.a.mean.Q_max);
                pts.y.push_back(r.a.mean.energy);
              }
              plot_png(dir.file("energy_vs_force.png"), {"Energy per cycle against peak force",
                                                         "Q_max [N]",
                                                         "energy per cycle [J]",
                                                         true,
                                                         true,
                                                         {pts},
                                                         ""});
            }
          }
          dir.commit();
        }
        if (o->json) {
          out = j.dump(2) + "\n";
        } else {
          for (const auto& r : runs) out += run_text(r) + "\n";
          if (exponent)
            out +=
                fmt::format("energy ~ Q_max^n over {} runs: n = {:.3f}\n", runs.size(), *exponent);
        }
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
  cmd->add_option("--preload", o->preload, "preload (default: the case's first load case)");
  cmd->add_option("--cycles", o->cycles, "harmonic cycles (10)");
  cmd->add_option("--frequency", o->frequency, "frequency f of Eq. 5.3 (1Hz)");
  cmd->add_option("--rate", o->rate, "sample rate (1000Hz)");
  cmd->add_option("--noise-delta", o->noise_delta, "rms noise of the displacement sensor (0.1um)");
  cmd->add_option("--noise-Q", o->noise_Q, "rms noise of the load cell (1N)");
  cmd->add_option("--k-pzt", o->k_pzt, "stiffness of the PZT side of the apparatus (38N/um)");
  cmd->add_option("--k-lc", o->k_lc, "stiffness of the load-cell side (1462N/um)");
  cmd->add_option("--seed", o->seed, "random seed (1)");
  cmd->add_flag("--no-imposed", o->no_imposed, "leave out the Delta column");
  cmd->add_option("--out", o->out, "output CSV file")->required();
  cmd->callback([o, &action] {
    action = [o] {
      return run_guarded([o](std::string& out) {
        const auto c = joint::read_case_file(o->case_file);
        const double P = o->preload ? required_quantity(o->preload, dim::force, "--preload")
                                    : c.preloads.front();
        if (o->cycles < 1) throw InvalidInput("--cycles must be >= 1");
        joint::SyntheticOptions s;
        s.excitation.amplitude = required_quantity(o->imposed, dim::length, "--imposed");
        s.excitation.frequency = required_quantity(o->frequency, dim::frequency, "--frequency");
        s.excitation.cycles = o->cycles;
        s.sample_rate = required_quantity(o->rate, dim::frequency, "--rate");
        s.noise_delta = required_quantity(o->noise_delta, dim::length, "--noise-delta");
        s.noise_Q = required_quantity(o->noise_Q, dim::force, "--noise-Q");
        s.pzt_stiffness = required_quantity(o->k_pzt, dim::stiffness, "--k-pzt");
        s.load_cell_stiffness = required_quantity(o->k_lc, dim::stiffness, "--k-lc");
        s.seed = o->seed;
        const auto lp = joint::predict_load(c.rough_flat(), P, {});
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
        core::write_csv_table(o->out, header, cols);
        out =
            fmt::format("wrote {} ({} samples; P = {:.4g} N, mu = {:.4f}, stiffness {:.4g} N/um)\n",
                        o->out, d.t.size(), P, lp.mu, lp.stiffness * 1e-6);
      });
    };
  });
}

}  // namespace asperity::cli
