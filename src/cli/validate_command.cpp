// asperity validate [--out DIR]: the thesis's numbers recomputed, as a Markdown report.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "asperity/core/error.hpp"
#include "asperity/fem/structure.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/joint/validation.hpp"
#include "asperity/vibration/quasi_static_fretting.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace {

struct ValidateOptions {
  std::optional<std::string> out;
  std::optional<std::string> fem;
  bool json = false;
  bool no_plots = false;
};

// Issue 11's figures: stiffness (ch. 5 and 6) and the energy-force exponent (ch. 6)
// against preload for every model variant, with the measured ranges.
std::vector<std::string> write_variant_plots(const std::vector<joint::VariantPoint>& points,
                                             joint::StagedDirectory& dir) {
  std::vector<std::string> written;
  const std::pair<const char*, const char*> joints[] = {{"ch. 5", "#000000"},
                                                        {"smooth Al", "#1f4e9a"},
                                                        {"rough Al", "#2ca02c"},
                                                        {"smooth St", "#e6a100"},
                                                        {"rough St", "#c0392b"}};
  const std::pair<const char*, int> variants[] = {
      {"uniform", 1}, {"bolt field", 2}, {"uniform + halves", 4}, {"bolt field + halves", 5}};
  const auto curve = [&](const char* joint, const char* color, const char* variant, int dash,
                         bool exponent) {
    Series s{fmt::format("{}, {}", joint, variant),
             {},
             {},
             fmt::format("linespoints pt 7 lc rgb '{}' dt {}", color, dash)};
    for (const auto& p : points) {
      if (p.joint != joint || p.variant != variant) continue;
      if (exponent && !p.exponent) continue;
      s.x.push_back(p.preload);
      s.y.push_back(exponent ? *p.exponent : p.stiffness * 1e-6);
    }
    return s;
  };
  const auto level = [](const std::string& title, double y, double x0, double x1,
                        const char* color) {
    return Series{title, {x0, x1}, {y, y}, fmt::format("lines lc rgb '{}' dt 3", color)};
  };
  for (const bool ch5 : {true, false}) {
    PlotSpec k{ch5 ? "Ch. 5 joint: tangential stiffness against preload, model variants"
                   : "Ch. 6 joints: tangential stiffness against preload, model variants",
               "preload [N]",
               "stiffness [N/um]",
               false,
               true,
               {},
               "set key below maxcols 3 font ',9'\n"};
    for (const auto& [joint, color] : joints) {
      if ((std::string(joint) == "ch. 5") != ch5) continue;
      for (const auto& [variant, dash] : variants) {
        auto s = curve(joint, color, variant, dash, false);
        if (!s.x.empty()) k.series.push_back(s);
      }
    }
    if (ch5) {
      // Down to 5 N/um: the measured 10 N/um inside the frame, not on it.
      k.extra += "set yrange [5:3000]\n";
      k.series.push_back(level("measured 10 N/um (section 5.2)", 10.0, 230.0, 725.0, "#c0392b"));
      k.series.push_back(level("measured 300 N/um (section 5.2)", 300.0, 230.0, 725.0, "#777777"));
    } else {
      k.series.push_back(
          level("measured steel 200-275 N/um (Fig. 6.11)", 200.0, 330.0, 722.0, "#e6a100"));
      k.series.push_back(level("", 275.0, 330.0, 722.0, "#e6a100"));
      k.series.push_back(
          level("measured Al 30-65 N/um (Fig. 6.11)", 30.0, 330.0, 722.0, "#1f4e9a"));
      k.series.push_back(level("", 65.0, 330.0, 722.0, "#1f4e9a"));
    }
    const std::string name = ch5 ? "ch5_stiffness_variants.png" : "ch6_stiffness_variants.png";
    plot_png(dir.file(name), k);
    written.push_back(name);
  }
  PlotSpec n{"Ch. 6 joints: energy-force exponent at PZT 2.25 um against preload",
             "preload [N]",
             "n = d ln W / d ln Q_peak",
             false,
             false,
             {},
             "set key below maxcols 3 font ',9'\nset yrange [1.5:*]\n"};
  for (const auto& [joint, color] : joints) {
    for (const auto& [variant, dash] : variants) {
      auto s = curve(joint, color, variant, dash, true);
      if (!s.x.empty()) n.series.push_back(s);
    }
  }
  n.series.push_back(level("measured range 2-3 (Fig. 6.12-6.14)", 2.0, 330.0, 722.0, "#777777"));
  n.series.push_back(level("", 3.0, 330.0, 722.0, "#777777"));
  plot_png(dir.file("ch6_exponent_vs_preload.png"), n);
  written.push_back("ch6_exponent_vs_preload.png");
  return written;
}

