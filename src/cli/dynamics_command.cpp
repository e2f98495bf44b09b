// asperity dynamics: the single-DOF base-excited system of thesis chapter 7 with a
// friction model, from a TOML case file (format: asperity/dynamics/case.hpp, which
// also parses, runs and summarises the case; this file writes the outputs and plots).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

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
  bool json = false;
};

Json to_json(const SummaryValue& v) {
  return std::visit(
      [](const auto& x) -> Json {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::nullptr_t>) {
          return Json(nullptr);
        } else if constexpr (std::is_same_v<T, SummaryArray>) {
          Json a = Json::array();
          for (const auto& e : x) a.push_back(to_json(e));
          return a;
        } else if constexpr (std::is_same_v<T, SummaryObject>) {
          Json o = Json::object();
          for (const auto& [k, e] : x) o[k] = to_json(e);
          return o;
        } else {
          return Json(x);
        }
      },
      v.data);
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
    const auto name = std::filesystem::path(*o.out_dir).lexically_normal().filename().string();
    if (o.out_dir->empty() || name == "." || name == ".." || name.empty()) {
      throw InvalidInput(fmt::format(
          "--out \"{}\": name a directory to create (or replace whole), not . or ..", *o.out_dir));
    }
    joint::require_output_apart_from_inputs(*o.out_dir, {{"the case file", o.case_file}});
    joint::require_replaceable_output(*o.out_dir, *o.out_dir);
  }
  const DynamicsCase c = read_case_file(o.case_file);
  const CaseResult r = run_case(c);
  const Trajectory& tr = r.trajectory;
  std::vector<std::string> plots;

  // Everything goes into a temporary sibling renamed to --out at the end: the directory
  // is written whole or not at all.
  std::optional<joint::StagedDirectory> staged;
  if (files) staged.emplace(*o.out_dir);
  if (files) {
    auto& dir = *staged;
    {
      const auto cols = time_history_columns(c, tr);
      std::string csv;
      for (std::size_t i = 0; i < cols.size(); ++i) csv += (i ? "," : "") + cols[i].name;
      csv += '\n';
      csv.reserve(tr.size() * 20 * cols.size());
      for (std::size_t k = 0; k < tr.size(); ++k) {
        for (std::size_t i = 0; i < cols.size(); ++i) {
          if (i) csv += ',';
          if (cols[i].name == "event") {
            csv += cols[i].values[k] != 0.0 ? '1' : '0';
          } else {
            csv += fmt::format("{:.12g}", cols[i].values[k]);
          }
        }
        csv += '\n';
      }
      write_file_atomically(dir.file("timeseries.csv"), csv);
    }
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
      // Thin the series for plotting (gnuplot reads text).
      const std::size_t stride = std::max<std::size_t>(1, tr.size() / 20000);
      auto series = [&](const std::string& title, const std::vector<double>& x,
                        const std::vector<double>& y, double t_from) {
        Series s{.title = title};
        for (std::size_t i = 0; i < tr.size(); i += stride) {
          if (tr.tau[i] < t_from) continue;
          s.x.push_back(x[i]);
          s.y.push_back(y[i]);
        }
        return s;
      };
      PlotSpec resp{
          .title = "Response (Fig. 7.5 style): " + label, .xlabel = "tau", .ylabel = "u = x/A"};
      resp.series.push_back(series("mass u", tr.tau, tr.u, 0.0));
      if (c.excitation_name != "free") resp.series.push_back(series("base y", tr.tau, tr.y, 0.0));
      plot_png(dir.file("response.png"), resp);
      plots.push_back("response.png");
      // Phase portrait and friction loop: the steady part for harmonic input (Fig. 7.6-7.7).
      double from = 0.0;
      if (const auto* h = std::get_if<HarmonicExcitation>(&c.excitation)) {
        from = std::max(0.0, c.simulation.duration - c.analysis.loop_cycles / h->frequency);
      }
      PlotSpec phase{.title = "Phase portrait (Fig. 7.6a-b / 7.7a-b style): " + label,
                     .xlabel = "u",
                     .ylabel = "u'"};
      phase.series.push_back(series("mass", tr.u, tr.v, from));
      plot_png(dir.file("phase.png"), phase);
      plots.push_back("phase.png");
      if (tr.friction_model != "none") {
        PlotSpec loop{
            .title = "Friction force vs displacement (Fig. 7.6c-d / 7.7c-d style): " + label,
            .xlabel = "u",
            .ylabel = "F_s = f_s/(k A)"};
        loop.series.push_back(series("friction", tr.u, tr.friction, from));
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

  for (const auto& w : r.warnings) fmt::print(stderr, "warning: {}\n", w);
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
  cmd->callback([o, &action] {
    action = [o] { return run_guarded([o](std::string& out) { run_dynamics(*o, out); }); };
  });
}

}  // namespace asperity::cli
