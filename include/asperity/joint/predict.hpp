#pragma once
// Predictions for a joint case (thesis ch. 5-6, Fig. 4.3): per load case the rough
// flat's separation, static friction, friction coefficient, tangential stiffness and
// backbone; per amplitude the peak force, the energy per cycle (Masing, exact) and the
// fretting regime. SI units throughout.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asperity/hysteresis/masing.hpp"
#include "asperity/hysteresis/odfalk_vingsbo.hpp"
#include "asperity/joint/case.hpp"

namespace asperity::joint {

struct AmplitudePrediction {
  double delta_max = 0.0;  ///< displacement amplitude of the joint [m]
  /// PZT tip amplitude it came from [m]; empty when the joint amplitude was given directly.
  std::optional<double> imposed;
  double Q_peak = 0.0;   ///< force at delta_max on the backbone [N]
  double energy = 0.0;   ///< energy per symmetric cycle [J]
  double Q_ratio = 0.0;  ///< Q_peak/Q_max
  /// "gross slip" when delta_max reaches LoadPrediction::gross_slip_amplitude (every
  /// asperity slips: Q_peak = Q_max to the backbone table's resolution), else "partial slip".
  std::string regime;
  /// Slip map: per patch of LoadPrediction::patches, 1 when the patch is in gross slip
  /// (delta_max reaches its own gross-slip amplitude), else 0; and the share of the loaded
  /// nominal area in gross slip.
  std::vector<std::uint8_t> patch_gross_slip;
  double gross_slip_area_fraction = 0.0;
  /// Local energy-force exponent n = d ln W / d ln Q_peak at delta_max (central
  /// difference over delta_max (1 +- 1e-3), the upper point capped at the gross-slip
  /// amplitude); empty in gross slip, where Q_peak no longer grows (and where it does not
  /// grow to rounding, within ~1e-12 of Q_max).
  std::optional<double> exponent;
};

/// One patch of the interface at one load (joint/interface.hpp): a rough flat of area
/// A_i carrying F_i.
struct PatchPrediction {
  InterfacePatch patch;
  double d_star = 0.0;                ///< its separation
  double Q_max = 0.0;                 ///< its static friction [N]
  double stiffness = 0.0;             ///< its tangential stiffness at reversals [N/m]
  double gross_slip_amplitude = 0.0;  ///< delta_max from which it is in gross slip [m]
};

struct LoadPrediction {
  double preload = 0.0;     ///< P [N]
  double torque = 0.0;      ///< bolt torque per bolt [N m], 0 when the preload was given
  double P_star = 0.0;      ///< P/(K H A0)
  double separation = 0.0;  ///< mean-plane separation d [m] (d* sigma_s)
  double d_star = 0.0;
  double Q_max = 0.0;      ///< static friction force [N] (Eq. 4.7)
  double mu = 0.0;         ///< Q_max/P
  double stiffness = 0.0;  ///< tangential stiffness at every reversal [N/m]
  /// The interface's own stiffness, and the halves' compliance in series with it [m/N]
  /// (0 without [interface.halves]): 1/stiffness = 1/interface_stiffness + compliance.
  double interface_stiffness = 0.0;
  double halves_compliance = 0.0;
  double contact_area_ratio = 0.0;  ///< real over nominal area
  double mean_pressure = 0.0;       ///< P/A0 [Pa]
  /// Amplitude from which the joint is in gross slip [m]: the end of the backbone table,
  /// beyond which Q_l equals Q_max to < 1e-12 (rough_flat.hpp).
  double gross_slip_amplitude = 0.0;
  /// Backbone in SI units (x [m], Q [N]): a ScaledBackbone over the rough flat's table (of
  /// the patches' summed backbone, surface/patched_flat.hpp, with an [interface]).
  std::shared_ptr<const hysteresis::Backbone> backbone;
  /// tangential = "odfalk_vingsbo": the parallelogram of plastic slip (Eq. 3.10) in series
  /// with `backbone`'s Masing loop (hysteresis::OdfalkVingsboHysteresis); the amplitude rows
  /// are then that law's (hysteresis::odfalk_vingsbo_cycle), `backbone` stays the elastic
  /// part. Unset: Masing on `backbone` alone.
  std::optional<hysteresis::OdfalkVingsboParameters> odfalk_vingsbo;
  /// The loaded patches (one, the whole A0, without an [interface]); patches that carry
  /// no force are left out (out of contact).
  std::vector<PatchPrediction> patches;
  /// Distinct asperity sums the backbone was built from (patches at equal pressure share one).
  std::size_t distinct_patch_sums = 1;
  std::vector<AmplitudePrediction> amplitudes;
};

struct JointPrediction {
  surface::SpectralMoments combined;
  double sigma = 0.0, eta = 0.0, R = 0.0, beta = 0.0, psi = 0.0;
  double force_scale = 0.0;  ///< K H A0 [N]
  std::vector<LoadPrediction> loads;
  /// Inputs outside the range of the thesis's laws and implausible results, one
  /// sentence each (RoughFlat::warnings, contact::hardness_warnings,
  /// surface::friction_coefficient_warning per preload).
  std::vector<std::string> warnings;
};

/// Predicts every load case of `c`. `progress(i, n)` (if given) is called after each.
[[nodiscard]] JointPrediction predict(
    const JointCase& c, const std::function<void(std::size_t, std::size_t)>& progress = {});

/// Predictions at one preload (SI) for given joint amplitudes and, through an apparatus
/// of compliance `apparatus_compliance` [m/N], for amplitudes imposed at the PZT tip;
/// the amplitudes come out sorted by delta_max.
[[nodiscard]] LoadPrediction predict_load(const surface::RoughFlat& flat, double preload,
                                          const std::vector<double>& amplitudes,
                                          const std::vector<double>& imposed = {},
                                          double apparatus_compliance = 0.0);

/// The same for an interface in patches (interface_patches): each loaded patch a rough
/// flat of area A_i at P_i, their backbones summed (surface::PatchedRoughFlatBackbone);
/// `series_compliance` [m/N] >= 0 puts the joint halves in series (halves_compliance):
/// the backbone, stiffness, amplitudes and gross-slip amplitudes are then those between
/// the measurement points, and interface_stiffness keeps the interface's own.
/// `preload` is the sum of the patches' forces. A patch beyond the model's range, or with
/// P_i/(K H A_i) below 1e-12 while carrying force, is an InvalidInput naming it.
[[nodiscard]] LoadPrediction predict_load(const surface::RoughFlat& flat, double preload,
                                          const std::vector<InterfacePatch>& patches,
                                          const std::vector<double>& amplitudes,
                                          const std::vector<double>& imposed,
                                          double apparatus_compliance,
                                          double series_compliance = 0.0);

/// The patches of case `c` at `preload` (its [interface]; minimum patch area
/// kMinAsperitiesPerPatch / eta).
[[nodiscard]] std::vector<InterfacePatch> case_patches(const JointCase& c, double preload);

/// The SI backbone of case `c` at one preload (uniform or patched as the case says): what
/// `dynamics` and other consumers of the joint's friction law use.
[[nodiscard]] LoadPrediction predict_case_load(const JointCase& c, double preload,
                                               const std::vector<double>& amplitudes = {},
                                               const std::vector<double>& imposed = {});

/// predict_case_load at the one preload of a case that must give exactly one (a joint
/// inside a dynamics or vibration case). InvalidInput messages start with `where` (the
/// case file and line, "path:12: load: "): a sweep of preloads names `consumer` ("`asperity
/// dynamics` runs"), and predict_case_load's own errors are passed on after it.
[[nodiscard]] LoadPrediction predict_single_load(const JointCase& c, const std::string& where,
                                                 const std::string& consumer);

/// The joint amplitude of a steady symmetric cycle imposed through a linear apparatus
/// (Fig. 5.7): the root of delta + c Q_l(delta) = imposed on the SI backbone (Masing: the
/// peak force of a symmetric loop is the backbone's).
[[nodiscard]] double joint_amplitude(const hysteresis::Backbone& backbone, double imposed,
                                     double apparatus_compliance);

/// The same loop for a load case: Masing on its backbone, or, with the Odfalk-Vingsbo law,
/// that law's steady loop (driven from the virgin state to delta_max first).
[[nodiscard]] std::pair<std::vector<double>, std::vector<double>> steady_loop(
    const LoadPrediction& load, double delta_max, std::size_t n = 100);

/// A steady symmetric fretting loop of amplitude delta_max on an SI backbone, from
/// (delta_max, Q_peak) down to -delta_max and back (Masing's rules), `n` points per
/// branch. Returns {delta, Q}.
[[nodiscard]] std::pair<std::vector<double>, std::vector<double>> steady_loop(
    const hysteresis::Backbone& backbone, double delta_max, std::size_t n = 100);

}  // namespace asperity::joint