// --fem CASE: the chapter 5 joint with its bodies in the apparatus (a structure case with
// [fretting] at Table 5.6's four preloads and 6.75 um tip), model against measurement.
constexpr double kTable55Preloads[] = {234.0, 331.0, 526.0, 721.0};

// The case, checked for Table 5.6's setting before any work.
fem::StructureCase read_fem_case(const std::string& path) {
  fem::StructureCase c = fem::read_structure_case(path);
  const double* P = kTable55Preloads;
  const auto& f = c.fretting;
  bool preloads = f.given && f.total_preloads.size() == 4;
  for (std::size_t i = 0; preloads && i < 4; ++i)
    preloads = std::abs(f.total_preloads[i] - P[i]) <= 0.5;
  const auto tip = std::find_if(f.tip_amplitudes.begin(), f.tip_amplitudes.end(),
                                [](double a) { return std::abs(a - 6.75e-6) <= 1e-12; });
  if (!preloads || tip == f.tip_amplitudes.end() || tip - f.tip_amplitudes.begin() < 2) {
    throw InvalidInput(fmt::format(
        "--fem {}: give a structure case of the chapter 5 joint with [fretting] total_preloads = "
        "[\"234 N\", \"331 N\", \"526 N\", \"721 N\"] (Table 5.5) and tip_amplitudes with "
        "\"6.75 um\" (Table 5.6) after at least two smaller ones (the energy-force exponent), as "
        "examples/lap_joint_ch5/lap_joint_ch5.toml",
        path));
  }
  return c;
}

std::vector<joint::ValidationRow> fem_rows(const fem::StructureCase& c) {
  const std::string& path = c.path;
  const double* P = kTable55Preloads;
  const double dmax[] = {4.26, 2.69, 1.32, 0.79};  // Table 5.6 [um]
  const auto& f = c.fretting;
  const auto k6 = static_cast<std::size_t>(
      std::find_if(f.tip_amplitudes.begin(), f.tip_amplitudes.end(),
                   [](double a) { return std::abs(a - 6.75e-6) <= 1e-12; }) -
      f.tip_amplitudes.begin());
  fem::StructureOptions options;
  options.progress = [](const std::string& step) {
    fmt::print(stderr, "asperity validate --fem: {}\n", step);
    std::fflush(stderr);
  };
  const auto r = vibration::structure_fretting(c, options);
  const std::string note = fmt::format(
      "finite elements of {} in the apparatus (bodies, bolts, {} rough-contact interface "
      "elements; geometry ASSUMED, docs/structures.md); bolts tightened in the grips; "
      "drive {:.4g} N/um from the PZT tip, load cell rigid",
      path, r.interface_elements, f.fixture.drive_stiffness * 1e-6);
  std::vector<joint::ValidationRow> rows;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& run = r.runs[i];
    rows.push_back(joint::experiment_range_row(
        "Ch. 5 stiffness with the bodies (section 5.2: 10-300 N/um)",
        fmt::format("k at {:.0f} N [N/um], finite elements", P[i]), 10.0, 300.0,
        run.fretting.stiffness * 1e-6,
        note + "; stiffness of the stuck joint between its gripped ends"));
  }
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& cy = r.runs[i].fretting.cycles[k6];
    rows.push_back(joint::experiment_row(
        "Table 5.6 with the bodies",
        fmt::format("delta_max at {:.0f} N [um] (PZT 6.75 um), finite "
                    "elements",
                    P[i]),
        dmax[i], cy.displacement_amplitude * 1e6,
        note + "; delta: the driven end's displacement amplitude (the laser sensor's)"));
  }
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& cy = r.runs[i].fretting.cycles;
    if (!std::isfinite(r.runs[i].exponents[0])) {
      throw NumericalError(fmt::format(
          "--fem: the two smallest cycles at {:.0f} N give no energy-force exponent (W = {} and "
          "{} J): give tip amplitudes where the joint slips partially",
          P[i], cy[0].energy, cy[1].energy));
    }
    rows.push_back(joint::experiment_range_row(
        "Energy-force exponent with the bodies (section 5.2: 2-3)",
        fmt::format("n at {:.0f} N, tip {:.3g}-{:.3g} um (Q/Q_6.75 = {:.2f}), finite elements",
                    P[i], cy[0].tip_amplitude * 1e6, cy[1].tip_amplitude * 1e6,
                    cy[1].force_amplitude / cy[k6].force_amplitude),
        2.0, 3.0, r.runs[i].exponents[0],
        note + "; d ln W / d ln Q_0 between the two smallest tip amplitudes"));
  }
  return rows;
}

