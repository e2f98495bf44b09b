#include "asperity/dynamics/analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <complex>
#include <kissfft/kissfft.hh>
#include <limits>
#include <numbers>
#include <numeric>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::dynamics {

Periodogram::Periodogram(std::span<const double> x, double dt) : x_(x.begin(), x.end()), dt_(dt) {
  core::require_positive("sample interval", dt);
  if (x_.size() < 4) throw InvalidInput("a power spectrum needs at least 4 samples");
  for (double v : x_) core::require_finite("signal sample", v);
  const double mean = std::accumulate(x_.begin(), x_.end(), 0.0) / static_cast<double>(x_.size());
  for (double& v : x_) v -= mean;
}

double Periodogram::operator()(double f) const {
  // Goertzel's recurrence in double: |sum x_n e^{-i theta n}|^2 with theta = 2 pi f dt.
  const double theta = 2.0 * std::numbers::pi * f * dt_;
  const double c = 2.0 * std::cos(theta);
  double s1 = 0.0, s2 = 0.0;
  for (double v : x_) {
    const double s0 = v + c * s1 - s2;
    s2 = s1;
    s1 = s0;
  }
  const double p = s1 * s1 + s2 * s2 - c * s1 * s2;
  return std::max(p, 0.0) * dt_ * dt_;
}

namespace {

// The smallest 2^a 3^b 5^c >= n (KISS FFT is fastest for these radices).
std::size_t next_fast_size(std::size_t n) {
  for (std::size_t m = std::max<std::size_t>(n, 1);; ++m) {
    std::size_t r = m;
    for (std::size_t f : {2, 3, 5}) {
      while (r % f == 0) r /= f;
    }
    if (r == 1) return m;
  }
}

}  // namespace

Spectrum power_spectrum(const Periodogram& p, double f_min, double f_max, std::size_t min_bins) {
  core::require_non_negative("f_min", f_min);
  if (!(f_max > f_min)) throw InvalidInput("the spectrum needs f_max > f_min");
  const double dt = p.dt();
  const double nyquist = 0.5 / dt;
  if (f_max > nyquist * (1.0 + 1e-12)) {
    throw InvalidInput(fmt::format(
        "the spectrum's f_max = {:.6g} exceeds the Nyquist frequency 1/(2 dt) = {:.6g} of samples "
        "every {:.6g}: lower f_max or sample finer (output_interval)",
        f_max, nyquist, dt));
  }
  const std::size_t n = p.size();
  // Zero padding 4x; a grid spacing of at most (f_max - f_min)/(min_bins - 1).
  double need = 4.0 * static_cast<double>(n);
  if (min_bins > 1) {
    need = std::max(need, static_cast<double>(min_bins - 1) / ((f_max - f_min) * dt));
  }
  constexpr double kMaxFft = 67108864.0;  // 2^26 points (1 GiB of complex doubles)
  if (!(need <= kMaxFft)) {
    throw InvalidInput(fmt::format(
        "a spectrum with {} points in [{:.6g}, {:.6g}] from samples every {:.6g} needs an FFT of "
        "{:.3g} points (at most 2^26): ask for fewer bins or a wider range",
        min_bins, f_min, f_max, dt, need));
  }
  const std::size_t nfft = next_fast_size(static_cast<std::size_t>(std::ceil(need)));
  std::vector<std::complex<double>> in(nfft), out(nfft);
  const auto x = p.samples();
  for (std::size_t i = 0; i < n; ++i) in[i] = {x[i], 0.0};
  const kissfft<double> fft(nfft, false);
  fft.transform(in.data(), out.data());
  const double df = 1.0 / (static_cast<double>(nfft) * dt);
  Spectrum s;
  const auto k0 = static_cast<std::size_t>(std::ceil(f_min / df - 1e-9));
  const auto k1 = std::min(nfft / 2, static_cast<std::size_t>(std::floor(f_max / df + 1e-9)));
  for (std::size_t k = k0; k <= k1; ++k) {
    s.frequency.push_back(static_cast<double>(k) * df);
    s.power.push_back(std::norm(out[k]) * dt * dt);
  }
  if (s.frequency.size() < 3) {
    throw InvalidInput(
        fmt::format("the spectrum range [{:.6g}, {:.6g}] holds fewer than 3 points "
                    "of the FFT grid (spacing {:.6g})",
                    f_min, f_max, df));
  }
  return s;
}

