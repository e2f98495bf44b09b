// Tests of the contact elements (vibration/contact_elements.hpp): the unilateral spring's
// tangent against finite differences, its describing function (the piecewise-linear
// oscillator's) against the closed form, and the backbone of a piecewise-linear
// oscillator computed by EPMC against the first-harmonic closed form.
// g++ 12 reports Eigen's freshly allocated dynamic matrices as potential null
// dereferences when their entries are written (a known false positive at -O3).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "../support.hpp"
#include "asperity/vibration/analysis.hpp"
#include "asperity/vibration/contact_elements.hpp"
#include "asperity/vibration/harmonic_balance.hpp"
#include "element_test_support.hpp"

namespace asperity::vibration {
namespace {

constexpr double kPi = std::numbers::pi;

// Mean F0 and first cosine coefficient F1 of the force f_c - N0 of a unilateral spring,
// f_c = k max(u - g_e, 0) with g_e = gap - N0 / k, for u = a0 + a1 cos(theta): with the
// contact window |theta| < phi, cos(phi) = (g_e - a0) / a1,
//   F0 = k/pi ((a0 - g_e) phi + a1 sin phi) - N0,  F1 = k a1/pi (phi - sin phi cos phi)
// (the describing function of a piecewise-linear stiffness).
struct DescribingFunction {
  double F0 = 0.0, F1 = 0.0;
};
DescribingFunction unilateral_describing_function(const UnilateralSpringParameters& p, double a0,
                                                  double a1) {
  const double ge = p.gap - p.N0 / p.k;
  const double c = (ge - a0) / a1;
  if (c >= 1.0) return {-p.N0, 0.0};
  if (c <= -1.0) return {p.k * (a0 - ge) - p.N0, p.k * a1};
  const double phi = std::acos(c), s = std::sin(phi);
  return {p.k / kPi * ((a0 - ge) * phi + a1 * s) - p.N0, p.k * a1 / kPi * (phi - s * c)};
}

// The tangent d f / d u of the periodic and the static response against central
// differences. The force is piecewise linear in u: central differences are exact (to
// round-off, eps |f| / h ~ 1e-9 relative) unless a sample lies within h of the kink, which
// the samples below avoid by construction (their distance to the kink is checked).
TEST(VibrationUnilateralSpring, TangentMatchesFiniteDifferences) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (const UnilateralSpringParameters p :
       {UnilateralSpringParameters{.k = 3.0, .gap = 0.2},
        UnilateralSpringParameters{.k = 3.0, .N0 = 0.5}, UnilateralSpringParameters{.k = 3.0}}) {
    const auto el = make_unilateral_spring_element(p);
    const Eigen::Index N = 64;
    Eigen::MatrixXd u(N, 1);
    for (Eigen::Index i = 0; i < N; ++i) u(i, 0) = U(rng);
    const double h = 1e-7, kink = p.gap - p.N0 / p.k;
    ASSERT_GT((u.array() - kink).abs().minCoeff(), 10.0 * h);
    PeriodicResponse r;
    el->periodic_response(u, Eigen::MatrixXd(), true, r);
    EXPECT_TRUE(r.history.empty());
    std::size_t in_contact = 0;
    for (Eigen::Index i = 0; i < N; ++i) {
      Eigen::MatrixXd up = u, um = u;
      up(i, 0) += h;
      um(i, 0) -= h;
      PeriodicResponse rp, rm;
      el->periodic_response(up, Eigen::MatrixXd(), false, rp);
      el->periodic_response(um, Eigen::MatrixXd(), false, rm);
      const double fd = (rp.f(i, 0) - rm.f(i, 0)) / (2.0 * h);
      EXPECT_NEAR(r.du(i, 0), fd, 1e-6 * p.k) << "sample " << i;
      // no dependence on the other samples (memoryless)
      EXPECT_EQ((rp.f - r.f).cwiseAbs().sum(), std::abs(rp.f(i, 0) - r.f(i, 0)));
      Eigen::VectorXd f, fp, fm;
      Eigen::MatrixXd K, Kp, Km;
      el->static_response(u.row(i).transpose(), f, K);
      el->static_response(up.row(i).transpose(), fp, Kp);
      el->static_response(um.row(i).transpose(), fm, Km);
      EXPECT_EQ(f(0), r.f(i, 0));
      EXPECT_NEAR(K(0, 0), (fp(0) - fm(0)) / (2.0 * h), 1e-6 * p.k);
      if (r.du(i, 0) > 0.0) ++in_contact;
    }
    EXPECT_GT(in_contact, 0U);  // both branches visited
    EXPECT_LT(in_contact, static_cast<std::size_t>(N));
  }
}

// Rest state: zero force at u = 0 with a gap or a preload (u = 0 is the equilibrium at
// rest), the stuck stiffness k only when preloaded, -N0 in separation.
TEST(VibrationUnilateralSpring, RestStateAndSeparation) {
  Eigen::VectorXd f;
  Eigen::MatrixXd K;
  const auto gap = make_unilateral_spring_element({.k = 2.0, .gap = 0.1});
  gap->static_response(Eigen::VectorXd::Zero(1), f, K);
  EXPECT_EQ(f(0), 0.0);
  EXPECT_EQ(gap->initial_stiffness()(0, 0), 0.0);
  gap->static_response(Eigen::VectorXd::Constant(1, 0.35), f, K);
  EXPECT_DOUBLE_EQ(f(0), 2.0 * 0.25);  // k (u - g)
  const auto pre = make_unilateral_spring_element({.k = 2.0, .N0 = 0.4});
  pre->static_response(Eigen::VectorXd::Zero(1), f, K);
  EXPECT_EQ(f(0), 0.0);
  EXPECT_EQ(pre->initial_stiffness()(0, 0), 2.0);
  pre->static_response(Eigen::VectorXd::Constant(1, -0.5), f, K);  // beyond -N0/k = -0.2
  EXPECT_EQ(f(0), -0.4);
  EXPECT_EQ(K(0, 0), 0.0);
}

// The AFT force's mean and first harmonic on N samples of u = a0 + a1 cos(theta) against
// the describing function. The force has two kinks (contact opening and closing) between
// samples; by Euler-Maclaurin each costs the trapezoidal rule at most |jump of d f/d theta|
// h^2 / 12 with h = 2 pi / N and the jump k a1 sin(phi) <= k a1, so |error| <= k a1 h^2 /
// (12 pi) for F0 and k a1 h^2 / (6 pi) for F1 (plus round-off).
TEST(VibrationUnilateralSpring, DescribingFunctionMatchesClosedForm) {
  const HarmonicBalanceOptions o{{0, 1}, 2048};
  const HarmonicBasis basis(o);
  const auto N = static_cast<Eigen::Index>(o.time_points);
  const double h = 2.0 * kPi / static_cast<double>(N);
  const auto c0 = static_cast<Eigen::Index>(basis.index_of(0, 0));
  const auto c1 = static_cast<Eigen::Index>(basis.index_of(1, 0));
  std::size_t partial = 0;
  for (const UnilateralSpringParameters p : {UnilateralSpringParameters{.k = 3.0, .gap = 0.2},
                                             UnilateralSpringParameters{.k = 3.0, .N0 = 0.5}}) {
    const auto el = make_unilateral_spring_element(p);
    for (const double a0 : {-0.3, 0.0, 0.1, 0.4}) {
      for (const double a1 : {0.05, 0.25, 0.7, 1.5}) {
        Eigen::MatrixXd u(N, 1);
        for (Eigen::Index i = 0; i < N; ++i) {
          u(i, 0) = a0 + a1 * std::cos(h * static_cast<double>(i));
        }
        PeriodicResponse r;
        el->periodic_response(u, Eigen::MatrixXd(), false, r);
        Eigen::VectorXd F(basis.coefficients());
        basis.project(r.f.data(), F.data());
        const auto df = unilateral_describing_function(p, a0, a1);
        const double bound = p.k * a1 * h * h / (6.0 * kPi) + 1e-13 * (p.k * a1 + p.N0);
        EXPECT_NEAR(F(c0), df.F0, bound) << "a0 " << a0 << " a1 " << a1;
        EXPECT_NEAR(F(c1), df.F1, bound) << "a0 " << a0 << " a1 " << a1;
        const double c = (p.gap - p.N0 / p.k - a0) / a1;
        if (std::abs(c) < 1.0) ++partial;
      }
    }
  }
  EXPECT_GE(partial, 8U);  // most cases open and close the contact within the period
}

// Backbone of the piecewise-linear oscillator m x'' + k0 x + k max(x - g, 0) = 0 by EPMC on
// harmonics {0, 1} against its first-harmonic closed form: for the HB's first-harmonic
// amplitude a1, the mean a0 solves k0 a0 + F0(a0, a1) = 0 (bisection) and
// omega^2 = (k0 + F1(a0, a1) / a1) / m. Below the gap the oscillator is linear,
// omega = sqrt(k0 / m). Tolerance: the AFT error of F0 and F1 is at most
// e = k a1 h^2 / (6 pi) (see the describing-function test); it moves a0 by at most e / k0
// and omega^2 by (e + (2 k / pi) e / k0) / (m a1) (dF1/da0 = 2 k sin(phi) / pi); plus 1e-8
// relative, ten times the Newton tolerance of the continuation.
TEST(VibrationUnilateralSpring, PiecewiseLinearBackboneMatchesDescribingFunction) {
  const double m = 1.5, k0 = 2.0;
  const UnilateralSpringParameters p{.k = 6.0, .gap = 0.05};
  Structure s{Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, k0),
              Eigen::MatrixXd::Zero(1, 1)};
  const HarmonicBalanceOptions o{{0, 1}, 1024};
  const HarmonicBalance hb(
      s, {{make_unilateral_spring_element(p), Eigen::MatrixXd::Constant(1, 1, 1.0), "stop"}}, o);
  NonlinearModeOptions opt;
  opt.log10_amplitude_from = -2.0;
  opt.log10_amplitude_to = 0.0;
  const auto r = nonlinear_mode(hb, opt, {0});
  ASSERT_TRUE(r.continuation.complete) << r.continuation.stop_reason;
  const double h = 2.0 * kPi / static_cast<double>(o.time_points);
  const auto i0 = hb.index(0, static_cast<std::size_t>(hb.basis().index_of(0, 0)));
  const auto i1c = hb.index(0, static_cast<std::size_t>(hb.basis().index_of(1, 0)));
  const auto i1s = hb.index(0, static_cast<std::size_t>(hb.basis().index_of(1, 1)));
  std::size_t linear = 0, contact = 0;
  for (Eigen::Index i = 0; i < r.omega.size(); ++i) {
    const Eigen::VectorXd& U = r.harmonics[static_cast<std::size_t>(i)];
    const double a1 = std::hypot(U(i1c), U(i1s));
    double lo = -unilateral_describing_function(p, 0.0, a1).F0 / k0, hi = 0.0;
    for (int it = 0; it < 200 && hi - lo > 1e-15 * a1; ++it) {
      const double mid = 0.5 * (lo + hi);
      (k0 * mid + unilateral_describing_function(p, mid, a1).F0 > 0.0 ? hi : lo) = mid;
    }
    const double a0 = 0.5 * (lo + hi);
    const double w2 = (k0 + unilateral_describing_function(p, a0, a1).F1 / a1) / m;
    const double e = p.k * a1 * h * h / (6.0 * kPi);
    const double tol_a0 = e / k0 + 1e-8 * a1;
    const double tol_w =
        (e + 2.0 * p.k / kPi * e / k0) / (m * a1) / (2.0 * std::sqrt(w2)) + 1e-8 * std::sqrt(w2);
    EXPECT_NEAR(U(i0), a0, tol_a0) << "a1 = " << a1;
    EXPECT_NEAR(r.omega(i), std::sqrt(w2), tol_w) << "a1 = " << a1;
    EXPECT_NEAR(r.xi(i), 0.0, 1e-8 * r.omega(i));  // conservative: no extra damping
    if (a1 < p.gap) {
      ++linear;
      EXPECT_NEAR(r.omega(i), std::sqrt(k0 / m), 1e-9 * std::sqrt(k0 / m));
    } else {
      ++contact;
    }
  }
  EXPECT_GT(linear, 0U);
  EXPECT_GT(contact, 0U);
  // Hardening: omega never decreases with the amplitude once the stop is touched.
  for (Eigen::Index i = 1; i < r.omega.size(); ++i) {
    EXPECT_GE(r.omega(i), r.omega(i - 1) * (1.0 - 1e-9));
  }
}

