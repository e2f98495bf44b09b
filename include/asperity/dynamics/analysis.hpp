#pragma once
// Analysis of simulated time histories (thesis section 7.4): power spectrum with the
// modal frequency and half-power damping of the main peak, amplitude-dependent
// frequency and damping of a free decay (logarithmic decrement), stick and slip
// intervals of a ramp response, and the friction loop of a steady harmonic response.
//
// Frequencies are in cycles per unit of the time axis (non-dimensional tau for a
// Trajectory: the undamped natural frequency is 1/(2 pi)).
#include <span>
#include <vector>

#include "asperity/dynamics/system.hpp"

namespace asperity::dynamics {

/// Power spectrum P(f) = |dt sum_n (x_n - mean) exp(-2 pi i f t_n)|^2 of a uniformly
/// sampled signal (a periodogram with a rectangular window): the signal with its mean
/// removed, and P at any single frequency by Goertzel's recurrence (the exact
/// discrete-time Fourier transform in double precision, O(N) per frequency), which
/// modal_estimate uses to refine a peak found on the FFT grid.
class Periodogram {
 public:
  Periodogram(std::span<const double> x, double dt);
  /// P at frequency f (>= 0), by Goertzel's recurrence.
  [[nodiscard]] double operator()(double f) const;
  [[nodiscard]] double dt() const { return dt_; }
  [[nodiscard]] std::size_t size() const { return x_.size(); }
  /// The samples with the mean removed.
  [[nodiscard]] std::span<const double> samples() const { return x_; }

 private:
  std::vector<double> x_;  // mean removed
  double dt_;
};

struct Spectrum {
  std::vector<double> frequency;
  std::vector<double> power;
};

/// P on the FFT grid f_k = k/(n_fft dt) inside [f_min, f_max], by KISS FFT
/// (kissfft<double>) of the mean-removed signal zero-padded to n_fft samples. n_fft is
/// the smallest 2^a 3^b 5^c that is at least 4 N (zero padding: the main lobe of a
/// peak, 2/T wide for a record of T = N dt, spans 8 grid points) and fine enough to put
/// at least `min_bins` points in [f_min, f_max]. Each value equals operator()(f_k) up
/// to round-off. Throws InvalidInput for f_min < 0, f_max <= f_min, f_max above the
/// Nyquist frequency 1/(2 dt), or a grid of more than 2^26 points.
[[nodiscard]] Spectrum power_spectrum(const Periodogram& p, double f_min, double f_max,
                                      std::size_t min_bins = 0);

/// The main peak of a spectrum and its half-power (-3 dB) points.
struct ModalEstimate {
  double frequency = 0.0;      ///< peak frequency
  double damping_ratio = 0.0;  ///< (f_high - f_low)/(2 frequency), half-power bandwidth
  double peak_power = 0.0;
  /// The undamped natural frequency estimated from the peak of a displacement
  /// spectrum: a viscously damped oscillator's |H|^2 peaks at f_n sqrt(1 - 2 zeta^2),
  /// so f_n = frequency/sqrt(1 - 2 zeta^2) (zeta = damping_ratio; NaN if zeta >= 1/sqrt 2).
  double undamped_frequency = 0.0;
  double f_low = 0.0;   ///< half-power point below the peak
  double f_high = 0.0;  ///< half-power point above the peak
};

/// Finds the largest interior peak (a local maximum, not a range end) of
/// power_spectrum(p, f_min, f_max, bins) and refines it by Brent's method on the exact
/// periodogram (Goertzel) within one grid spacing; the half-power points are bracketed
/// on the grid and found by root finding on the exact periodogram. The refinement adds
/// accuracy: the grid alone places the peak to within half a spacing, 1/(8 T) (3e-3 of
/// the frictionless 1/(2 pi) for a 400-tau record), while the refined peak is exact to
/// ~1e-9. Throws NumericalError if there is no interior peak or a half-power point lies
/// outside [f_min, f_max] (widen the range or lengthen the record).
[[nodiscard]] ModalEstimate modal_estimate(const Periodogram& p, double f_min, double f_max,
                                           std::size_t bins = 4000);

/// The uniformly sampled displacement of a trajectory recorded with output_interval > 0
/// (events and the final state, recorded off the grid, are skipped), from tau_start on.
[[nodiscard]] std::vector<double> uniform_samples(const Trajectory& tr, double output_interval,
                                                  double tau_start = 0.0);

/// Extrema of the displacement (velocity reversals): located events when the
/// trajectory has them, otherwise sign changes of the sampled velocity refined by a
/// parabola through three samples.
struct Extremum {
  double tau;
  double u;
};
[[nodiscard]] std::vector<Extremum> extrema(const Trajectory& tr, double tau_start = 0.0);

/// One cycle of a free decay.
struct DecayPoint {
  double tau = 0.0;            ///< time of the first extremum of the cycle
  double amplitude = 0.0;      ///< half the swing between the first two extrema
  double frequency = 0.0;      ///< 1/(time between extrema k and k+2)
  double damping_ratio = 0.0;  ///< from the logarithmic decrement
};

/// Amplitude-dependent frequency and damping of a free decay by the logarithmic
/// decrement over each full cycle, using swings between successive extrema so that a
/// shifted equilibrium (a stuck friction contact) does not bias it:
///   s_k = |u_{k+1} - u_k|,  delta_k = ln(s_k / s_{k+2}),  zeta_k = delta_k/sqrt(4 pi^2 +
///   delta_k^2).
/// Exact for a linear viscously damped oscillator. Stops when a swing falls below
/// `floor` times the largest one (there the motion is at the level of the integration
/// tolerance, or the contact has stuck).
[[nodiscard]] std::vector<DecayPoint> free_decay(const Trajectory& tr, double tau_start = 0.0,
                                                 double floor = 1e-4);

/// Stick and slip intervals: the contact sticks while |v| < velocity_threshold.
struct MotionInterval {
  double begin = 0.0;
  double end = 0.0;
  bool stick = false;
};
[[nodiscard]] std::vector<MotionInterval> stick_slip_intervals(const Trajectory& tr,
                                                               double velocity_threshold);

/// The friction loop of a steady harmonic response over the last `cycles` periods.
struct LoopSummary {
  double energy_per_cycle = 0.0;        ///< closed integral of F_s du, per cycle
  double displacement_amplitude = 0.0;  ///< (max u - min u)/2
  double force_amplitude = 0.0;         ///< (max F - min F)/2
  double mean_displacement = 0.0;
};
[[nodiscard]] LoopSummary steady_loop(const Trajectory& tr, double period, int cycles = 1);

}  // namespace asperity::dynamics
