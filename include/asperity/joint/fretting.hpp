#pragma once
// Measured fretting data (thesis ch. 5-6): reading, splitting into cycles, loop
// metrics of Fig. 6.1 (energy per cycle, stiffness at reversals, peak force,
// mu = Q_max/P of Eq. 6.1, sliding and partial-slip displacement), averaged loops, the
// energy-force power law; and synthetic experiments (Eq. 5.3 excitation, the 1-DOF
// apparatus compliance of Fig. 5.7, sensor noise) with a known answer.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "asperity/hysteresis/masing.hpp"

namespace asperity::joint {

/// A fretting record: time [s], joint displacement delta [m] (the LNS), tangential
/// force Q [N] (the load cell), optionally the imposed displacement Delta [m] (PZT).
struct FrettingData {
  std::string source;
  std::vector<double> t, delta, Q, Delta;
  /// Throws InvalidInput (naming the source and the row) unless the columns have equal
  /// length, every value is finite, time increases strictly and has no gap (a step
  /// over 5 times the median step).
  void validate() const;
};

/// Reads columns t, delta, Q (and optionally Delta) with units in the header
/// ("t[s],delta[um],Q[N]").
[[nodiscard]] FrettingData read_fretting_csv(const std::string& path);

struct AnalysisOptions {
  /// Stiffness at a reversal: least-squares polynomial delta(Q) over the samples after
  /// the reversal until |Q - Q_r| reaches this fraction of the cycle's peak-to-peak
  /// force; stiffness = 1/(d delta/dQ at the reversal). Q is the regressor because its
  /// noise (1 N) is small against the force swing, while delta's (0.1 um) is not small
  /// against the displacement swing (a regression on delta would be biased low). Per
  /// cycle: a quadratic at each of its two reversals. The mean stiffness: a cubic with
  /// common coefficients pooled over every reversal (one intercept each). On
  /// noise-free Masing loops of the ch. 5 joint the cubic's bias is 0.2 % at 0.3.
  double stiffness_window = 0.3;
  /// With the imposed displacement Delta in the data (noise-free: the PZT drive) the
  /// apparatus between the PZT tip and the joint is a linear spring in series (Fig.
  /// 5.7), Delta = delta + c Q + const: its compliance c is fitted to all samples, the
  /// force is fitted as a polynomial in Delta after each reversal (the regressor has no
  /// noise, so the slope is unbiased) and stiffness = 1/(dDelta/dQ - c). The joint's
  /// displacement then enters only through c, fitted on every sample, instead of
  /// through the 0.1-0.2 um it moves inside each fit window. false: delta(Q) as above.
  bool stiffness_from_imposed = true;
  /// Points per branch of the averaged loop.
  std::size_t loop_points = 200;
};

struct CycleMetrics {
  double t_start = 0.0, t_end = 0.0;
  double energy = 0.0;     ///< loop area by the trapezoidal rule, closed [J]
  double Q_max = 0.0;      ///< half the peak-to-peak force [N]
  double delta_max = 0.0;  ///< half the peak-to-peak displacement [m]
  double Q_center = 0.0, delta_center = 0.0;
  double stiffness = 0.0;  ///< mean of the stiffness at the cycle's two reversals [N/m]
  double stiffness_unloading = 0.0, stiffness_reloading = 0.0;
  double sliding = 0.0;       ///< delta_s: half the loop's opening at Q = Q_center [m] (Fig. 6.1)
  double partial_slip = 0.0;  ///< delta_max - delta_s [m]
};

struct FrettingAnalysis {
  double P = 0.0;
  std::vector<CycleMetrics> cycles;
  CycleMetrics mean;  ///< mean over cycles; the stiffness pooled over all reversals
  double mu = 0.0;    ///< mean Q_max / P (Eq. 6.1)
  std::vector<double> loop_delta, loop_Q;  ///< averaged loop (unloading then reloading branch)
  double loop_energy = 0.0;                ///< area of the averaged loop [J]
  /// Set when the stiffness came from the imposed displacement: the fitted compliance
  /// c of Delta = delta + c Q + const [m/N] and the rms residual of that fit [m] (about
  /// the displacement noise when the apparatus is linear; much larger: it is not).
  bool stiffness_from_imposed = false;
  double apparatus_compliance = 0.0;
  double apparatus_residual_rms = 0.0;
};

/// Splits into cycles (maximum -> minimum -> maximum of the displacement, smoothed by a
/// moving average over 1/50 of a cycle; the reversal of Delta when given) and computes
/// the metrics. Throws InvalidInput with fewer than one complete cycle.
[[nodiscard]] FrettingAnalysis analyze_fretting(const FrettingData& data, double P,
                                                const AnalysisOptions& options = {});

/// Exponent n of energy = c Q_max^n over a set of runs (least squares in log-log).
/// Throws InvalidInput with fewer than two runs or non-positive values.
[[nodiscard]] double power_law_exponent(const std::vector<double>& Q_max,
                                        const std::vector<double>& energy);

/// Imposed displacement of Eq. 5.3 at time t: a ramp to `amplitude` over a half
/// period, `cycles` periods of amplitude (1 + sin 2 pi f t) from phase pi (so the
/// motion turns down at the end of the ramp), and a ramp back to zero over a half
/// period. The print's last branch A(10.5 - t) is discontinuous; we ramp from the
/// value at the end of the harmonic part down to 0 (docs/joints.md).
struct Eq53Excitation {
  double amplitude = 0.0;  ///< half the peak-to-peak motion of the harmonic part [m] (0.5 A)
  double frequency = 1.0;  ///< f [Hz]
  int cycles = 10;
  [[nodiscard]] double duration() const { return (static_cast<double>(cycles) + 1.0) / frequency; }
  [[nodiscard]] double operator()(double t) const;
};

/// 1-DOF apparatus of Fig. 5.7 and the sensors of section 5.2.
struct SyntheticOptions {
  Eq53Excitation excitation;
  double sample_rate = 1000.0;          ///< [Hz]
  double pzt_stiffness = 38e6;          ///< PZT side, A-B [N/m] (section 5.2: 38 N/um)
  double load_cell_stiffness = 1462e6;  ///< connector block + load cell [N/m] (1462 N/um)
  double noise_delta = 0.1e-6;          ///< rms noise of the LNS [m] (0.1 um)
  double noise_Q = 1.0;                 ///< rms noise of the load cell [N] (1 N)
  std::uint64_t seed = 1;
};

/// A synthetic experiment: the PZT tip follows Eq. 5.3; the joint (Masing on
/// `backbone`, SI) sits in series with the apparatus springs, so at each sample
/// Delta = delta + Q(delta) (1/k_pzt + 1/k_lc) is solved for the joint displacement
/// delta; Gaussian noise is added to the recorded delta and Q (seeded). Delta is
/// recorded without noise (the PZT's strain gauge).
[[nodiscard]] FrettingData synthetic_experiment(
    std::shared_ptr<const hysteresis::Backbone> backbone, const SyntheticOptions& options);

}  // namespace asperity::joint
