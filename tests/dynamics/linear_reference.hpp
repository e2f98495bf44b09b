#pragma once
// Closed-form responses of the damped oscillator u'' + eps u' + u = y + eps y'
// (Eq. 7.1 without friction, Table 7.1), the references of the frictionless tests.
#include <cmath>
#include <complex>
#include <numbers>

namespace asperity::dynamics::testing {

struct State {
  double u;
  double v;
};

/// Free response from (u0, v0) after time tau (underdamped, eps < 2).
inline State free_response(double eps, double u0, double v0, double tau) {
  const double z = 0.5 * eps;
  const double wd = std::sqrt(1.0 - z * z);
  const double C1 = u0;
  const double C2 = (v0 + z * u0) / wd;
  const double e = std::exp(-z * tau);
  const double c = std::cos(wd * tau);
  const double s = std::sin(wd * tau);
  const double u = e * (C1 * c + C2 * s);
  const double v = e * (-z * (C1 * c + C2 * s) + wd * (-C1 * s + C2 * c));
  return {u, v};
}

/// Response to y = a sin(W tau) for tau >= 0, from rest at tau = 0.
inline State harmonic_response(double eps, double a, double W, double tau) {
  const std::complex<double> H =
      std::complex<double>(1.0, eps * W) / std::complex<double>(1.0 - W * W, eps * W);
  auto particular = [&](double t) {
    return State{a * (H.real() * std::sin(W * t) + H.imag() * std::cos(W * t)),
                 a * W * (H.real() * std::cos(W * t) - H.imag() * std::sin(W * t))};
  };
  const State p0 = particular(0.0);
  const State h = free_response(eps, -p0.u, -p0.v, tau);
  const State p = particular(tau);
  return {p.u + h.u, p.v + h.v};
}

/// Response to the half-sine pulse y = a sin(W tau), 0 <= tau < pi/W, from rest.
inline State impulse_response(double eps, double a, double W, double tau) {
  const double T = std::numbers::pi / W;
  if (tau <= T) return harmonic_response(eps, a, W, tau);
  const State s = harmonic_response(eps, a, W, T);
  return free_response(eps, s.u, s.v, tau - T);
}

}  // namespace asperity::dynamics::testing
