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
        const auto rows = joint::validation_rows();
        for (const auto& r : rows) failures += r.verdict == "FAIL";
        const auto md = joint::validation_markdown(rows);
        if (*out_dir) {
          joint::StagedDirectory dir(**out_dir, "asperity validate");
          write_file_atomically(dir.file("validation.md"), md);
          const auto c = joint::chapter5_joint();
          write_prediction_files(c, joint::predict(c), dir, true, false, "ch5_");
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