Json rows_json(const std::vector<joint::ValidationRow>& rows, int failures) {
  Json a = Json::array();
  for (const auto& r : rows) {
    a.push_back(Json{
        {"source", r.source},
        {"quantity", r.quantity},
        {"thesis", r.thesis},
        {"ours", r.ours},
        {"relative_difference",
         std::isfinite(r.relative_difference()) ? Json(r.relative_difference()) : Json(nullptr)},
        {"tolerance", r.tolerance},
        {"verdict", r.verdict},
        {"kind", r.kind()},
        {"range", r.range_high > 0.0 ? Json::array({r.range_low, r.range_high}) : Json(nullptr)},
        {"note", r.note}});
  }
  return Json{{"rows", a}, {"failures", failures}};
}

}  // namespace

void add_validate_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<ValidateOptions>();
  auto* cmd = app.add_subcommand(
      "validate",
      "Recompute the thesis's tables (3.2, 3.4, 4.1, 5.2, 5.4, 5.5, 6.2, 6.3, the ch. 5 friction "
      "coefficients, Fig. 4.4 statements; Tables 5.6 and 6.4 against the model) and print a "
      "Markdown report; exit 1 if a row that should agree does not.");
  cmd->add_option("--out", o->out,
                  "write DIR/validation.md, the chapter 5 figures (ch5_*.png) and the model "
                  "variants' stiffness and exponent plots (ch5_/ch6_*variants.png, "
                  "ch6_exponent_vs_preload.png) into DIR (a new "
                  "directory, or one asperity wrote before); a name ending in .md writes only "
                  "the report, - prints it");
  cmd->add_flag("--json", o->json,
                "print the rows as JSON (source, quantity, thesis, ours, relative_difference, "
                "tolerance, verdict, note) instead of Markdown");
  cmd->add_flag("--no-plots", o->no_plots,
                "do not draw the chapter 5 figures into --out DIR (no gnuplot needed)");
  cmd->add_option("--fem", o->fem,
                  "also the chapter 5 joint with its bodies in the fretting apparatus: a structure "
                  "case with [fretting] (examples/lap_joint_ch5/lap_joint_ch5.toml; gmsh, several "
                  "minutes): stiffness, Table 5.6's delta_max and the energy-force exponent "
                  "against the measurements, as model-vs-experiment rows");
  cmd->callback([o, &action] {
    action = [o] {
      int failures = 0;
      const int rc = run_guarded([&](std::string& out) {
        const OutKind kind = out_kind(o->out, ".md");
        if (kind == OutKind::standard_output && o->json)
          throw InvalidInput("--json and --out - both print on standard output: give one of them");
        // Refuse a foreign --out directory before the work.
        if (kind == OutKind::directory) joint::require_replaceable_output(*o->out, *o->out);
        std::optional<fem::StructureCase> fem_case;
        if (o->fem) fem_case = read_fem_case(*o->fem);
        std::vector<joint::VariantPoint> points;
        auto rows = joint::validation_rows(&points);
        if (fem_case)
          for (auto& r : fem_rows(*fem_case)) rows.push_back(std::move(r));
        for (const auto& r : rows) failures += r.verdict == "FAIL";
        const auto md = joint::validation_markdown(rows);
        // The Markdown report is the document on stdout; "wrote" goes to stderr.
        const bool stdout_is_data = true;
        out = o->json ? json_output(rows_json(rows, failures)) : md;
        if (kind == OutKind::directory) {
          joint::StagedDirectory dir(*o->out, "asperity validate");
          write_file_atomically(dir.file("validation.md"), md);
          std::vector<std::string> written{"validation.md"};
          if (!o->no_plots) {
            const auto c = joint::chapter5_joint();
            for (const auto& f :
                 write_prediction_files(c, joint::predict(c), dir, true, false, "ch5_"))
              written.push_back(f);
            for (const auto& f : write_variant_plots(points, dir)) written.push_back(f);
          }
          dir.commit();
          report_written_directory(*o->out, written, stdout_is_data, out);
        } else if (kind == OutKind::file) {
          write_file_atomically(*o->out, md);
          report_written({*o->out}, stdout_is_data, out);
        }
      });
      if (rc != 0) return rc;
      if (failures > 0) {
        std::cerr << fmt::format("asperity validate: {} row(s) FAIL\n", failures);
        return 1;
      }
      return 0;
    };
  });
}

}  // namespace asperity::cli