// Preloaded: the contact stays closed while a1 < N0 / k, where the oscillator is linear
// with k0 + k (omega = sqrt((k0 + k) / m), to the Newton tolerance), then softens.
TEST(VibrationUnilateralSpring, PreloadedLinearLimit) {
  const double m = 1.0, k0 = 1.0;
  const UnilateralSpringParameters p{.k = 3.0, .N0 = 0.3};
  Structure s{Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, k0),
              Eigen::MatrixXd::Zero(1, 1)};
  const HarmonicBalance hb(
      s, {{make_unilateral_spring_element(p), Eigen::MatrixXd::Constant(1, 1, 1.0), "stop"}},
      HarmonicBalanceOptions{{0, 1, 2, 3}, 256});
  NonlinearModeOptions opt;
  opt.log10_amplitude_from = -3.0;
  opt.log10_amplitude_to = 0.0;
  const auto r = nonlinear_mode(hb, opt, {0});
  ASSERT_TRUE(r.continuation.complete) << r.continuation.stop_reason;
  const double w_closed = std::sqrt((k0 + p.k) / m);
  EXPECT_NEAR(r.linear_omega, w_closed, 1e-12 * w_closed);
  std::size_t closed = 0;
  for (Eigen::Index i = 0; i < r.omega.size(); ++i) {
    if (r.amplitude(i) < 0.9 * p.N0 / p.k) {
      ++closed;
      EXPECT_NEAR(r.omega(i), w_closed, 1e-9 * w_closed);
    }
  }
  EXPECT_GT(closed, 0U);
  EXPECT_LT(r.omega(r.omega.size() - 1), 0.9 * w_closed);  // softened by the separation
}

