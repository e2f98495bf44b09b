// Newton and arclength continuation on a closed-form problem with turning points: the
// one-harmonic balance of a Duffing oscillator x'' + c x' + x + gamma x^3 = F cos(w t),
//   (1 - w^2) a + c w b + 3/4 gamma r^2 a = F,  (1 - w^2) b - c w a + 3/4 gamma r^2 b = 0,
// r^2 = a^2 + b^2 (e.g. Krack & Gross 2019, sec. 2.2). For gamma = 1, c = 0.05, F = 0.3 its
// response curve over w in [0.5, 2.5] folds twice (the hardening overhang), so a
// continuation in w alone would fail and the arclength one must turn twice.

// g++ 12 reports writes into Eigen's dynamic matrices as potential null dereferences
// (a known false positive of -Wnull-dereference at -O3).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "asperity/core/error.hpp"
#include "asperity/vibration/continuation.hpp"

namespace asperity::vibration {
namespace {

constexpr double kGamma = 1.0, kC = 0.05, kF = 0.3;

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

// Each continuation test runs with full Newton and with chord Newton (chord_unknowns = 1:
// the factorisation at the last point reused by the next corrector), which must trace the
// same curve to the same tolerances.
class VibrationContinuationCorrector : public ::testing::TestWithParam<std::size_t> {};
INSTANTIATE_TEST_SUITE_P(FullAndChordNewton, VibrationContinuationCorrector,
                         ::testing::Values(std::size_t{1500}, std::size_t{1}));

TEST_P(VibrationContinuationCorrector, FollowsBothTurningPointsOfTheDuffingResponse) {
  ContinuationProblem pb;
  pb.f = duffing;
  pb.parameter = 2;
  pb.scale = Eigen::Vector3d(1.0, 1.0, 2.0);
  pb.residual_scale = kF;
  pb.parameter_end = 2.5;
  ContinuationOptions opt;
  opt.step = 0.01;
  opt.max_step = 0.05;
  opt.chord_unknowns = GetParam();
  const Eigen::Vector3d y0(kF / (1.0 - 0.25), 0.0, 0.5);  // the linear response as a guess
  const ContinuationResult r = continue_curve(pb, y0, opt);
  ASSERT_TRUE(r.complete) << r.stop_reason;
  EXPECT_EQ(r.turning_points, 2u);
  double peak = 0.0;
  for (const auto& y : r.points) {
    Eigen::VectorXd R;
    duffing(y, R, nullptr);
    EXPECT_LT(R.cwiseAbs().maxCoeff(), 1e-9 * kF);  // every point solves the equations
    peak = std::max(peak, std::hypot(y(0), y(1)));
  }
  // The peak lies on the backbone near r = F / (c w): the continuation climbs the whole
  // overhang (w ~ 1 + 3/8 gamma r^2 ~ 2.4 there, r ~ 2.5; within 5 %).
  EXPECT_GT(peak, 0.95 * kF / (kC * 2.4));
  EXPECT_DOUBLE_EQ(r.points.back()(2), 2.5);
}

// A Z-shaped curve whose folds are kinks: lambda = f(x) with f piecewise linear, slope 1
// up to x = 1, -2 up to x = 1.2, 1 beyond (the shape of the AFT curves of issue 23, where
// contact located at samples makes the residual piecewise smooth). At each kink the curve
// leaves backwards (the next piece's tangent (1, -2)/sqrt 5 makes an obtuse angle with
// (1, 1)/sqrt 2), so no point on the corrector's plane normal to the arriving tangent
// continues it: the continuation has to take the next piece's tangent.
void zigzag(const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
  const double x = y(0), lambda = y(1);
  const double f = x < 1.0 ? x : (x < 1.2 ? 1.0 - 2.0 * (x - 1.0) : 0.6 + (x - 1.2));
  const double slope = x < 1.0 ? 1.0 : (x < 1.2 ? -2.0 : 1.0);
  R = Eigen::VectorXd::Constant(1, f - lambda);
  if (J) *J = Eigen::RowVector2d(slope, -1.0);
}

TEST_P(VibrationContinuationCorrector, FollowsFoldsAtKinksOfAPiecewiseLinearCurve) {
  ContinuationProblem pb;
  pb.f = zigzag;
  pb.parameter = 1;
  pb.scale = Eigen::Vector2d(1.0, 1.0);
  pb.residual_scale = 1.0;
  pb.parameter_end = 2.0;
  ContinuationOptions opt;
  opt.step = 0.01;
  opt.max_step = 0.05;
  opt.chord_unknowns = GetParam();
  const ContinuationResult r = continue_curve(pb, Eigen::Vector2d(0.0, 0.0), opt);
  ASSERT_TRUE(r.complete) << r.stop_reason;
  EXPECT_EQ(r.turning_points, 2u);  // down at x = 1, up again at x = 1.2
  EXPECT_EQ(r.kinks, 2u);
  bool on_the_middle_piece = false;
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    Eigen::VectorXd R;
    zigzag(r.points[k], R, nullptr);
    EXPECT_LT(std::abs(R(0)), 1e-12);  // a piecewise-linear residual: Newton is exact
    // Along the curve x only grows: no piece is traced twice.
    if (k > 0) {
      EXPECT_GT(r.points[k](0), r.points[k - 1](0));
    }
    on_the_middle_piece = on_the_middle_piece || (r.points[k](0) > 1.0 && r.points[k](0) < 1.2);
  }
  EXPECT_TRUE(on_the_middle_piece);
  EXPECT_DOUBLE_EQ(r.points.back()(1), 2.0);
}

TEST(VibrationContinuation, NewtonConvergesQuadraticallyOnASmoothSystem) {
  // x^2 = 2 by Newton from 1: 1.5, 1.41667, 1.414216, ...: converged in at most 6.
  const SystemFunction f = [](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    R = Eigen::VectorXd::Constant(1, y(0) * y(0) - 2.0);
    if (J) *J = Eigen::MatrixXd::Constant(1, 1, 2.0 * y(0));
  };
  const NewtonResult r =
      solve_newton(f, Eigen::VectorXd::Constant(1, 1.0), Eigen::VectorXd::Ones(1), 1.0, {});
  ASSERT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 6);
  EXPECT_NEAR(r.y(0), std::sqrt(2.0), 1e-14);
}

