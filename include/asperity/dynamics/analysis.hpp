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
/// sampled signal (a periodogram with a rectangular window).
///
/// Computed by a direct DFT in double precision (Goertzel's recurrence) at any
/// frequency rather than with KISS FFT: Debian ships KISS FFT in single precision
/// only, and the peak and its half-power points need the spectrum between FFT bins
/// (resolution 1/T), which the direct sum gives without zero padding. Cost O(N) per
/// frequency: 4000 frequencies on 8000 samples (a 400-tau record every 0.05) take
/// ~30 ms. For very long records sample coarser (output_interval).
class Periodogram {
 public:
  Periodogram(std::span<const double> x, double dt);
  /// P at frequency f (>= 0).
  [[nodiscard]] double operator()(double f) const;
  [[nodiscard]] double dt() const { return dt_; }
  [[nodiscard]] std::size_t size() const { return x_.size(); }

 private:
  std::vector<double> x_;  // mean removed
  double dt_;
};

struct Spectrum {
  std::vector<double> frequency;
  std::vector<double> power;
};

/// P on `bins` equally spaced frequencies in [f_min, f_max].
[[nodiscard]] Spectrum power_spectrum(const Periodogram& p, double f_min, double f_max,
                                      std::size_t bins);

/// The main peak of a spectrum and its half-power (-3 dB) points.
struct ModalEstimate {
  double frequency = 0.0;      ///< peak frequency
  double damping_ratio = 0.0;  ///< (f_high - f_low)/(2 frequency), half-power bandwidth
  double peak_power = 0.0;
  double f_low = 0.0;   ///< half-power point below the peak
  double f_high = 0.0;  ///< half-power point above the peak
};

/// Finds the largest interior peak (a local maximum, not a range end) on a grid of `bins`
/// frequencies in [f_min, f_max], refines it by Brent's method on the periodogram, and locates the
/// half-power points by root finding on the periodogram (not on the grid). Throws NumericalError if
/// a half-power point lies outside [f_min, f_max] (widen the range or lengthen the record).
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
