// asperity validate [--out DIR]: the thesis's numbers recomputed, as a Markdown report.
#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "asperity/core/error.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/joint/validation.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace {

struct ValidateOptions {
  std::optional<std::string> out;
  bool json = false;
  bool no_plots = false;
};

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
                  "write DIR/validation.md and the chapter 5 figures (ch5_*.png) into DIR (a new "
                  "directory, or one asperity wrote before); a name ending in .md writes only "
                  "the report, - prints it");
  cmd->add_flag("--json", o->json,
                "print the rows as JSON (source, quantity, thesis, ours, relative_difference, "
                "tolerance, verdict, note) instead of Markdown");
  cmd->add_flag("--no-plots", o->no_plots,
                "do not draw the chapter 5 figures into --out DIR (no gnuplot needed)");
  cmd->callback([o, &action] {
    action = [o] {
      int failures = 0;
      const int rc = run_guarded([&](std::string& out) {
        const OutKind kind = out_kind(o->out, ".md");
        if (kind == OutKind::standard_output && o->json)
          throw InvalidInput("--json and --out - both print on standard output: give one of them");
        // Refuse a foreign --out directory before the work.
        if (kind == OutKind::directory) joint::require_replaceable_output(*o->out, *o->out);
        const auto rows = joint::validation_rows();
        for (const auto& r : rows) failures += r.verdict == "FAIL";
        const auto md = joint::validation_markdown(rows);
        // The Markdown report is the document on stdout; "wrote" goes to stderr.
        const bool stdout_is_data = true;
        out = o->json ? rows_json(rows, failures).dump(2) + "\n" : md;
        if (kind == OutKind::directory) {
          joint::StagedDirectory dir(*o->out, "asperity validate");
          write_file_atomically(dir.file("validation.md"), md);
          std::vector<std::string> written{"validation.md"};
          if (!o->no_plots) {
            const auto c = joint::chapter5_joint();
            for (const auto& f :
                 write_prediction_files(c, joint::predict(c), dir, true, false, "ch5_"))
              written.push_back(f);
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