TEST(VibrationContinuation, NewtonShortensAStepThatTakesAnElementOutOfItsRange) {
  // exp(x) - 1 = 0 from x = -3: the full Newton step lands at x = 16.1 and the first halving
  // at 6.55, both past x = 5 where the "element" throws (as a rough contact pressed past
  // its tables does); the line search goes on halving (x = -0.61 at 1/8) and Newton
  // converges to 0, the message kept.
  const SystemFunction f = [](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    if (y(0) > 5.0) throw NumericalError("element 1: outside its tables");
    R = Eigen::VectorXd::Constant(1, std::exp(y(0)) - 1.0);
    if (J) *J = Eigen::MatrixXd::Constant(1, 1, std::exp(y(0)));
  };
  const NewtonResult r =
      solve_newton(f, Eigen::VectorXd::Constant(1, -3.0), Eigen::VectorXd::Ones(1), 1.0, {});
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.y(0), 0.0, 1e-12);
  EXPECT_NE(r.failure.find("outside its tables"), std::string::npos) << r.failure;
}

TEST_P(VibrationContinuationCorrector, AnElementErrorAtTrialPointsStopsTheCurveWithItsMessage) {
  // x = lambda^2 continued in lambda from 0 towards 3; the system refuses lambda > 1.5.
  // The curve up to 1.5 is kept and the stop names the stall and the element's message
  // (before, the error ended the analysis and the points were lost).
  ContinuationProblem pb;
  pb.f = [](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    if (y(1) > 1.5) throw NumericalError("element 1: outside its tables");
    R = Eigen::VectorXd::Constant(1, y(0) - y(1) * y(1));
    if (J) {
      J->resize(1, 2);
      *J << 1.0, -2.0 * y(1);
    }
  };
  pb.parameter = 1;
  pb.scale = Eigen::VectorXd::Ones(2);
  pb.parameter_end = 3.0;
  ContinuationOptions opt;
  opt.step = 0.1;
  opt.min_step = 1e-4;
  opt.chord_unknowns = GetParam();
  const ContinuationResult r = continue_curve(pb, Eigen::Vector2d(0.0, 0.0), opt);
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.cause, StopCause::stalled);
  EXPECT_NE(r.stop_reason.find("outside its tables"), std::string::npos) << r.stop_reason;
  ASSERT_GE(r.points.size(), 2U);
  EXPECT_GT(r.points.back()(1), 1.49);
  EXPECT_LE(r.points.back()(1), 1.5);
  for (const auto& y : r.points) EXPECT_NEAR(y(0), y(1) * y(1), 1e-8);
}

// A residual with a jump: x - lambda + D [x > 1], D = 1. Along x = lambda the curve ends at
// x = 1 (for 1 < lambda < 2 neither piece has a solution), so every step past it is rejected
// and the continuation stalls there, as the BRB's mode 2 does where one element's response
// jumps (docs/brb.md). Newton cannot converge onto a jump: a rejected step is to cost the
// corrector's budget, at most 2 max(2, max_iterations / 4) factorisations (the chord
// corrector's, then as many for full Newton from its last iterate where |R| fell tenfold);
// before, full Newton restarted from the predictor with max_iterations more (25 per rejected
// step with the defaults).
TEST(VibrationContinuation, AStepRejectedAtAJumpCostsTheCorrectorsBudgetOfFactorisations) {
  constexpr double kJump = 1.0;
  ContinuationProblem pb;
  pb.f = [](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    R = Eigen::VectorXd::Constant(1, y(0) - y(1) + (y(0) > 1.0 ? kJump : 0.0));
    if (J) *J = Eigen::RowVector2d(1.0, -1.0);
  };
  pb.parameter = 1;
  pb.scale = Eigen::Vector2d(1.0, 1.0);
  pb.parameter_end = 3.0;
  ContinuationOptions opt;
  opt.step = 0.05;
  opt.max_step = 0.1;
  opt.min_step = 1e-6;
  opt.chord_unknowns = 1;
  const ContinuationResult r = continue_curve(pb, Eigen::Vector2d(0.0, 0.0), opt);
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.cause, StopCause::stalled);
  ASSERT_GE(r.points.size(), 2U);
  EXPECT_GT(r.points.back()(1), 1.0 - 1e-4);  // stalled at the jump, not before it
  EXPECT_LE(r.points.back()(0), 1.0);
  EXPECT_GE(r.rejected_steps, 15U);  // 0.1 halved below 1e-6: the stall is reached by halving
  // Each point on a linear piece takes at most one (the start's; the others converge on the
  // factorisation made at the last point). Measured: 236 for 24 rejected steps and 22 points.
  const auto budget = static_cast<std::size_t>(2 * std::max(2, opt.newton.max_iterations / 4));
  EXPECT_LE(r.factorizations, budget * r.rejected_steps + r.points.size())
      << r.rejected_steps << " rejected steps, " << r.points.size() << " points";
}

}  // namespace
}  // namespace asperity::vibration
