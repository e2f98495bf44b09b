// asperity: physics-based friction of bolted and clamped joints.
#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <string_view>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/parallel.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "suggest.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "asperity: friction, tangential stiffness and energy per cycle of clamped joints from "
      "materials, roughness and load (Eriten 2012), with no fitted friction coefficient."};
  app.require_subcommand(1);
  app.footer(
      "Examples (a case file for every command) and the JSON Schemas of every --json output: "
      "examples/ and docs/schema/ of the source, shipped in the Python package as "
      "asperity.data_path(\"examples\") and asperity.data_path(\"schema\") (print them: "
      "python3 -c 'import asperity; print(asperity.data_path())').");
  // The version, the git revision of the source and the build type.
  app.set_version_flag("--version", "asperity " + asperity::cli::version_text());
  std::function<int()> action;
  asperity::cli::add_sphere_command(app, action);
  asperity::cli::add_flat_command(app, action);
  asperity::cli::add_roughness_command(app, action);
  asperity::cli::add_dynamics_command(app, action);
  asperity::cli::add_vibration_command(app, action);
  asperity::cli::add_structure_command(app, action);
  asperity::cli::add_predict_command(app, action);
  asperity::cli::add_analyze_command(app, action);
  asperity::cli::add_synthesize_command(app, action);
  asperity::cli::add_validate_command(app, action);
  asperity::cli::add_sweep_command(app, action);
  // The arguments of `sweep` are the Python module's, forwarded untouched ("--" included).
  if (argc >= 2 && std::string_view(argv[1]) == "sweep")
    return asperity::cli::run_sweep({argv + 2, argv + argc});
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One prefix for every error (ours and CLI11's), with the nearest command or option
    // for a mistyped one; bad input: exit 2 like every other input error.
    std::cerr << "asperity: error: " << asperity::cli::parse_error_message(app, e, argc, argv)
              << "\n";
    return 2;
  }
  try {
    (void)asperity::core::worker_count();  // ASPERITY_THREADS checked before any work
  } catch (const asperity::InvalidInput& e) {
    std::cerr << "asperity: error: " << e.what() << "\n";
    return 2;
  }
  // A SIGINT or SIGTERM while outputs are written removes their temporaries.
  asperity::core::install_cleanup_signal_handlers();
  return action ? action() : 2;
}
