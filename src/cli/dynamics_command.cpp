// asperity dynamics: the single-DOF base-excited system of thesis chapter 7 with a
// friction model, from a TOML case file (format: asperity/dynamics/case.hpp, which
// also parses, runs and summarises the case; this file writes the outputs and plots).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <memory>
#include <optional>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/dynamics/case.hpp"
#include "asperity/joint/output_dir.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace {

using namespace asperity::dynamics;

struct DynamicsOptions {
  std::string case_file;
  std::optional<std::string> out_dir;
  bool no_plots = false;
  std::size_t decimate = 1;
  bool json = false;
};

// Thinned plot series, filled sample by sample while the run streams (gnuplot reads
// text: about 20000 points a series).
struct PlotSeries {
  std::size_t stride = 1;
  double loop_from = 0.0;  // phase portrait and friction loop: the steady part
  std::size_t k = 0;
  Series mass{.title = "mass u"}, base{.title = "base y"}, phase{.title = "mass"},
      loop{.title = "friction"};
  void add(const TrajectorySample& x) {
    if (k++ % stride != 0) return;
    mass.x.push_back(x.tau);
    mass.y.push_back(x.u);
    base.x.push_back(x.tau);
    base.y.push_back(x.y);
    if (x.tau < loop_from) return;
    phase.x.push_back(x.u);
    phase.y.push_back(x.v);
    loop.x.push_back(x.u);
    loop.y.push_back(x.friction);
  }
};

// The y range of the response plot follows the mass: an impulse or a large base motion
// would otherwise set it and draw the mass as a flat line. When the base reaches more
// than 5 times the mass's largest |u|, the range is +-1.15 max|u| and the base's title
// gives its peak (clipped).
void clip_base_to_mass(PlotSpec& spec, PlotSeries& s) {
  double u = 0.0, y = 0.0;
  for (double v : s.mass.y) u = std::max(u, std::abs(v));
  for (double v : s.base.y) y = std::max(y, std::abs(v));
  if (!(u > 0.0) || !(y > 5.0 * u)) return;
  spec.extra += fmt::format("set yrange [{:.6g}:{:.6g}]\n", -1.15 * u, 1.15 * u);
  s.base.title = fmt::format("base y (clipped, peak {:.3g})", y);
}

