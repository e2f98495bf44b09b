// asperity validate [--out DIR]: the thesis's numbers recomputed, as a Markdown report.
#include <fmt/format.h>

#include <iostream>

#include "asperity/core/error.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/joint/validation.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace {

// Issue 11's figures: stiffness (ch. 5 and 6) and the energy-force exponent (ch. 6)
// against preload for every model variant, with the measured ranges.
void write_variant_plots(const std::vector<joint::VariantPoint>& points,
                         joint::StagedDirectory& dir) {
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
      k.series.push_back(level("measured 10 N/um (section 5.2)", 10.0, 230.0, 725.0, "#777777"));
      k.series.push_back(level("measured 300 N/um (section 5.2)", 300.0, 230.0, 725.0, "#777777"));
    } else {
      k.series.push_back(
          level("measured steel 200-275 N/um (Fig. 6.11)", 200.0, 330.0, 722.0, "#e6a100"));
      k.series.push_back(level("", 275.0, 330.0, 722.0, "#e6a100"));
      k.series.push_back(
          level("measured Al 30-65 N/um (Fig. 6.11)", 30.0, 330.0, 722.0, "#1f4e9a"));
      k.series.push_back(level("", 65.0, 330.0, 722.0, "#1f4e9a"));
    }
    plot_png(dir.file(ch5 ? "ch5_stiffness_variants.png" : "ch6_stiffness_variants.png"), k);
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
}

}  // namespace

void add_validate_command(CLI::App& app, std::function<int()>& action) {
  auto out_dir = std::make_shared<std::optional<std::string>>();
  auto* cmd = app.add_subcommand(
      "validate",
      "Recompute the thesis's tables (3.2, 3.4, 4.1, 5.2, 5.4, 5.5, 6.2, 6.3, the ch. 5 friction "
      "coefficients, Fig. 4.4 statements; Tables 5.6 and 6.4 against the model) and print a "
      "Markdown report; exit 1 if a row that should agree does not.");
  cmd->add_option("--out", *out_dir,
                  "write DIR/validation.md and the chapter 5 figures (ch5_*.png) into DIR (a new "
                  "directory, or one asperity wrote before)");
  cmd->callback([out_dir, &action] {
    action = [out_dir] {
      int failures = 0;
      const int rc = run_guarded([&](std::string& out) {
        // Refuse a foreign --out directory before the work.
        if (*out_dir) joint::require_replaceable_output(**out_dir, **out_dir);
        std::vector<joint::VariantPoint> points;
        const auto rows = joint::validation_rows(&points);
        for (const auto& r : rows) failures += r.verdict == "FAIL";
        const auto md = joint::validation_markdown(rows);
        if (*out_dir) {
          joint::StagedDirectory dir(**out_dir, "asperity validate");
          write_file_atomically(dir.file("validation.md"), md);
          const auto c = joint::chapter5_joint();
          write_prediction_files(c, joint::predict(c), dir, true, false, "ch5_");
          write_variant_plots(points, dir);
          dir.commit();
        }
        out = md;
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
