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
  /// Line of each sample in the source file (filled by read_fretting_csv; empty for data
  /// built in memory, whose errors then name the sample number).
  std::vector<std::size_t> lines;
  /// Throws InvalidInput ("FILE:LINE: ...") unless the columns have equal length, every
  /// value is finite, time increases strictly and has no gap (a step over 5 times the
  /// median step).
  void validate() const;
  /// "FILE:LINE" of sample i (or "SOURCE: sample i+1").
  [[nodiscard]] std::string where(std::size_t i) const;
};

/// Reads columns t, delta, Q (and optionally Delta) with units in the header
/// ("t[s],delta[um],Q[N]").
[[nodiscard]] FrettingData read_fretting_csv(const std::string& path);

struct AnalysisOptions {
  /// Stiffness at a reversal (the slope where the loop reverses, section 6.3): a least-
  /// squares fit over the samples after each reversal until |Q - Q_r| (smoothed force)
  /// reaches this fraction of the cycle's peak-to-peak force. Every branch of a steady
  /// Masing loop has the same shape, so the fit is pooled over all reversals: an
  /// intercept per reversal, a slope per cycle and common higher-order coefficients
  /// (polynomial of `stiffness_degree` in the regressor). Per cycle the joint compliance
  /// C_i = 1/k_i follows from the slope; the mean stiffness is 1/mean(C_i) (the
  /// harmonic mean of the per-cycle values, so it lies between them when all are
  /// positive) with the standard error of that mean from the spread of C_i.
  /// Defaults (window 0.35, quadratic) chosen on synthetic experiments of the thesis's
  /// ch. 5 joint at its 1 kHz sampling (docs/joints.md: the error of the mean is 4-7 % rms
  /// there, the reported standard error covers it; 5 % needs denser sampling).
  double stiffness_window = 0.35;
  int stiffness_degree = 2;
  /// With the imposed displacement Delta in the data (noise-free: the PZT drive) the
  /// apparatus between the PZT tip and the joint is a linear spring in series (Fig.
  /// 5.7), Delta = delta + c Q + const: its compliance c is fitted to all samples, the
  /// force is fitted as a polynomial in Delta after each reversal (the regressor has no
  /// noise, so the slope is unbiased) and C = dDelta/dQ - c. The joint's displacement
  /// then enters only through c, fitted on every sample, instead of through the
  /// 0.1-0.2 um it moves inside each fit window. false: delta as a polynomial in Q
  /// (Q's 1 N noise is small against its swing), C = d delta/dQ.
  bool stiffness_from_imposed = true;
  /// Points per branch of the averaged loop.
  std::size_t loop_points = 200;
};

struct CycleMetrics {
  double t_start = 0.0, t_end = 0.0;
  /// Energy dissipated in the cycle, the closed loop integral of Q d delta (trapezoidal
  /// rule on the smoothed signals; the loop runs maximum -> minimum -> maximum, so a
  /// dissipative loop gives a positive value) [J]. Signed: with noise a cycle of a
  /// small loop can come out negative; the mean over cycles stays unbiased.
  double energy = 0.0;
  double Q_max = 0.0;      ///< half the peak-to-peak force [N]
  double delta_max = 0.0;  ///< half the peak-to-peak displacement [m]
  double Q_center = 0.0, delta_center = 0.0;
  /// Stiffness at the cycle's reversals, 1/C_i [N/m]; negative or infinite when noise
  /// swamps the joint's compliance (then stiffness_resolved is false).
  double stiffness = 0.0;
  double stiffness_unloading = 0.0, stiffness_reloading = 0.0;  ///< per reversal [N/m]
  bool stiffness_resolved = true;
  double sliding = 0.0;       ///< delta_s: half the loop's opening at Q = Q_center [m] (Fig. 6.1)
  double partial_slip = 0.0;  ///< delta_max - delta_s [m]
  /// Trace of the cycle (samples, SI), for export.
  std::size_t first_sample = 0, last_sample = 0;
};