ModalEstimate modal_estimate(const Periodogram& p, double f_min, double f_max, std::size_t bins) {
  const Spectrum s = power_spectrum(p, f_min, f_max, bins);
  const std::size_t nb = s.frequency.size();
  // The largest interior local maximum: a spectrum falling from the lower end (the
  // slow creep of a regularized Coulomb contact, a drift) is not a mode.
  std::size_t k = 0;
  for (std::size_t i = 1; i + 1 < nb; ++i) {
    if (s.power[i] >= s.power[i - 1] && s.power[i] > s.power[i + 1] &&
        (k == 0 || s.power[i] > s.power[k])) {
      k = i;
    }
  }
  if (k == 0 || !(s.power[k] > 0.0)) {
    throw NumericalError(fmt::format(
        "power spectrum: no peak between {:.6g} and {:.6g} (the response may be overdamped)", f_min,
        f_max));
  }
  const double df = s.frequency[1] - s.frequency[0];
  ModalEstimate m;
  {
    // Brent's method on the exact periodogram within one grid spacing of the grid peak.
    const auto r = boost::math::tools::brent_find_minima(
        [&](double f) { return -p(f); }, s.frequency[k - 1], s.frequency[k + 1], 50);
    m.frequency = r.first;
    m.peak_power = -r.second;
    if (m.peak_power < s.power[k]) {
      m.frequency = s.frequency[k];
      m.peak_power = s.power[k];
    }
  }
  const double half = 0.5 * m.peak_power;
  auto g = [&](double f) { return p(f) - half; };
  // Below the peak.
  std::size_t i = k;
  while (i > 0 && s.power[i] > half) --i;
  if (s.power[i] > half) {
    throw NumericalError(
        fmt::format("power spectrum: the lower half-power point of the peak at {:.6g} lies below "
                    "f_min = {:.6g}",
                    m.frequency, f_min));
  }
  m.f_low = core::find_root(g, s.frequency[i], std::min(m.frequency, s.frequency[i] + df),
                            "lower half-power point", 50);
  std::size_t j = k;
  while (j + 1 < nb && s.power[j] > half) ++j;
  if (s.power[j] > half) {
    throw NumericalError(
        fmt::format("power spectrum: the upper half-power point of the peak at {:.6g} lies above "
                    "f_max = {:.6g}",
                    m.frequency, f_max));
  }
  m.f_high = core::find_root(g, std::max(m.frequency, s.frequency[j] - df), s.frequency[j],
                             "upper half-power point", 50);
  m.damping_ratio = (m.f_high - m.f_low) / (2.0 * m.frequency);
  const double c = 1.0 - 2.0 * m.damping_ratio * m.damping_ratio;
  m.undamped_frequency =
      c > 0.0 ? m.frequency / std::sqrt(c) : std::numeric_limits<double>::quiet_NaN();
  return m;
}

std::vector<double> uniform_samples(const Trajectory& tr, double output_interval,
                                    double tau_start) {
  core::require_positive("output_interval", output_interval);
  std::vector<double> out;
  out.reserve(tr.size());
  double last = -1.0;
  for (std::size_t i = 0; i < tr.size(); ++i) {
    if (tr.tau[i] < tau_start) continue;
    const double n = tr.tau[i] / output_interval;
    const double k = std::round(n);
    // Events and the final state are recorded off the grid: skip them (once per node).
    if (std::abs(n - k) > 1e-9 * std::max(1.0, k) || k <= last) continue;
    last = k;
    out.push_back(tr.u[i]);
  }
  return out;
}

std::vector<Extremum> extrema(const Trajectory& tr, double tau_start) {
  std::vector<Extremum> out;
  const bool has_events =
      std::any_of(tr.is_event.begin(), tr.is_event.end(), [](bool b) { return b; });
  if (has_events) {
    for (std::size_t i = 0; i < tr.size(); ++i) {
      if (tr.is_event[i] && tr.tau[i] >= tau_start) out.push_back({tr.tau[i], tr.u[i]});
    }
    return out;
  }
  for (std::size_t i = 1; i < tr.size(); ++i) {
    if (tr.tau[i] < tau_start) continue;
    const double v0 = tr.v[i - 1], v1 = tr.v[i];
    if (!((v0 > 0.0 && v1 <= 0.0) || (v0 < 0.0 && v1 >= 0.0))) continue;
    if (v1 == 0.0 && i + 1 < tr.size() && (tr.v[i + 1] > 0.0) == (v0 > 0.0)) continue;
    // Crossing time by linear interpolation of v; u there by the cubic Hermite
    // interpolant of (u, v) at the two samples.
    const double t0 = tr.tau[i - 1], t1 = tr.tau[i], h = t1 - t0;
    const double s = v0 / (v0 - v1);
    const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
    const double h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
    const double u = h00 * tr.u[i - 1] + h10 * h * v0 + h01 * tr.u[i] + h11 * h * v1;
    out.push_back({t0 + s * h, u});
  }
  return out;
}

