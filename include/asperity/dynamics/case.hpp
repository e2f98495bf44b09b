#pragma once
// A dynamics case file (TOML, read by `asperity dynamics` and asperity.run_dynamics_case):
// the single-DOF system of Eq. 7.1, its excitation, friction law, integrator settings and
// analysis options; running it gives the trajectory, its spectrum and the summary that
// summary.json holds. The CLI and the Python package share this code, so both report
// the same numbers under the same names.
//
// Case file (every table optional except [dynamics]; unknown keys are errors):
//
//   [dynamics]
//   excitation = "impulse"     # impulse | ramp | harmonic | free
//   epsilon = 0.032            # c/sqrt(m k); or give mass, stiffness, damping with units
//   # mass = "10 kg"  stiffness = "1e5 N/m"  damping = "32 N*s/m"  amplitude = "1 mm"
//   duration = 300             # in tau = sqrt(k/m) t, or a time with units ("3 s")
//   [dynamics.impulse]   Omega = 31.4159 (rad per tau) or "314 rad/s"; amplitude = 1
//   [dynamics.ramp]      alpha = 1, or velocity = "1 mm/s"
//   [dynamics.harmonic]  frequency = 1 (f~ = sqrt(m/k) f), or "10 Hz"; amplitude = 1
//   [dynamics.free]      u0 = 1, v0 = 0
//   [dynamics.friction]  model = "none|coulomb|dankowicz|jenkins|iwan|physics", and
//       coulomb: F_max, k_tan; dankowicz: F_max, delta; jenkins: F_max, stiffness;
//       iwan: F_S, K_T, chi, beta (all four required); physics: memory =
//       "masing|reset_at_reversal" and backbone = "rough_flat" (the default):
//         asperity_model, E_star, G_star, H, nu, sigma, R, eta, A0, P or P_tilde
//         (= P/(k A)), mu_cfc (needs stiffness and amplitude in [dynamics]); or
//         backbone = "mindlin": F_max, slip_displacement (a two-parameter
//         Cattaneo-Mindlin-shaped stand-in, not the rough flat)
//   [dynamics.integrator] method = "dp54|bs23", rtol, atol (number or per-state array),
//                         max_step, initial_step, min_step (collapse threshold),
//                         max_steps, output_interval
//   [dynamics.analysis]  f_min, f_max, bins, stick_velocity, loop_cycles, decay_start
//
// Numbers are non-dimensional (section 7.2); strings are quantities with units and need
// the scales (mass, stiffness, amplitude) in [dynamics].
//
// Instead of [dynamics.friction] parameters, a joint described as for `asperity
// predict` gives the physics-based law: [joint], [load] with one preload (or bolts with
// one torque) and optionally [profiles], read by joint::parse_case (same keys, same
// errors with file and line); the joint's rough flat at that preload gives the SI
// backbone, seen through the scales stiffness and amplitude of [dynamics].
// [dynamics.friction] may then hold only model = "physics", backbone = "joint" and
// memory.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "asperity/dynamics/analysis.hpp"
#include "asperity/dynamics/friction_model.hpp"
#include "asperity/dynamics/system.hpp"

