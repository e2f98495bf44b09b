#pragma once
// A vibration case file (TOML, read by `asperity vibration` and the Python package): a
// structure with joint elements, the harmonic-balance settings and the analyses to run
// (nonlinear mode by EPMC, forced response curves, quasi-static modal estimate). Running
// it gives the curves and the summary that summary.json holds; the CLI and Python share
// this code, so both report the same numbers under the same names.
//
// Case file (documented key by key in docs/vibration_cases.md; SI throughout; every value that has
// a dimension may instead be a quantity string with units, "2.5e7 N/m", see core/units.hpp; unknown
// keys are errors naming the key and its line):
//
//   [structure]
//   mass = [[1.0]]              # or mass_file = "M.mtx" (MatrixMarket, relative to the
//   stiffness = [[1.0]]         #    case file); same for stiffness / stiffness_file
//   damping = [[0.01]]          # or damping_file, or rayleigh = { alpha = .., beta = .. }
//                               #    (C = alpha M + beta K); none of them: C = 0
//   output_dofs = [0]           # 0-based; default: every DOF ([0] with a model)
//   # or: model = "reduced_model.mat"  a reduced model of `asperity structure` (or the
//   #    published Brake-Reuss beam layout M, K, Fv, L, Qm, Tm): M and K from it, and an
//   #    element's T may name one of its interface elements:
//   #    T = { interface_element = 12, directions = ["t1", "n"] }  (rows of Q; t1, t2, n)
//
//   [[element]]                 # any number, each acting on u = T x
//   type = "jenkins"            # rough_flat | jenkins | iwan4 | masing_table | coulomb |
//                               #   elastic_dry_friction_2d | polynomial_stiffness | cubic_damping
//                               | #   unilateral_spring
//   name = "bolt 1"             # optional
//   T = [[1.0]]                 # rows: element directions; columns: structure DOFs
//                               #    (one direction may be written as a flat list)
//     jenkins:   k_t [N/m], F_s [N]
//     coulomb:   F_s [N], k_tan [s/m]              (f = F_s tanh(k_tan v), Eq. 7.3)
//     iwan4:     F_S [N], K_T [N/m], chi, beta      (Segalman's four parameters)
//     masing_table: a backbone table under Masing's rules, from
//       table = "backbones.csv"   columns delta|x|displacement and Q|force with units in the
//                                 header (relative to the case file); with a preload
//                                 column (predict --out's backbones.csv) preload = "526 N"
//                                 chooses the rows; or
//       displacement = [...] (m) and force = [...] (N) inline.
//       Checked: through the origin, x increasing, Q non-decreasing; monotone cubic
//       interpolation, constant beyond the last point (hysteresis/table_backbone.hpp).
//     elastic_dry_friction_2d: k_t, k_n [N/m], mu, N0 [N] (optional, 0; < 0: a gap of
//                               -N0/k_n); T has 2 rows
//                               (tangential, normal)
//     polynomial_stiffness: k1 [N/m], k2 [N/m^2], k3 [N/m^3] (each optional, not all
//                               zero): f = k1 u + k2 u^2 + k3 u^3 (Duffing: k3)
//     cubic_damping: c3 [N s^3/m^3]: f = c3 v^3
//     elastic_dry_friction_3d: k_t, k_n [N/m], mu, N0 [N] as elastic_dry_friction_2d;
//                               T has 3 rows (t1, t2, normal); isotropic slider
//     unilateral_spring: k [N/m], gap [m] (optional, 0) or N0 [N] (optional, 0; a preload
//                               carried outside the model): f_c = max(N0 + k (u - gap), 0),
//                               the structure receives f_c - N0
//     rough_flat: the rough flat at one normal load, through Masing's rules, from
//       backbone = "dimensional": E_star, G_star, H, sigma, R, eta, A0, P (quantities),
//                                 nu, asperity_model (bke), mu_cfc (optional)
//       backbone = "normalized":  beta, psi, nu, G_over_E, P_star = P/(K H A0),
//                                 sigma [m] and force_scale = K H A0 [N] (the SI scales),
//                                 asperity_model, mu_cfc (optional)
//       backbone = "joint":       the case file's [joint], [load] (one preload, or bolts
//                                 with one torque) and [profiles] tables, exactly as for
//                                 `asperity predict` (joint::parse_case)
//       (backbone may be left out: "normalized" with beta, "dimensional" with E_star,
//       "joint" when the file has a [joint] table)
//
//   [harmonic_balance]
//   harmonics = [0, 1, 2, 3]    # or max = 3 (0 .. 3); must hold 1
//   time_points = 1024          # N_t per period (default 256)
//
//   [nonlinear_mode]            # EPMC of one mode
//   mode = 1
//   log10_amplitude = { from = -2.0, to = 5.0 }   # modal amplitude a [sqrt(kg) m]
//   continuation = { step, min_step, max_step, max_points, target_iterations, max_angle,
//                    max_iterations, step_tolerance, residual_tolerance }  # all optional
//
//   [[frequency_response]]      # any number
//   force_cos = [[0.0], [3.3]]  # rows: harmonics in `harmonics` order (missing rows are
//   force_sin = [[0.0], [0.0]]  #   zero); columns: DOFs [N]; harmonic 0 has no sine part
//   # with a reduced model, force_cos / force_sin may be a force at an output point instead:
//   #   force_cos = { point = "tip", direction = [0, 0, 1], force = [0, "2 N"] }
//   #   (rows: harmonics; generalised forces f d^T R_point, the recovery rows' virtual work)
//   force_per_omega_cos = ..    # optional, same layout: F_ex = force + omega force_per_omega
//   force_per_omega2_cos = ..   #   + omega^2 force_per_omega2 (and _sin): base excitation,
//                               #   e.g. y = Y sin(omega t) through k, c: force_sin = k Y,
//                               #   force_per_omega_cos = c Y [N s]
//   force_scales = [0.5, 1.0]   # optional, default [1.0]: one curve per scale
//   omega = { from = 0.2, to = 0.4 }   # rad/s as numbers, or quantity strings in Hz
//                                      # ("10 Hz", converted by 2 pi) or rad/s ("62.8 rad/s")
//   continuation = { ... }      # as above
//   stability = true            # optional (default false): Hill's stability of every
//                               #   point (stability.hpp; costly, docs/vibration.md)
//
//   [[force_response]]          # any number: continuation in the force scale at one omega
//   force_cos = [[0.0], [1.0]]  # force_sin, force_per_omega*_cos/_sin as frequency_response
//   omega = 1.6                 # the fixed frequency: rad/s, or "10 Hz", "62.8 rad/s"
//   force_scale = { from = 0.0, to = 2.0 }   # lambda, >= 0: F_ex = lambda force
//   continuation = { ... }      # as above (steps in units of the lambda range)
//
//   [[amplitude_control]]       # any number: first harmonic of `dof` held at `amplitude`
//   force_cos = [[0.0], [1.0]]  # force_sin as frequency_response; F_ex = lambda force
//   dof = 0                     # the controlled DOF
//   amplitude = "1 mm"          # its first-harmonic amplitude [m]
//   omega = { from = 0.5, to = 2.0 }   # continuation in omega
//   continuation = { ... }
//
//   [[phase_resonance]]         # any number: first harmonic of `dof` lags its force by 90 deg
//   force_cos = [[0.0], [1.0]]  # must drive `dof` (the phase reference)
//   dof = 0
//   mode = 1                    # optional: the stuck mode that starts the search
//   log10_amplitude = { from = -3.0, to = 0.0 }   # of that DOF's amplitude [m]
//   continuation = { ... }
//
//   [[superharmonic_resonance]] # any number: the r:1 resonance followed in force (VPRNM)
//   force_cos = [[0.0], [1.0]]  # as frequency_response; F_ex = lambda force
//   harmonic = 3                # r >= 2, kept in harmonic_balance
//   mode = 1                    # optional: the stuck mode; the search starts at its omega / r
//   log10_force = { from = -2.0, to = 0.0 }   # log10 lambda
//   continuation = { ... }
//
//   [[backbone_rom]]            # any number: forced responses from the [nonlinear_mode]
//   force_cos = [[0.0], [0.1]]  #   of the same case (single nonlinear mode theory,
//   force_sin = ..              #   mode_rom.hpp); layout as frequency_response, only the
//                               #   first harmonic is used
//   force_scales = [0.5, 1.0]   # optional, default [1.0]: one curve per scale
//   subdivisions = 16           # optional: points per backbone interval (1 .. 10000)
//
//   [quasi_static_mode]         # Masing-based estimate of one mode
//   mode = 1
//   amplitude = { from = 1e-3, to = 1e3 }   # modal amplitude a [sqrt(kg) m]
//   points = 60
//
// Usage (the CLI and Python):
//   const VibrationCase c = read_case_file("case.toml");   // or parse_case_text(...)
//   const VibrationResult r = run_case(c, progress);       // r.summary -> summary.json
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/dynamics/case.hpp"
#include "asperity/vibration/analysis.hpp"
#include "asperity/vibration/elements.hpp"
#include "asperity/vibration/force_response.hpp"
#include "asperity/vibration/harmonic_balance.hpp"
#include "asperity/vibration/mode_rom.hpp"
#include "asperity/vibration/response_control.hpp"
#include "asperity/vibration/structure.hpp"