struct FrettingAnalysis {
  double P = 0.0;
  std::vector<CycleMetrics> cycles;
  /// Mean over cycles; stiffness = 1/mean(1/k_i) (see AnalysisOptions).
  CycleMetrics mean;
  double mu = 0.0;  ///< mean Q_max / P (Eq. 6.1)
  /// Standard errors of the means [J], [N/m]: the spread of the per-cycle values over
  /// sqrt(cycles) (with one cycle: the noise floor / the fit's covariance).
  double energy_standard_error = 0.0;
  double stiffness_standard_error = 0.0;
  /// Noise of the recorded signals, estimated from the data (second differences,
  /// median absolute deviation): delta [m], Q [N].
  double noise_delta = 0.0, noise_Q = 0.0;
  /// Standard deviation that sensor noise alone gives the mean energy per cycle [J]:
  /// sqrt(noise_delta^2 Sum dQ^2 + noise_Q^2 Sum d delta^2 + N 2 noise_delta^2 noise_Q^2/w^3)
  /// / sqrt(cycles), the sums over a cycle's N increments of the signals (the smoothed
  /// ones, less the noise the w-sample moving average leaves in them). The run's energy
  /// is resolved when it exceeds 3 times this floor.
  double energy_noise_floor = 0.0;
  bool energy_resolved = true;
  /// Joint displacement over the stiffness fit window (window force span / stiffness)
  /// and the displacement noise it competes with (noise_delta; with the imposed
  /// displacement: c noise_Q, the noise of Delta - c Q) [m].
  double stiffness_window_motion = 0.0, stiffness_noise = 0.0;
  std::vector<std::string> warnings;
  std::vector<double> loop_delta, loop_Q;  ///< averaged loop (unloading then reloading branch)
  double loop_energy = 0.0;                ///< area of the averaged loop (smoothed signals) [J]
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

/// Power law energy = c Q_max^n over a set of runs: least squares in log-log.
struct PowerLawFit {
  double exponent = 0.0;
  double standard_error = 0.0;         ///< of the exponent (NaN with two runs)
  double ci_low = 0.0, ci_high = 0.0;  ///< 95 % confidence interval (Student t; NaN with two runs)
  std::size_t runs = 0;
};

/// Fits the power law. Throws InvalidInput with fewer than two runs, non-positive
/// values or runs that all have the same Q_max.
[[nodiscard]] PowerLawFit fit_power_law(const std::vector<double>& Q_max,
                                        const std::vector<double>& energy);
/// The exponent of fit_power_law.
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

/// Fewest samples per period of Eq. 5.3 a synthetic experiment takes. analyze_fretting
/// smooths over 1/50 period and fits the reversal stiffness on the samples within
/// AnalysisOptions::stiffness_window of each reversal (about 1/5 period at the default
/// 0.35), which needs degree + 3 = 5 samples: below 25 samples per period the analysis
/// cannot fit it at all, and at 25 the trapezoidal energy per cycle is already 1 % low
/// on noise-free data of the ch. 5 joint (0.26 % at 50, 0.06 % at 100). 50 keeps the
/// moving average at least one sample wide and the error of the energy below 0.3 %.
inline constexpr double kMinSamplesPerPeriod = 50.0;
/// Most samples a synthetic experiment writes: 1e7 rows are ~500 MB of CSV and ~1 GB of
/// memory while writing (4 columns of doubles plus the text), and 900 times the
/// thesis's records (11 s at 1 kHz, section 5.3); more is a typing slip, not an
/// experiment, and would exhaust the memory instead of failing clearly.
inline constexpr double kMaxSyntheticSamples = 1e7;
/// Largest PZT tip amplitude (half peak-to-peak) of a synthetic experiment [m]: 1 mm,
/// beyond the stroke of fretting PZT stacks (tens to a few hundred um; the thesis's
/// 2.25-18 um, section 6.2) and beyond fretting (gross sliding over the joint).
inline constexpr double kMaxImposedAmplitude = 1e-3;

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
/// recorded without noise (the PZT's strain gauge). Throws InvalidInput unless
/// sample_rate / frequency >= kMinSamplesPerPeriod and the record (duration x
/// sample_rate + 1 samples) holds at most kMaxSyntheticSamples.
[[nodiscard]] FrettingData synthetic_experiment(
    std::shared_ptr<const hysteresis::Backbone> backbone, const SyntheticOptions& options);

}  // namespace asperity::joint