namespace asperity::dynamics {

/// A JSON-like value: the summary of a run, serialised by the CLI (summary.json) and
/// converted to a dict by the Python package.
struct SummaryValue;
using SummaryArray = std::vector<SummaryValue>;
using SummaryObject = std::vector<std::pair<std::string, SummaryValue>>;
struct SummaryValue {
  std::variant<std::nullptr_t, bool, std::int64_t, double, std::string, SummaryArray, SummaryObject>
      data;
  SummaryValue() : data(nullptr) {}
  SummaryValue(std::nullptr_t) : data(nullptr) {}                      // NOLINT
  SummaryValue(bool b) : data(b) {}                                    // NOLINT
  SummaryValue(double d) : data(d) {}                                  // NOLINT
  SummaryValue(std::size_t i) : data(static_cast<std::int64_t>(i)) {}  // NOLINT
  SummaryValue(int i) : data(static_cast<std::int64_t>(i)) {}          // NOLINT
  SummaryValue(std::string s) : data(std::move(s)) {}                  // NOLINT
  SummaryValue(const char* s) : data(std::string(s)) {}                // NOLINT
  SummaryValue(SummaryArray a) : data(std::move(a)) {}                 // NOLINT
  SummaryValue(SummaryObject o) : data(std::move(o)) {}                // NOLINT
  /// The value of `key` in an object (nullptr if absent or not an object).
  [[nodiscard]] const SummaryValue* find(const std::string& key) const;
};

/// The SI scales of section 7.2 given in [dynamics] (each optional).
struct CaseScales {
  std::optional<double> m;  ///< mass [kg]
  std::optional<double> k;  ///< structural stiffness [N/m]
  std::optional<double> A;  ///< displacement scale [m]
  [[nodiscard]] bool complete() const { return m && k && A; }
};

struct CaseAnalysis {
  double f_min = 0.0;  ///< 0: 2/duration
  double f_max = 0.0;  ///< 0: min(Nyquist, 10)
  std::size_t bins = 4000;
  double stick_velocity = 0.05;  ///< stick while |u'| < this fraction of the ramp's alpha
  int loop_cycles = 5;
  double decay_start = -1.0;  ///< < 0: the end of the impulse
};

struct DynamicsCase {
  std::string source;  ///< the case file (or "<string>")
  SystemParameters system;
  Excitation excitation;
  std::string excitation_name;
  std::shared_ptr<const FrictionModel> friction;
  SimulationOptions simulation;
  CaseScales scales;
  CaseAnalysis analysis;
  /// The `friction` section of the summary: the model, its parameters as used
  /// (non-dimensional, and SI when the scales allow) and, for the rough flat or a
  /// joint, the derived Q_max, mu, k_t, F~max = Q_max/(k A) and k_t/k.
  SummaryObject friction_summary;
  /// The `joint` section when the friction law comes from a [joint].
  std::optional<SummaryObject> joint;
};

/// Parses a case file's text; `source` names it in errors, `base_dir` resolves the
/// relative profile paths of a [joint]. Throws InvalidInput naming the key (and line).
[[nodiscard]] DynamicsCase parse_case_text(const std::string& text, const std::string& source,
                                           const std::string& base_dir);
/// Reads and parses a case file (base_dir: its directory).
[[nodiscard]] DynamicsCase read_case_file(const std::string& path);

struct CaseResult {
  Trajectory trajectory;
  std::optional<Spectrum> spectrum;  ///< impulse and free decays
  /// Warnings about the run's accuracy or cost (also in the summary's "warnings").
  std::vector<std::string> warnings;
  SummaryObject summary;
};

/// Integrates the case and analyses the result (spectrum and modal estimate for decays,
/// free decay, stick-slip intervals of a ramp, the steady loop of a harmonic response,
/// the energy balance). Warns when the energy balance error exceeds 100 rtol, when a
/// Dankowicz internal state overshoots |z| <= delta by more than 100 rtol, and when more
/// than 20 % of the steps are rejected over a long run (a stiff problem).
///
/// With `options.summary_only`, only the samples the summary needs are kept in the
/// result's trajectory (a harmonic response: its last loop_cycles + 1 periods; the other
/// excitations' analyses need the whole record); the summary is the same either way.
/// `options.sink` receives every sample as it is produced (SimulationOptions::sink).
struct RunOptions {
  bool summary_only = false;
  std::function<void(const TrajectorySample&)> sink;
};
[[nodiscard]] CaseResult run_case(const DynamicsCase& c, const RunOptions& options = {});

/// Steps a harmonic response takes at least: about kStepsPerPeriod per forcing period over
/// the duration (measured: examples/dynamics/harmonic_physics_smooth.toml at frequency 10,
/// 17959 steps for 600 periods). 0 for the other excitations.
inline constexpr double kStepsPerPeriod = 30.0;
[[nodiscard]] double expected_steps(const DynamicsCase& c);
/// The cost of a run before it starts: InvalidInput when expected_steps exceeds the
/// integrator's max_steps (naming both), a warning (with the expected steps and time)
/// when it exceeds 1e7, else empty. run_case calls it too.
[[nodiscard]] std::string expected_cost_warning(const DynamicsCase& c);

/// The time-history columns of a run, in the order of timeseries.csv: the
/// non-dimensional tau, u, v, y, friction, the internal states (z), the energy terms and
/// event (1 at a located reversal), then, when the scales allow, the dimensional
/// t[s] (needs m and k), x[m], xdot[m/s] (needs m, k, A), base[m] (A) and f_s[N] (k, A).
struct Column {
  std::string name;  ///< with its unit in brackets when dimensional
  std::vector<double> values;
};
[[nodiscard]] std::vector<Column> time_history_columns(const DynamicsCase& c, const Trajectory& tr);

/// The same columns one sample at a time, for streaming a run to disk: the names
/// (time_history_columns' order) and one sample's values (event as 1 or 0).
[[nodiscard]] std::vector<std::string> time_history_names(const DynamicsCase& c);
void time_history_row(const DynamicsCase& c, const TrajectorySample& x, std::vector<double>& row);

}  // namespace asperity::dynamics
