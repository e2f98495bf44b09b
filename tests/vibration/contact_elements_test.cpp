// Tests of the contact elements (vibration/contact_elements.hpp): the unilateral spring's
// tangent against finite differences, its describing function (the piecewise-linear
// oscillator's) against the closed form, and the backbone of a piecewise-linear
// oscillator computed by EPMC against the first-harmonic closed form.
// g++ 12 reports Eigen's freshly allocated dynamic matrices as potential null
// dereferences when their entries are written (a known false positive at -O3).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "../support.hpp"
#include "asperity/vibration/analysis.hpp"
#include "asperity/vibration/contact_elements.hpp"
#include "asperity/vibration/harmonic_balance.hpp"

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

}  // namespace
}  // namespace asperity::vibration