TEST(VibrationUnilateralSpring, BadParametersNameTheField) {
  using testing::invalid_input_message;
  EXPECT_NE(invalid_input_message([] {
              (void)make_unilateral_spring_element({.k = 0.0});
            }).find("unilateral_spring.k"),
            std::string::npos);
  EXPECT_NE(invalid_input_message([] {
              (void)make_unilateral_spring_element({.k = 1.0, .gap = -0.1});
            }).find("unilateral_spring.gap"),
            std::string::npos);
  EXPECT_NE(invalid_input_message([] {
              (void)make_unilateral_spring_element({.k = 1.0, .N0 = -1.0});
            }).find("unilateral_spring.N0"),
            std::string::npos);
  EXPECT_NE(invalid_input_message([] {
              (void)make_unilateral_spring_element({.k = 1.0, .gap = 0.1, .N0 = 1.0});
            }).find("both given"),
            std::string::npos);
  const auto el = make_unilateral_spring_element({.k = 1.0});
  PeriodicResponse r;
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(4, 1);
  u(2, 0) = std::nan("");
  EXPECT_NE(invalid_input_message([&] {
              el->periodic_response(u, Eigen::MatrixXd(), true, r);
            }).find("NaN"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------
// Elastic dry friction in three directions

// Smooth periodic samples of `dirs` directions: a mean, three harmonics, random phases.
Eigen::MatrixXd random_path(Eigen::Index N, Eigen::Index dirs, double amplitude,
                            std::mt19937_64& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::MatrixXd u(N, dirs);
  for (Eigen::Index d = 0; d < dirs; ++d) {
    const double a0 = 0.2 * U(rng), p1 = kPi * U(rng), a2 = 0.3 * U(rng), p2 = kPi * U(rng),
                 a3 = 0.2 * U(rng), p3 = kPi * U(rng);
    for (Eigen::Index i = 0; i < N; ++i) {
      const double t = 2.0 * kPi * static_cast<double>(i) / static_cast<double>(N);
      u(i, d) = amplitude *
                (a0 + std::cos(t + p1) + a2 * std::cos(2 * t + p2) + a3 * std::sin(3 * t + p3));
    }
  }
  return u;
}

// d f_d(t_i) / d u_e(t_j) as a dense (N dirs) x (N dirs) matrix, index i + N d.
using test_support::dense_tangent;

// With no motion along t2 the trial force stays on t1, |trial| = |trial_1| and e = +-1
// exactly, so the 3-D element performs the 2-D element's operations: forces and the
// (t1, n) block of the tangent agree to round-off (1e-13 relative), the t2 force is zero.
TEST(VibrationElasticDryFriction3d, ReducesTo2dWithoutT2Motion) {
  std::mt19937_64 rng(23);
  const Eigen::Index N = 64;
  for (const double N0 : {0.4, 0.0, -0.3}) {
    const auto el3 =
        make_elastic_dry_friction_3d_element({.k_t = 2.0, .k_n = 3.0, .mu = 0.4, .N0 = N0});
    const auto el2 =
        make_elastic_dry_friction_2d_element({.k_t = 2.0, .k_n = 3.0, .mu = 0.4, .N0 = N0});
    for (const double amplitude : {0.05, 0.3, 2.0}) {
      Eigen::MatrixXd u2 = random_path(N, 2, amplitude, rng);
      // normal: across the contact's opening (at u_n = -N0 / k_n) at every amplitude
      u2.col(1) = (0.3 * u2.col(1)).array() + std::max(-N0 / 3.0, 0.0);
      Eigen::MatrixXd u3 = Eigen::MatrixXd::Zero(N, 3);
      u3.col(0) = u2.col(0);
      u3.col(2) = u2.col(1);
      PeriodicResponse r2, r3;
      el2->periodic_response(u2, Eigen::MatrixXd(), true, r2);
      el3->periodic_response(u3, Eigen::MatrixXd(), true, r3);
      const double fscale = r2.f.cwiseAbs().maxCoeff() + 1e-300;
      EXPECT_LE((r3.f.col(0) - r2.f.col(0)).cwiseAbs().maxCoeff(), 1e-13 * fscale);
      EXPECT_LE((r3.f.col(2) - r2.f.col(1)).cwiseAbs().maxCoeff(), 1e-13 * fscale);
      EXPECT_EQ(r3.f.col(1).cwiseAbs().maxCoeff(), 0.0);
      const Eigen::MatrixXd D2 = dense_tangent(r2, N, 2), D3 = dense_tangent(r3, N, 3);
      Eigen::MatrixXd D3r(2 * N, 2 * N);  // rows and columns of t1 and n
      const std::array<Eigen::Index, 2> map{0, 2};
      for (Eigen::Index a = 0; a < 2; ++a) {
        for (Eigen::Index b = 0; b < 2; ++b) {
          D3r.block(N * a, N * b, N, N) = D3.block(N * map[static_cast<std::size_t>(a)],
                                                   N * map[static_cast<std::size_t>(b)], N, N);
        }
      }
      const double scale = D2.cwiseAbs().maxCoeff();
      ASSERT_GT(scale, 0.0);
      EXPECT_LE((D3r - D2).cwiseAbs().maxCoeff(), 1e-13 * scale)
          << "N0 " << N0 << " amplitude " << amplitude;
    }
  }
}

// A circular tangential path u_t = R (cos theta, sin theta) at constant normal load, slipping
// throughout (R > r = mu f_n / k_t). Radial return at step h = 2 pi / N has the exact steady
// state f_t = mu f_n (cos, sin)(theta_i + psi_h) with cos(psi_h + h/2) = r cos(h/2) / R (the
// trial force k_t R 2 sin(h/2) along the chord added to f_t must point at theta_{i+1} +
// psi_h); psi_h -> acos(r / R), the continuous sliding lag, as h -> 0. The transient from
// the virgin start decays by about exp(-2 pi tan psi_h) per revolution (measured, R = 2 r,
// N = 64: 6.0e-5 against 5.8e-5): at R = 10 r, e^-60, so the second pass is steady to
// round-off (1e-12 rad and 1e-14 relative in the magnitude).
TEST(VibrationElasticDryFriction3d, CircularPathGivesSteadySlidingForce) {
  const ElasticDryFriction3dParameters p{.k_t = 2.0, .k_n = 3.0, .mu = 0.4, .N0 = 1.0};
  const auto el = make_elastic_dry_friction_3d_element(p);
  const double un = 1.0 / 6.0, fn = p.N0 + p.k_n * un, F = p.mu * fn, r = F / p.k_t, R = 10.0 * r;
  for (const Eigen::Index N : {64, 1024}) {
    const double h = 2.0 * kPi / static_cast<double>(N);
    Eigen::MatrixXd u(N, 3);
    for (Eigen::Index i = 0; i < N; ++i) {
      u(i, 0) = R * std::cos(h * static_cast<double>(i));
      u(i, 1) = R * std::sin(h * static_cast<double>(i));
      u(i, 2) = un;
    }
    PeriodicResponse out;
    el->periodic_response(u, Eigen::MatrixXd(), false, out);
    const double psi_h = std::acos(r * std::cos(0.5 * h) / R) - 0.5 * h;
    for (Eigen::Index i = 0; i < N; ++i) {
      const double theta = h * static_cast<double>(i);
      EXPECT_NEAR(std::hypot(out.f(i, 0), out.f(i, 1)), F, 1e-14 * F);
      const double lag = std::remainder(std::atan2(out.f(i, 1), out.f(i, 0)) - theta, 2.0 * kPi);
      EXPECT_NEAR(lag, psi_h, 1e-12) << "N " << N << " sample " << i;
      EXPECT_NEAR(out.f(i, 2), fn - p.N0, 1e-15 * fn);
    }
    // The continuous limit: psi_h - acos(r/R) = O(h) (-h/2 + O(h^2)).
    EXPECT_NEAR(psi_h, std::acos(r / R), 0.6 * h);
  }
}

// The tangent (local + history) of the periodic and the static response against central
// differences. Slip with a turning direction makes the force smooth but not linear within
// a regime: the truncation error is O(h^2 k_t^3 / (mu f_n)^2) ~ 1e-14 relative at
// h = 1e-7 amplitude, round-off eps |f| / h ~ 1e-9; a sample within h of a stick-slip or
// contact switch (probability ~ N h / amplitude ~ 1e-5) would show as an O(1) mismatch.
TEST(VibrationElasticDryFriction3d, TangentMatchesFiniteDifferences) {
  std::mt19937_64 rng(29);
  const Eigen::Index N = 32;
  const auto el =
      make_elastic_dry_friction_3d_element({.k_t = 2.0, .k_n = 3.0, .mu = 0.4, .N0 = 0.2});
  std::size_t with_history = 0;
  for (const double amplitude : {0.05, 0.3, 2.0}) {
    Eigen::MatrixXd u = random_path(N, 3, amplitude, rng);
    u.col(2) *= 0.3;  // normal: partly separating
    PeriodicResponse r;
    el->periodic_response(u, Eigen::MatrixXd(), true, r);
    if (!r.history.empty()) ++with_history;
    const Eigen::MatrixXd D = dense_tangent(r, N, 3);
    const double h = 1e-7 * amplitude;
    Eigen::MatrixXd Dfd(D.rows(), D.cols());
    for (Eigen::Index c = 0; c < D.cols(); ++c) {
      Eigen::MatrixXd up = u, um = u;
      up(c % N, c / N) += h;
      um(c % N, c / N) -= h;
      PeriodicResponse rp, rm;
      el->periodic_response(up, Eigen::MatrixXd(), false, rp);
      el->periodic_response(um, Eigen::MatrixXd(), false, rm);
      const Eigen::MatrixXd df = (rp.f - rm.f) / (2.0 * h);
      Dfd.col(c) = Eigen::Map<const Eigen::VectorXd>(df.data(), df.size());
    }
    const double scale = D.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    EXPECT_LT((D - Dfd).cwiseAbs().maxCoeff(), 1e-6 * scale) << "amplitude " << amplitude;
    for (Eigen::Index i = 0; i < N; ++i) {
      Eigen::VectorXd f;
      Eigen::MatrixXd K;
      el->static_response(u.row(i).transpose(), f, K);
      for (Eigen::Index e = 0; e < 3; ++e) {
        Eigen::VectorXd up = u.row(i).transpose(), um = up, fp, fm;
        up(e) += h;
        um(e) -= h;
        Eigen::MatrixXd Kp, Km;
        el->static_response(up, fp, Kp);
        el->static_response(um, fm, Km);
        EXPECT_LT((K.col(e) - (fp - fm) / (2.0 * h)).cwiseAbs().maxCoeff(), 1e-6 * scale);
      }
    }
  }
  EXPECT_GE(with_history, 2U);  // slip and stick with history at the larger amplitudes
}

// The work done on the element over one period, W = sum_i f_i . (u_i - u_{i-1}) (the
// period closes: u_{-1} = u_{N-1}), is the energy the radial return dissipates and never
// negative: tangentially, u_t,i - u_t,i-1 = (f_t,i - f_t,i-1) / k_t + slip along f_t,i, so
// f_t,i . du = (|f_i|^2 - |f_i-1|^2) / 2 k_t + |f_i - f_i-1|^2 / 2 k_t + mu f_n |slip|
// (telescoping to zero over the period, the rest >= 0); normally f_n(u_n,i) (u_n,i -
// u_n,i-1) >= the integral of the non-decreasing f_n, which closes to zero. Checked on
// random paths with stick, slip, turning slip directions and separation.
TEST(VibrationElasticDryFriction3d, DissipationPerCycleIsNeverNegative) {
  std::mt19937_64 rng(31);
  const Eigen::Index N = 128;
  std::size_t dissipating = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const double N0 = trial % 3 == 0 ? -0.2 : 0.5;
    const auto el =
        make_elastic_dry_friction_3d_element({.k_t = 2.0, .k_n = 3.0, .mu = 0.4, .N0 = N0});
    const double amplitude = std::pow(10.0, -1.5 + 2.0 * static_cast<double>(trial % 10) / 9.0);
    Eigen::MatrixXd u = random_path(N, 3, amplitude, rng);
    u.col(2) *= 0.3;
    PeriodicResponse r;
    el->periodic_response(u, Eigen::MatrixXd(), false, r);
    double W = 0.0, scale = 0.0;
    for (Eigen::Index i = 0; i < N; ++i) {
      const Eigen::Index im = (i + N - 1) % N;
      const double w = r.f.row(i).dot(u.row(i) - u.row(im));
      W += w;
      scale += std::abs(w);
    }
    EXPECT_GE(W, -1e-13 * scale) << "trial " << trial;
    if (W > 1e-6 * scale) ++dissipating;
  }
  EXPECT_GT(dissipating, 30U);
}

TEST(VibrationElasticDryFriction3d, BadInputNamesTheField) {
  using testing::invalid_input_message;
  EXPECT_NE(invalid_input_message([] {
              (void)make_elastic_dry_friction_3d_element({.k_t = 1.0, .k_n = 1.0, .mu = 0.0});
            }).find("elastic_dry_friction_3d.mu"),
            std::string::npos);
  EXPECT_NE(invalid_input_message([] {
              (void)make_elastic_dry_friction_3d_element({.k_t = -1.0, .k_n = 1.0, .mu = 0.1});
            }).find("elastic_dry_friction_3d.k_t"),
            std::string::npos);
  const auto el = make_elastic_dry_friction_3d_element({.k_t = 1.0, .k_n = 1.0, .mu = 0.1});
  PeriodicResponse r;
  EXPECT_NE(invalid_input_message([&] {
              el->periodic_response(Eigen::MatrixXd::Zero(4, 2), Eigen::MatrixXd(), true, r);
            }).find("3 directions"),
            std::string::npos);
}

}  // namespace
}  // namespace asperity::vibration