void run_dynamics(const DynamicsOptions& o, std::string& out) {
  const OutKind kind = out_kind(o.out_dir, ".json");
  const bool files = kind == OutKind::directory;
  if (kind == OutKind::standard_output && o.json)
    throw InvalidInput("--json and --out - both print summary.json: give one of them");
  const bool stdout_is_data = o.json || kind == OutKind::standard_output;
  if (kind == OutKind::file) {
    require_distinct_outputs({{"the case file", o.case_file}, {"--out", *o.out_dir}});
  }
  if (files) {
    require_case_output_directory(*o.out_dir, o.case_file);
  }
  const DynamicsCase c = read_case_file(o.case_file);
  // A long run says so before it starts (and one beyond max_steps is refused here).
  const std::string cost = expected_cost_warning(c);
  if (!cost.empty()) fmt::print(stderr, "warning: {}\n", cost);
  // Only what is asked for is kept: the summary's samples (run_case summary_only), the
  // time history streamed to timeseries.csv in chunks as the integration produces it
  // (every --decimate'th sample, events and the final state always), thinned plot series.
  const double dt = c.simulation.output_interval;
  const double expected_samples = dt > 0.0 ? c.simulation.duration / dt + 1.0 : 0.0;
  if (files && expected_samples / static_cast<double>(o.decimate) > 5e7) {
    throw InvalidInput(fmt::format(
        "--out: timeseries.csv would hold about {:.3g} rows (duration / output_interval / "
        "--decimate), more than the 5e7 allowed: give --decimate {} or more, or a larger "
        "output_interval",
        expected_samples / static_cast<double>(o.decimate),
        static_cast<std::size_t>(std::ceil(expected_samples / 5e7))));
  }
  PlotSeries plot_series;
  plot_series.stride = std::max<std::size_t>(1, static_cast<std::size_t>(expected_samples / 20000));
  if (const auto* h = std::get_if<HarmonicExcitation>(&c.excitation)) {
    plot_series.loop_from =
        std::max(0.0, c.simulation.duration - c.analysis.loop_cycles / h->frequency);
  }
  const bool want_plots = files && !o.no_plots;

  // Everything goes into a temporary sibling renamed to --out at the end: the directory
  // is written whole or not at all.
  std::optional<joint::StagedDirectory> staged;
  if (files) staged.emplace(*o.out_dir, "asperity dynamics");
  CaseResult r;
  if (files) {
    core::write_file_streamed(staged->file("timeseries.csv"), [&](const core::ChunkSink& sink) {
      fmt::memory_buffer buf;
      const auto names = time_history_names(c);
      for (std::size_t i = 0; i < names.size(); ++i) {
        fmt::format_to(std::back_inserter(buf), "{}{}", i ? "," : "", names[i]);
      }
      buf.push_back('\n');
      const std::size_t event_col = 5 + c.friction->internal_states() + 4;
      std::vector<double> row;
      std::size_t k = 0;
      RunOptions run{.summary_only = true};
      run.sink = [&](const TrajectorySample& x) {
        if (want_plots) plot_series.add(x);
        const bool last = x.tau >= c.simulation.duration;
        if (k++ % o.decimate != 0 && !x.is_event && !last) return;
        time_history_row(c, x, row);
        for (std::size_t i = 0; i < row.size(); ++i) {
          if (i) buf.push_back(',');
          if (i == event_col) {
            buf.push_back(row[i] != 0.0 ? '1' : '0');
          } else {
            fmt::format_to(std::back_inserter(buf), "{:.12g}", row[i]);
          }
        }
        buf.push_back('\n');
        if (buf.size() >= (std::size_t{1} << 20)) {
          sink(std::string_view(buf.data(), buf.size()));
          buf.clear();
        }
      };
      r = run_case(c, run);
      sink(std::string_view(buf.data(), buf.size()));
    });
  } else {
    r = run_case(c, {.summary_only = true});
  }
  const Trajectory& tr = r.trajectory;
  std::vector<std::string> plots;

  if (files) {
    auto& dir = *staged;
    if (r.spectrum) {
      std::string csv = "frequency,power\n";
      for (std::size_t i = 0; i < r.spectrum->frequency.size(); ++i) {
        csv += fmt::format("{:.10g},{:.10g}\n", r.spectrum->frequency[i], r.spectrum->power[i]);
      }
      write_file_atomically(dir.file("spectrum.csv"), csv);
    }
    write_file_atomically(dir.file("summary.json"), json_output(to_json(r.summary)));

    if (!o.no_plots) {
      const std::string label =
          fmt::format("{} friction, {} excitation", tr.friction_model, c.excitation_name);
      PlotSpec resp{
          .title = "Response (Fig. 7.5 style): " + label, .xlabel = "tau", .ylabel = "u = x/A"};
      if (c.excitation_name != "free") clip_base_to_mass(resp, plot_series);
      resp.series.push_back(std::move(plot_series.mass));
      if (c.excitation_name != "free") resp.series.push_back(std::move(plot_series.base));
      plot_png(dir.file("response.png"), resp);
      plots.push_back("response.png");
      // Phase portrait and friction loop: the steady part for harmonic input (Fig. 7.6-7.7).
      PlotSpec phase{.title = "Phase portrait (Fig. 7.6a-b / 7.7a-b style): " + label,
                     .xlabel = "u",
                     .ylabel = "u'"};
      phase.series.push_back(std::move(plot_series.phase));
      plot_png(dir.file("phase.png"), phase);
      plots.push_back("phase.png");
      if (tr.friction_model != "none") {
        PlotSpec loop{
            .title = "Friction force vs displacement (Fig. 7.6c-d / 7.7c-d style): " + label,
            .xlabel = "u",
            .ylabel = "F_s = f_s/(k A)"};
        loop.series.push_back(std::move(plot_series.loop));
        plot_png(dir.file("friction_loop.png"), loop);
        plots.push_back("friction_loop.png");
      }
      if (r.spectrum) {
        // Normalised by its peak (the largest value in the range), so spectra of runs
        // with different pulse amplitudes compare on one scale; half power is 0.5.
        double peak = 0.0;
        for (double p : r.spectrum->power) peak = std::max(peak, p);
        PlotSpec sp{.title = "Power spectrum of u (Fig. 7.3-7.4 style): " + label,
                    .xlabel = "frequency [cycles per unit tau]",
                    .ylabel = "power / peak power",
                    .logy = true};
        Series s{.title = tr.friction_model};
        for (std::size_t i = 0; i < r.spectrum->frequency.size(); ++i) {
          if (r.spectrum->power[i] > 0.0 && peak > 0.0) {
            s.x.push_back(r.spectrum->frequency[i]);
            s.y.push_back(r.spectrum->power[i] / peak);
          }
        }
        // A response that never moves has no power to draw on a log axis: no plot.
        if (!s.x.empty()) {
          sp.series.push_back(std::move(s));
          plot_png(dir.file("spectrum.png"), sp);
          plots.push_back("spectrum.png");
        }
      }
    }
    dir.commit();
  }

  for (const auto& w : r.warnings) {
    if (w != cost) fmt::print(stderr, "warning: {}\n", w);  // said before the run
  }
  if (stdout_is_data || kind == OutKind::file) {
    const std::string summary_json = json_output(to_json(r.summary));
    if (kind == OutKind::file) write_file_atomically(*o.out_dir, summary_json);
    if (stdout_is_data) {
      out += summary_json;
      if (kind == OutKind::file) report_written({*o.out_dir}, true, out);
      if (files) {
        std::vector<std::string> list{"summary.json", "timeseries.csv"};
        if (r.spectrum) list.emplace_back("spectrum.csv");
        for (const auto& p : plots) list.push_back(p);
        report_written_directory(*o.out_dir, list, true, out);
      }
      return;
    }
  }

  out += fmt::format(
      "{}: {} friction, {} excitation, eps = {:.4g}, {} steps ({} rejected), {} force evaluations, "
      "{} reversals\n",
      o.case_file, tr.friction_model, c.excitation_name, c.system.epsilon, tr.stats.steps,
      tr.stats.rejected_steps, tr.force_evaluations, tr.stats.events);
  const SummaryValue summary(r.summary);
  auto num = [](const SummaryValue* v) {
    return v && std::holds_alternative<double>(v->data) ? std::get<double>(v->data) : NAN;
  };
  if (const auto* f = summary.find("friction"); f && f->find("F_max_tilde") && f->find("P_N")) {
    out += fmt::format(
        "friction: P = {:.6g} N, mu = Q_max/P = {:.4g}, Q_max = {:.6g} N, tangential stiffness "
        "{:.4g} N/m (F~max = {:.4g}, k_t/k = {:.4g})\n",
        num(f->find("P_N")), num(f->find("mu")), num(f->find("Q_max_N")),
        num(f->find("k_t_N_per_m")), num(f->find("F_max_tilde")), num(f->find("k_t_over_k")));
  }
  if (const auto* mf = summary.find("modal_frequency"); mf && num(mf) == num(mf)) {
    out += fmt::format(
        "modal frequency {:.5g} at the spectral peak, {:.5g} undamped (cycles per unit tau), "
        "half-power damping {:.4g}\n",
        num(mf), num(summary.find("modal_frequency_undamped")), num(summary.find("modal_damping")));
  }
  out += fmt::format("energy balance error {:.3g} of the input work\n", tr.energy_balance_error());
  if (files) {
    std::vector<std::string> list{"summary.json", "timeseries.csv"};
    if (r.spectrum) list.emplace_back("spectrum.csv");
    for (const auto& p : plots) list.push_back(p);
    report_written_directory(*o.out_dir, list, false, out);
  } else if (kind == OutKind::file) {
    report_written({*o.out_dir}, false, out);
  } else {
    out += "no files written (--out DIR writes summary.json, the time history and plots)\n";
  }
}

}  // namespace