std::vector<DecayPoint> free_decay(const Trajectory& tr, double tau_start, double floor) {
  core::require_in_half_open("free-decay amplitude floor", floor, 0.0, 1.0);
  const auto e = extrema(tr, tau_start);
  std::vector<DecayPoint> out;
  double s_max = 0.0;
  for (std::size_t k = 0; k + 1 < e.size(); ++k)
    s_max = std::max(s_max, std::abs(e[k + 1].u - e[k].u));
  for (std::size_t k = 0; k + 3 < e.size(); ++k) {
    const double s0 = std::abs(e[k + 1].u - e[k].u);
    const double s2 = std::abs(e[k + 3].u - e[k + 2].u);
    if (!(s0 > 0.0 && s2 > floor * s_max)) break;
    const double d = std::log(s0 / s2);
    out.push_back(
        {.tau = e[k].tau,
         .amplitude = 0.5 * s0,
         .frequency = 1.0 / (e[k + 2].tau - e[k].tau),
         .damping_ratio = d / std::sqrt(4.0 * std::numbers::pi * std::numbers::pi + d * d)});
  }
  return out;
}

std::vector<MotionInterval> stick_slip_intervals(const Trajectory& tr, double velocity_threshold) {
  core::require_positive("stick velocity threshold", velocity_threshold);
  std::vector<MotionInterval> out;
  if (tr.size() == 0) return out;
  auto sticks = [&](std::size_t i) { return std::abs(tr.v[i]) < velocity_threshold; };
  MotionInterval cur{tr.tau[0], tr.tau[0], sticks(0)};
  for (std::size_t i = 1; i < tr.size(); ++i) {
    const bool st = sticks(i);
    if (st != cur.stick) {
      // Boundary where |v| crosses the threshold, by linear interpolation.
      const double a0 = std::abs(tr.v[i - 1]) - velocity_threshold;
      const double a1 = std::abs(tr.v[i]) - velocity_threshold;
      const double s = a0 == a1 ? 1.0 : std::clamp(a0 / (a0 - a1), 0.0, 1.0);
      const double tb = tr.tau[i - 1] + s * (tr.tau[i] - tr.tau[i - 1]);
      cur.end = tb;
      out.push_back(cur);
      cur = {tb, tb, st};
    }
  }
  cur.end = tr.tau.back();
  out.push_back(cur);
  return out;
}

LoopSummary steady_loop(const Trajectory& tr, double period, int cycles) {
  core::require_positive("period", period);
  if (cycles < 1) throw InvalidInput("steady_loop needs at least one cycle");
  if (tr.size() < 3) throw InvalidInput("steady_loop needs a recorded trajectory");
  const double t_end = tr.tau.back();
  const double t_start = t_end - cycles * period;
  if (t_start < tr.tau.front()) {
    throw InvalidInput(fmt::format("the trajectory ({:.6g}) is shorter than {} cycles of {:.6g}",
                                   t_end - tr.tau.front(), cycles, period));
  }
  LoopSummary s;
  double umin = INFINITY, umax = -INFINITY, fmin = INFINITY, fmax = -INFINITY, area = 0.0;
  double usum = 0.0, tsum = 0.0;
  std::size_t first = 0;
  while (tr.tau[first] < t_start) ++first;
  for (std::size_t i = first; i < tr.size(); ++i) {
    umin = std::min(umin, tr.u[i]);
    umax = std::max(umax, tr.u[i]);
    fmin = std::min(fmin, tr.friction[i]);
    fmax = std::max(fmax, tr.friction[i]);
    if (i > first) {
      area += 0.5 * (tr.friction[i] + tr.friction[i - 1]) * (tr.u[i] - tr.u[i - 1]);
      const double dt = tr.tau[i] - tr.tau[i - 1];
      usum += 0.5 * (tr.u[i] + tr.u[i - 1]) * dt;
      tsum += dt;
    }
  }
  s.energy_per_cycle = area / cycles;
  s.displacement_amplitude = 0.5 * (umax - umin);
  s.force_amplitude = 0.5 * (fmax - fmin);
  s.mean_displacement = tsum > 0.0 ? usum / tsum : tr.u.back();
  return s;
}

}  // namespace asperity::dynamics
