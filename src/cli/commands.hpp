#pragma once
// Registration of the subcommands of the asperity CLI. Each adds its subcommand to
// `app` and, when it is chosen, sets `action` to the function that runs it.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace asperity::cli {

void add_sphere_command(CLI::App& app, std::function<int()>& action);
void add_flat_command(CLI::App& app, std::function<int()>& action);
void add_roughness_command(CLI::App& app, std::function<int()>& action);
void add_dynamics_command(CLI::App& app, std::function<int()>& action);
void add_vibration_command(CLI::App& app, std::function<int()>& action);
void add_structure_command(CLI::App& app, std::function<int()>& action);
void add_predict_command(CLI::App& app, std::function<int()>& action);
void add_analyze_command(CLI::App& app, std::function<int()>& action);
void add_synthesize_command(CLI::App& app, std::function<int()>& action);
void add_validate_command(CLI::App& app, std::function<int()>& action);
void add_sweep_command(CLI::App& app, std::function<int()>& action);
/// `asperity sweep ARGS...`: runs `python -m asperity.sweep ARGS...` (sweep_command.cpp)
/// and returns its exit status; 2 when no interpreter has the package.
int run_sweep(const std::vector<std::string>& args);

}  // namespace asperity::cli

namespace asperity::joint {
struct JointCase;
struct JointPrediction;
struct NamedInput;
class StagedDirectory;
}  // namespace asperity::joint

namespace asperity::cli {

struct PlotSpec;

/// Adds the slope-2 and slope-3 guides of Fig. 6.12-6.14 (energy ~ Q^2, Q^3) through
/// (q0, e0) over [qmin, qmax] to a log-log energy-force plot (predict, analyze, validate).
void add_power_guides(PlotSpec& spec, double q0, double e0, double qmin, double qmax);

/// Log-log ranges of an energy-force plot spanning the data ([qmin, qmax] x [emin, emax],
/// a factor 1.25 in force and 2 in energy beyond), with force ticks at 1, 2, 5 x 10^k as
/// plain numbers (the data span about a decade, where decade ticks leave one label).
void set_energy_force_ranges(PlotSpec& spec, double qmin, double qmax, double emin, double emax);

/// predict's output files (summary.json, loops.csv, energy.csv with `data`; the PNG plots
/// with `plots`), each name prefixed with `prefix`; shared with validate. Returns the
/// names of the files written (no loops or energies without amplitudes).
std::vector<std::string> write_prediction_files(const joint::JointCase& c,
                                                const joint::JointPrediction& p,
                                                joint::StagedDirectory& dir, bool plots, bool data,
                                                const std::string& prefix);

/// The profile files a case reads (its halves' scans), as inputs an --out directory must
/// not hold (predict, analyze --model).
std::vector<joint::NamedInput> profile_inputs(const joint::JointCase& c);

}  // namespace asperity::cli
