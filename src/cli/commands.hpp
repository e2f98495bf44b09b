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
void add_validate_command(CLI::App& app, std::function<int()>& action);

}  // namespace asperity::cli

namespace asperity::joint {
struct JointCase;
struct JointPrediction;
class StagedDirectory;
}  // namespace asperity::joint

namespace asperity::cli {

/// predict's output files (summary.json, loops.csv, energy.csv with `data`; the PNG plots
/// with `plots`), each name prefixed with `prefix`; shared with validate.
void write_prediction_files(const joint::JointCase& c, const joint::JointPrediction& p,
                            joint::StagedDirectory& dir, bool plots, bool data,
                            const std::string& prefix);

}  // namespace asperity::cli
