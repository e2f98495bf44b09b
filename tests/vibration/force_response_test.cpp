// Tests of the continuation in force amplitude (vibration/force_response.hpp): the linear
// limit and the one-harmonic Duffing response at fixed frequency with its two turning
// points in the force against their closed forms.
// g++ 12 reports Eigen's freshly allocated dynamic matrices as potential null
// dereferences when their entries are written (a known false positive at -O3).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <gtest/gtest.h>

#include <cmath>

#include "../support.hpp"
#include "asperity/vibration/force_response.hpp"

namespace asperity::vibration {
namespace {

Structure sdof(double m, double k, double c) {
  return Structure{Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, k),
                   Eigen::MatrixXd::Constant(1, 1, c)};
}

// Linear SDOF under lambda F cos(w t): |X| = lambda F / sqrt((k - m w^2)^2 + (c w)^2) at
// every point, to the Newton tolerance (1e-9, scaled).
TEST(VibrationForceResponse, LinearLimitIsProportional) {
  const double m = 2.0, k = 3.0, c = 0.1, w = 1.1, F = 0.7;
  const HarmonicBalance hb(sdof(m, k, c), {}, HarmonicBalanceOptions{{0, 1, 2, 3}, 16});
  ForceResponseOptions o;
  o.force = Eigen::VectorXd::Zero(hb.unknowns());
  o.force(hb.index(0, static_cast<std::size_t>(hb.basis().index_of(1, 0)))) = F;
  o.omega = w;
  o.scale_from = 0.0;
  o.scale_to = 2.0;
  const ForceResponseCurve r = force_response(hb, o, {0});
  ASSERT_TRUE(r.continuation.complete) << r.continuation.stop_reason;
  ASSERT_GE(r.force_scale.size(), 3);
  const double gain = F / std::hypot(k - m * w * w, c * w);
  for (Eigen::Index i = 0; i < r.force_scale.size(); ++i) {
    EXPECT_NEAR(r.output_amplitude(i, 0), r.force_scale(i) * gain, 1e-9 * 2.0 * gain);
  }
  EXPECT_NEAR(r.force_scale(r.force_scale.size() - 1), 2.0, 1e-12);
  EXPECT_TRUE(r.folds.empty());
}

// Duffing x'' + c x' + x + gamma x^3 = lambda cos(w t) on one harmonic (AFT exact: the
// cubic of harmonic 1 holds harmonics 1 and 3, 16 samples alias neither onto 1): with
// r = |X|, lambda^2 = G(r^2), G(x) = x ((A + B x)^2 + C^2), A = 1 - w^2, B = 3/4 gamma,
// C = c w. Above resonance (w = 1.6) lambda(r) rises, falls and rises: the turning points
// in lambda are the roots of G'(x) = 3 B^2 x^2 + 4 A B x + A^2 + C^2 = 0. Every point
// solves lambda^2 = G(r^2) to the Newton tolerance (1e-8 relative, ten times it); the
// refined folds give lambda to 1e-9 (the maximum of lambda is flat there) and x to 1e-6
// (Brent on the chord to sqrt(eps), a first-order error in the location).
TEST(VibrationForceResponse, DuffingFoldsMatchClosedForm) {
  const double gamma = 1.0, c = 0.05, w = 1.6;
  const Eigen::MatrixXd T = Eigen::MatrixXd::Constant(1, 1, 1.0);
  const HarmonicBalance hb(sdof(1.0, 1.0, c),
                           {{make_polynomial_stiffness_element({.k3 = gamma}), T, "duffing"}},
                           HarmonicBalanceOptions{{1}, 16});
  ForceResponseOptions o;
  o.force = Eigen::VectorXd::Zero(hb.unknowns());
  o.force(hb.index(0, static_cast<std::size_t>(hb.basis().index_of(1, 0)))) = 1.0;
  o.omega = w;
  o.scale_from = 0.0;
  o.scale_to = 1.5;
  const ForceResponseCurve r = force_response(hb, o, {0});
  ASSERT_TRUE(r.continuation.complete) << r.continuation.stop_reason;
  const double A = 1.0 - w * w, B = 0.75 * gamma, C = c * w;
  const auto G = [&](double x) { return x * ((A + B * x) * (A + B * x) + C * C); };
  for (Eigen::Index i = 0; i < r.force_scale.size(); ++i) {
    const double a = r.output_amplitude(i, 0);
    EXPECT_NEAR(r.force_scale(i), std::sqrt(G(a * a)), 1e-8 * (r.force_scale(i) + 1e-3))
        << "r = " << a;
  }
  EXPECT_EQ(r.continuation.turning_points, 2U);
  ASSERT_EQ(r.folds.size(), 2U);
  const double disc = std::sqrt(16.0 * A * A * B * B - 12.0 * B * B * (A * A + C * C));
  const double x_max = (-4.0 * A * B - disc) / (6.0 * B * B);  // lambda's local maximum
  const double x_min = (-4.0 * A * B + disc) / (6.0 * B * B);  // and minimum
  const double a_max = r.folds[0].output_amplitude(0), a_min = r.folds[1].output_amplitude(0);
  EXPECT_NEAR(a_max * a_max, x_max, 1e-6 * x_max);
  EXPECT_NEAR(a_min * a_min, x_min, 1e-6 * x_min);
  EXPECT_NEAR(r.folds[0].force_scale, std::sqrt(G(x_max)), 1e-9 * std::sqrt(G(x_max)));
  EXPECT_NEAR(r.folds[1].force_scale, std::sqrt(G(x_min)), 1e-9 * std::sqrt(G(x_min)));
  // The computed points of the lower branch (below the first fold's amplitude) stay below
  // the refined maximum of lambda.
  for (Eigen::Index i = 0; i < r.force_scale.size(); ++i) {
    if (r.output_amplitude(i, 0) < a_max) {
      EXPECT_LE(r.force_scale(i), r.folds[0].force_scale * (1.0 + 1e-12));
    }
  }
}

TEST(VibrationForceResponse, BadOptionsNameTheField) {
  using testing::invalid_input_message;
  const HarmonicBalance hb(sdof(1.0, 1.0, 0.1), {}, HarmonicBalanceOptions{{0, 1}, 8});
  ForceResponseOptions o;
  o.force = Eigen::VectorXd::Zero(hb.unknowns());
  o.omega = 1.0;
  EXPECT_NE(invalid_input_message([&] { (void)force_response(hb, o, {0}); }).find("is zero"),
            std::string::npos);
  o.force(1) = 1.0;
  o.omega = -1.0;
  EXPECT_NE(
      invalid_input_message([&] { (void)force_response(hb, o, {0}); }).find("force_response.omega"),
      std::string::npos);
  o.omega = 1.0;
  o.scale_to = -2.0;
  EXPECT_NE(invalid_input_message([&] {
              (void)force_response(hb, o, {0});
            }).find("force_response.force_scale.to"),
            std::string::npos);
  o.scale_to = 1.0;
  EXPECT_NE(invalid_input_message([&] { (void)force_response(hb, o, {3}); }).find("output_dofs"),
            std::string::npos);
}

}  // namespace
}  // namespace asperity::vibration
