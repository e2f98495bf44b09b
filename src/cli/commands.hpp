#pragma once
// Registration of the subcommands of the asperity CLI. Each adds its subcommand to
// `app` and, when it is chosen, sets `action` to the function that runs it.
#include <CLI/CLI.hpp>
#include <functional>

namespace asperity::cli {

void add_sphere_command(CLI::App& app, std::function<int()>& action);
void add_flat_command(CLI::App& app, std::function<int()>& action);
void add_roughness_command(CLI::App& app, std::function<int()>& action);
void add_dynamics_command(CLI::App& app, std::function<int()>& action);
void add_predict_command(CLI::App& app, std::function<int()>& action);
void add_analyze_command(CLI::App& app, std::function<int()>& action);
void add_synthesize_command(CLI::App& app, std::function<int()>& action);

}  // namespace asperity::cli
