// Synthetic fretting experiments: the excitation of Eq. 5.3 and the apparatus of Fig. 5.7
// with sensor noise.
#include "asperity/joint/fretting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "asperity/core/error.hpp"
#include "asperity/core/random.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::joint {

double Eq53Excitation::operator()(double t) const {
  const double T = 1.0 / frequency;
  const double t_ramp = 0.5 * T;
  const double t_end = t_ramp + static_cast<double>(cycles) * T;
  if (t <= 0.0) return 0.0;
  if (t <= t_ramp) return amplitude * t / t_ramp;  // A t
  if (t <= t_end) {  // 0.5 A (1 + sin 2 pi f t), phase pi at the end of the ramp
    return amplitude *
           (1.0 + std::sin(2.0 * std::numbers::pi * frequency * (t - t_ramp) + std::numbers::pi));
  }
  const double x_end =
      amplitude *
      (1.0 + std::sin(2.0 * std::numbers::pi * static_cast<double>(cycles) + std::numbers::pi));
  if (t <= t_end + t_ramp) return x_end * (1.0 - (t - t_end) / t_ramp);
  return 0.0;
}

FrettingData synthetic_experiment(std::shared_ptr<const hysteresis::Backbone> backbone,
                                  const SyntheticOptions& o) {
  if (!(o.excitation.amplitude > 0.0) || !std::isfinite(o.excitation.amplitude)) {
    throw InvalidInput(fmt::format(
        "synthetic experiment: amplitude (imposed) = {} m is not allowed: the half peak-to-peak "
        "motion of the PZT tip (0.5 A of Eq. 5.3) must be a finite number > 0",
        core::format_value(o.excitation.amplitude)));
  }
  if (o.excitation.amplitude > kMaxImposedAmplitude) {
    throw InvalidInput(fmt::format(
        "synthetic experiment: amplitude (imposed) = {} m is not allowed: at most {:g} m (1 mm), "
        "beyond the stroke of fretting PZT stacks (the thesis's 2.25-18 um, section 6.2); check "
        "the unit",
        core::format_value(o.excitation.amplitude), kMaxImposedAmplitude));
  }
  core::require_positive("synthetic experiment: frequency [Hz]", o.excitation.frequency);
  if (o.excitation.cycles < 1) {
    throw InvalidInput(fmt::format(
        "synthetic experiment: cycles = {} is not allowed: it must be a whole number >= 1",
        o.excitation.cycles));
  }
  core::require_positive("synthetic experiment: sample_rate", o.sample_rate);
  core::require_positive("synthetic experiment: pzt_stiffness", o.pzt_stiffness);
  core::require_positive("synthetic experiment: load_cell_stiffness", o.load_cell_stiffness);
  core::require_non_negative("synthetic experiment: noise_delta", o.noise_delta);
  core::require_non_negative("synthetic experiment: noise_Q", o.noise_Q);
  const double per_period = o.sample_rate / o.excitation.frequency;
  if (!(per_period >= kMinSamplesPerPeriod)) {
    throw InvalidInput(fmt::format(
        "synthetic experiment: sample_rate = {:.6g} Hz gives {:.3g} samples per period at "
        "frequency = {:.6g} Hz; at least {:.0f} are needed for the analysis to resolve the "
        "loop (sample_rate >= {:.6g} Hz)",
        o.sample_rate, per_period, o.excitation.frequency, kMinSamplesPerPeriod,
        kMinSamplesPerPeriod * o.excitation.frequency));
  }
  const double samples = std::floor(o.excitation.duration() * o.sample_rate) + 1.0;
  if (!(samples <= kMaxSyntheticSamples)) {
    throw InvalidInput(fmt::format(
        "synthetic experiment: {:.4g} samples (sample_rate = {:.6g} Hz over (cycles + 1)/frequency "
        "= {:.6g} s) exceed the limit of {:.0e}; lower the sample rate or the number of cycles",
        samples, o.sample_rate, o.excitation.duration(), kMaxSyntheticSamples));
  }
  const double compliance = 1.0 / o.pzt_stiffness + 1.0 / o.load_cell_stiffness;
  const auto n = static_cast<std::size_t>(samples);
  FrettingData d;
  d.source = "synthetic";
  d.t.resize(n);
  d.delta.resize(n);
  d.Q.resize(n);
  d.Delta.resize(n);
  hysteresis::Hysteresis h(std::move(backbone));
  double x = 0.0, D_prev = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / o.sample_rate;
    const double D = o.excitation(t);
    // Solve x + Q(x) c = D on [x, x + (D - D_prev)] (Q moves with x, so the residual is
    // monotone on the bracket) by regula falsi with the Illinois modification.
    double lo = x, hi = x + (D - D_prev);
    if (lo > hi) std::swap(lo, hi);
    const auto residual = [&](double xi) {
      auto copy = h;
      return xi + copy.update(xi) * compliance - D;
    };
    if (hi > lo) {
      double flo = residual(lo), fhi = residual(hi);
      int side = 0;
      double xm = lo;
      for (int it = 0; it < 100; ++it) {
        if (flo >= 0.0) {
          xm = lo;
          break;
        }
        if (fhi <= 0.0) {
          xm = hi;
          break;
        }
        xm = (lo * fhi - hi * flo) / (fhi - flo);
        if (!(xm > lo && xm < hi)) xm = 0.5 * (lo + hi);
        const double fm = residual(xm);
        if (std::abs(fm) <= 1e-13 * std::abs(D - D_prev) ||
            hi - lo <= 1e-15 * std::max(1e-9, std::abs(hi)))
          break;
        if (fm > 0.0) {
          hi = xm;
          fhi = fm;
          if (side == -1) flo *= 0.5;
          side = -1;
        } else {
          lo = xm;
          flo = fm;
          if (side == 1) fhi *= 0.5;
          side = 1;
        }
      }
      x = xm;
    }
    const double Q = h.update(x);
    d.t[i] = t;
    d.delta[i] = x;
    d.Q[i] = Q;
    d.Delta[i] = D;
    D_prev = D;
  }
  // The same seed gives the same noise with any standard library (core/random.hpp).
  core::StandardNormal nd(o.seed);
  for (std::size_t i = 0; i < n; ++i) {
    d.delta[i] += o.noise_delta * nd();
    d.Q[i] += o.noise_Q * nd();
  }
  return d;
}

}  // namespace asperity::joint