namespace asperity::vibration {

using dynamics::SummaryArray;
using dynamics::SummaryObject;
using dynamics::SummaryValue;

/// One [[frequency_response]] table: the force at scale 1 as given (harmonics in the
/// order of `harmonics` x DOFs) and the options with the force in the unknowns' layout.
/// A force given at an output point (force_cos = { point, direction, force }): the
/// legends name it in N at the point, not as the norm of its generalised forces.
struct PointForceLabel {
  std::string point;       ///< "" when the force is given as rows of DOFs
  double amplitude = 0.0;  ///< [N] the norm of the given values over harmonics (cos and sin)
};

struct FrequencyResponseCase {
  Eigen::MatrixXd force_cos;
  Eigen::MatrixXd force_sin;
  FrequencyResponseOptions options;
  PointForceLabel at_point;
};

/// One [[force_response]] table: the force at scale 1 as given and the options.
struct ForceResponseCase {
  Eigen::MatrixXd force_cos;
  Eigen::MatrixXd force_sin;
  ForceResponseOptions options;
};

/// One [[backbone_rom]] table: the force at scale 1 as given and in the unknowns' layout.
struct BackboneRomCase {
  Eigen::MatrixXd force_cos;
  Eigen::MatrixXd force_sin;
  PointForceLabel at_point;
  Eigen::VectorXd force;
  std::vector<double> force_scales{1.0};
  int subdivisions = 16;
};

/// A named output point of a reduced model (an accelerometer position): its recovery rows
/// give the point's displacement (x, y, z) from the structure's DOFs.
struct OutputPoint {
  std::string name;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< [m] (NaN when the file has none)
  Eigen::MatrixXd rows;                             ///< 3 x n
};

/// First-harmonic response of an output point at each point of a curve: displacement
/// amplitude sqrt(a_1^2 + b_1^2) of x, y, z [m] and acceleration amplitude omega^2 times it
/// [m/s^2] (what an accelerometer's fundamental reads).
struct OutputPointResponse {
  std::string name;
  Eigen::MatrixXd displacement;  ///< points x 3
  Eigen::MatrixXd acceleration;  ///< points x 3
};

/// Where a placed element sits on a reduced model's interface (rough_contact elements
/// placed on every interface element): the model's element index, centroid and area.
struct ElementSite {
  Eigen::Index interface_element = -1;  ///< -1: the element is not on an interface element
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< [m]
  double area = 0.0;                                   ///< [m^2]
};

/// The interface along a curve: per point and element on the interface, the energy it
/// dissipates per cycle over its area and (rough_contact) its cycle-mean normal pressure
/// and stick/slip state.
struct InterfaceMap {
  std::vector<std::size_t> elements;  ///< indices into VibrationCase::elements
  Eigen::MatrixXd dissipation;        ///< points x elements [J/m^2 per cycle]
  Eigen::MatrixXd mean_pressure;      ///< points x elements [Pa]; NaN if not rough_contact
  /// points x elements, rough_contact only (NaN otherwise): the fraction of the period's
  /// samples in gross slip (the traction at the rough flat's static limit Q_max(p), Eq.
  /// 4.7) and out of contact (p <= 0).
  Eigen::MatrixXd slip_fraction, open_fraction;
};

struct VibrationCase {
  std::string source;  ///< the case file (or "<string>")
  Structure structure;
  std::string damping = "none";  ///< "matrix", "rayleigh" or "none"
  RayleighDamping rayleigh;      ///< when damping == "rayleigh"
  std::vector<Eigen::Index> output_dofs;
  /// The model's named output points (every one of a `model` with recovery rows).
  std::vector<OutputPoint> output_points;
  std::vector<PlacedElement> elements;
  /// One per element (interface_element -1 where it sits on none).
  std::vector<ElementSite> element_sites;
  HarmonicBalanceOptions harmonic_balance;
  std::optional<NonlinearModeOptions> nonlinear_mode;
  std::vector<FrequencyResponseCase> frequency_responses;
  std::vector<ForceResponseCase> force_responses;
  std::vector<AmplitudeControlOptions> amplitude_controls;
  std::vector<PhaseResonanceOptions> phase_resonances;
  std::vector<SuperharmonicResonanceOptions> superharmonic_resonances;
  std::vector<BackboneRomCase> backbone_roms;  ///< need nonlinear_mode
  std::optional<QuasiStaticModeOptions> quasi_static_mode;
  /// The `joint` section when a rough_flat element comes from a [joint] table.
  std::optional<SummaryObject> joint;
  /// Notes from reading the case (e.g. interface elements left out), carried into the
  /// result's warnings.
  std::vector<std::string> warnings;
};

/// Parses a case file's text; `source` names it in errors, `base_dir` resolves the
/// .mtx files and the profiles of a [joint]. Throws InvalidInput naming the key (and
/// line) and what is allowed.
[[nodiscard]] VibrationCase parse_case_text(const std::string& text, const std::string& source,
                                            const std::string& base_dir);
/// Reads and parses a case file (base_dir: its directory).
[[nodiscard]] VibrationCase read_case_file(const std::string& path);

/// Progress of a run: the analysis ("nonlinear_mode", "frequency_response",
/// "quasi_static_mode") and the fraction of its range covered, in [0, 1].
using CaseProgress = std::function<void(const std::string& analysis, double fraction)>;

struct VibrationResult {
  std::optional<NonlinearModeResult> nonlinear_mode;
  /// The output points' response along the nonlinear mode (one per case output point).
  std::vector<OutputPointResponse> nonlinear_mode_output_points;
  /// The interface along the nonlinear mode (when elements sit on interface elements).
  std::optional<InterfaceMap> nonlinear_mode_interface;
  /// Every curve of every [[frequency_response]] table, in order (tables, then scales).
  std::vector<FrequencyResponseCurve> frequency_response;
  std::vector<std::size_t> frequency_response_table;  ///< the table (0-based) of each curve
  /// Every [[force_response]] curve that ran, in order, and its table (0-based).
  std::vector<ForceResponseCurve> force_response;
  std::vector<std::size_t> force_response_table;
  /// Every [[amplitude_control]] and [[phase_resonance]] that ran, with its table.
  std::vector<AmplitudeControlResult> amplitude_control;
  std::vector<std::size_t> amplitude_control_table;
  std::vector<PhaseResonanceResult> phase_resonance;
  std::vector<std::size_t> phase_resonance_table;
  /// Every [[superharmonic_resonance]] that ran, with its table.
  std::vector<SuperharmonicResonanceResult> superharmonic_resonance;
  std::vector<std::size_t> superharmonic_resonance_table;
  /// Every [[backbone_rom]] curve (tables, then scales), its table and force scale.
  std::vector<ModeRomCurve> backbone_rom;
  std::vector<std::size_t> backbone_rom_table;
  std::vector<double> backbone_rom_force_scale;
  std::optional<QuasiStaticModeResult> quasi_static_mode;
  /// Every continuation reached its end (false: a curve stalled, hit max_points or
  /// turned back; its points are kept and `stop_reason` says why).
  bool complete = true;
  std::string stop_reason;
  /// What helps, when a continuation stopped early (empty otherwise).
  std::string remedy;
  /// Frequency response curves that could not start, each "frequency_response[k] at force
  /// scale s: reason"; the other curves are computed (complete is then false).
  std::vector<std::string> failures;
  std::vector<std::string> warnings;
  /// summary.json: case, structure, elements, harmonic_balance, joint (if any),
  /// nonlinear_mode, frequency_response, backbone_rom, quasi_static_mode, solver, warnings.
  SummaryObject summary;
};

/// Runs the analyses of the case. A frequency response curve that cannot start (its
/// first point does not converge) is named in `failures` and the others run (complete =
/// false); when nothing at all could be computed, and for a nonlinear mode that cannot
/// start or a quasi-static push without equilibrium, the case is bad input: InvalidInput
/// with what to change. A continuation that stops early is not an exception: the result
/// has complete = false and every point computed.
[[nodiscard]] VibrationResult run_case(const VibrationCase& c, const CaseProgress& progress = {});

}  // namespace asperity::vibration