void add_dynamics_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<DynamicsOptions>();
  auto* cmd = app.add_subcommand(
      "dynamics",
      "Single-DOF base-excited system with friction (thesis ch. 7): impulse, ramp or harmonic "
      "base motion, with regularized Coulomb, Dankowicz, Jenkins, Iwan or physics-based friction "
      "(from rough-flat parameters, or from a [joint] and [load] as for `asperity predict`). "
      "Writes summary.json, timeseries.csv, spectrum.csv and PNG plots.");
  cmd->add_option(
         "case", o->case_file,
         "TOML case file with a [dynamics] table (and optionally [joint], [load], [profiles])")
      ->required();
  cmd->add_option("--out", o->out_dir,
                  "output directory, written whole (created; an existing one is replaced only "
                  "if asperity wrote it); a name ending in .json writes only summary.json there, "
                  "- prints it; without --out only the summary is printed");
  cmd->add_flag("--no-plots", o->no_plots, "do not draw PNG plots (no gnuplot needed)");
  cmd->add_flag("--json", o->json, "print summary.json instead of the text summary");
  cmd->add_option("--decimate", o->decimate,
                  "write every Nth sample to timeseries.csv, events and the final state "
                  "always (default: 1, every sample of output_interval)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 40));
  cmd->callback([o, &action] {
    action = [o] { return run_guarded([o](std::string& out) { run_dynamics(*o, out); }); };
  });
}

}  // namespace asperity::cli
