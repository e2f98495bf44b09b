// Peak and fold refinement on forced responses (issue 23) against closed forms: the
// linear single-DOF resonance, and the folds and peak of the one-harmonic Duffing
// response, located between the computed points of a continuation.

// g++ 12 reports writes into Eigen's dynamic matrices as potential null dereferences
// (a known false positive of -Wnull-dereference at -O3).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <gtest/gtest.h>

#include <cmath>

#include "asperity/vibration/analysis.hpp"
#include "asperity/vibration/continuation.hpp"

namespace asperity::vibration {
namespace {

// m x'' + c x' + k x = F cos(w t): |X|^2 = F^2 / ((k - m w^2)^2 + c^2 w^2) peaks at
// w^2 = k/m - c^2/(2 m^2) with |X| = F / (c sqrt(k/m - c^2/(4 m^2))) (d|X|^2/d w^2 = 0).
TEST(VibrationPeaks, LinearResonancePeakMatchesClosedForm) {
  const double m = 1.0, k = 1.0, c = 0.05, F = 1.0;
  Structure s{Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, k),
              Eigen::MatrixXd::Constant(1, 1, c)};
  const HarmonicBalance hb(s, {}, HarmonicBalanceOptions{{1}, 8});
  FrequencyResponseOptions opt;
  opt.force = Eigen::VectorXd::Zero(hb.unknowns());
  opt.force(hb.index(0, 0)) = F;
  opt.omega_from = 0.5;
  opt.omega_to = 1.5;
  const auto curves = frequency_response(hb, opt, {0});
  ASSERT_TRUE(curves[0].continuation.complete);
  ASSERT_EQ(curves[0].peaks.size(), 1u);
  EXPECT_TRUE(curves[0].folds.empty());  // a linear response does not fold
  const ResponsePeak& pk = curves[0].peaks.front();
  const double w_peak = std::sqrt(k / m - c * c / (2.0 * m * m));
  const double X_peak = F / (c * std::sqrt(k / m - c * c / (4.0 * m * m)));
  // The amplitude is flat at the peak: Brent's sqrt(eps) location error gives about
  // 1e-8 in omega (relative) and round-off in |X|; the points themselves miss the peak
  // by the step size (checked below so that the test shows the refinement).
  EXPECT_NEAR(pk.omega, w_peak, 1e-7 * w_peak);
  EXPECT_NEAR(pk.amplitude, X_peak, 1e-10 * X_peak);
  EXPECT_LT(curves[0].output_amplitude.maxCoeff(), X_peak * (1.0 - 1e-8));
}

constexpr double kGamma = 1.0, kC = 0.05, kF = 0.3;

// One-harmonic Duffing x'' + c x' + x + gamma x^3 = F cos(w t) (as continuation_test.cpp):
// with r^2 = a^2 + b^2, u = w^2 and A = 1 + 3/4 gamma r^2, the response is
// G(r, u) = (A - u)^2 + c^2 u - F^2 / r^2 = 0. A fold (du/ds = 0) has dG/dr = 0:
// 3 gamma r (A - u) + 2 F^2 / r^3 = 0; a peak of r (dr/ds = 0) has dG/du = 0:
// c^2 - 2 (A - u) = 0.
void duffing(const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
  const double a = y(0), b = y(1), w = y(2);
  const double r2 = a * a + b * b, k = 1.0 - w * w + 0.75 * kGamma * r2;
  R.resize(2);
  R << k * a + kC * w * b - kF, k * b - kC * w * a;
  if (!J) return;
  J->resize(2, 3);
  (*J)(0, 0) = k + 1.5 * kGamma * a * a;
  (*J)(0, 1) = kC * w + 1.5 * kGamma * a * b;
  (*J)(1, 0) = -kC * w + 1.5 * kGamma * a * b;
  (*J)(1, 1) = k + 1.5 * kGamma * b * b;
  (*J)(0, 2) = -2.0 * w * a + kC * b;
  (*J)(1, 2) = -2.0 * w * b - kC * a;
}

TEST(VibrationPeaks, DuffingFoldsAndPeakMatchTheirClosedForms) {
  ContinuationProblem pb;
  pb.f = duffing;
  pb.parameter = 2;
  pb.scale = Eigen::Vector3d(1.0, 1.0, 2.0);
  pb.residual_scale = kF;
  pb.parameter_end = 2.5;
  ContinuationOptions opt;
  opt.step = 0.01;
  opt.max_step = 0.05;
  const ContinuationResult r = continue_curve(pb, Eigen::Vector3d(0.4, 0.0, 0.5), opt);
  ASSERT_TRUE(r.complete) << r.stop_reason;
  std::vector<double> w, minus_w, amplitude;
  for (const auto& y : r.points) {
    w.push_back(y(2));
    minus_w.push_back(-y(2));
    amplitude.push_back(std::hypot(y(0), y(1)));
  }
  const auto none = [](double) { return 0.0; };
  const auto top = prominent_maxima(w, none), bottom = prominent_maxima(minus_w, none),
             peaks = prominent_maxima(amplitude, none);
  ASSERT_EQ(top.size(), 1u);     // the overhang's tip
  ASSERT_EQ(bottom.size(), 1u);  // its jump-up point
  ASSERT_EQ(peaks.size(), 1u);
  const auto check = [&](const Eigen::VectorXd& y, bool fold) {
    Eigen::VectorXd R;
    duffing(y, R, nullptr);
    EXPECT_LT(R.cwiseAbs().maxCoeff(), 1e-9 * kF);  // on the curve
    const double r2 = y(0) * y(0) + y(1) * y(1), rr = std::sqrt(r2), u = y(2) * y(2);
    const double A = 1.0 + 0.75 * kGamma * r2;
    // The condition to Brent's location error (sqrt(eps) of a chord of ~0.05 times the
    // curve's turn): 1e-6 of its terms' magnitude.
    if (fold) {
      const double t1 = 3.0 * kGamma * rr * (A - u), t2 = 2.0 * kF * kF / (r2 * rr);
      EXPECT_NEAR(t1 + t2, 0.0, 1e-6 * (std::abs(t1) + t2)) << "fold at w = " << y(2);
    } else {
      EXPECT_NEAR(kC * kC - 2.0 * (A - u), 0.0, 1e-6 * (kC * kC + 2.0 * std::abs(A - u)))
          << "peak at w = " << y(2);
    }
  };
  const auto omega = [](const Eigen::VectorXd& y) { return y(2); };
  const auto minus_omega = [](const Eigen::VectorXd& y) { return -y(2); };
  const auto radius = [](const Eigen::VectorXd& y) { return std::hypot(y(0), y(1)); };
  const Eigen::VectorXd tip = refine_curve_maximum(pb, r.points, top[0], opt.newton, omega);
  const Eigen::VectorXd jump =
      refine_curve_maximum(pb, r.points, bottom[0], opt.newton, minus_omega);
  const Eigen::VectorXd peak = refine_curve_maximum(pb, r.points, peaks[0], opt.newton, radius);
  check(tip, true);
  check(jump, true);
  check(peak, false);
  EXPECT_GE(tip(2), w[top[0]]);
  EXPECT_LE(jump(2), w[bottom[0]]);
  EXPECT_GE(radius(peak), amplitude[peaks[0]]);
}

}  // namespace
}  // namespace asperity::vibration
