// Tests of the single-nonlinear-mode reduced-order model (vibration/mode_rom.hpp): exact
// for the one-harmonic Duffing oscillator with viscous damping, and against the full
// forced response of a 2-DOF system with a Jenkins joint.
// g++ 12 reports Eigen's freshly allocated dynamic matrices as potential null
// dereferences when their entries are written (a known false positive at -O3).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <gtest/gtest.h>

#include <cmath>

#include "../support.hpp"
#include "asperity/vibration/mode_rom.hpp"

namespace asperity::vibration {
namespace {

// x'' + c x' + x + gamma x^3 = F cos(W t) on one harmonic: EPMC gives omega^2 = 1 + 3/4
// gamma a^2 and xi = c, and the model's equation is then the first-harmonic balance of the
// forced response itself, ((1 + 3/4 gamma a^2 - W^2)^2 + (c W)^2) a^2 = F^2: every point to
// the EPMC's Newton tolerance (1e-8 relative, ten times it).
TEST(VibrationModeRom, ExactForTheOneHarmonicDuffingOscillator) {
  const double gamma = 1.0, c = 0.05, F = 0.3;
  const Eigen::MatrixXd T = Eigen::MatrixXd::Constant(1, 1, 1.0);
  const HarmonicBalance hb(
      Structure{Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd::Constant(1, 1, 1.0),
                Eigen::MatrixXd::Constant(1, 1, c)},
      {{make_polynomial_stiffness_element({.k3 = gamma}), T, "duffing"}},
      HarmonicBalanceOptions{{1}, 16});
  NonlinearModeOptions opt;
  opt.log10_amplitude_from = -2.0;
  opt.log10_amplitude_to = 0.5;
  const auto mode = nonlinear_mode(hb, opt, {0});
  ASSERT_TRUE(mode.continuation.complete);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(hb.unknowns());
  f(hb.index(0, static_cast<std::size_t>(hb.basis().index_of(1, 0)))) = F;
  // On the backbone's own points (no interpolation between them) the model is exact.
  const ModeRomCurve rom = nonlinear_mode_rom(hb, mode, f, {0}, 1);
  ASSERT_GT(rom.low_side_points, 3U);
  ASSERT_GT(static_cast<std::size_t>(rom.omega.size()), rom.low_side_points + 3);
  for (Eigen::Index i = 0; i < rom.omega.size(); ++i) {
    const double a = rom.amplitude(i), W = rom.omega(i);
    const double lhs = std::hypot(1.0 + 0.75 * gamma * a * a - W * W, c * W) * a;
    EXPECT_NEAR(lhs, F, 1e-8 * F) << "a = " << a << " W = " << W;
    EXPECT_NEAR(rom.output_amplitude(i, 0), a, 1e-12 * a);
  }
  // The low side lies below the backbone, the high side above it (the overhang of the
  // hardening response is on the high side, where W is not monotone along the curve).
  for (Eigen::Index i = 0; i < rom.omega.size(); ++i) {
    const double wb = std::sqrt(1.0 + 0.75 * gamma * rom.amplitude(i) * rom.amplitude(i));
    if (static_cast<std::size_t>(i) < rom.low_side_points) {
      EXPECT_LT(rom.omega(i), wb);
    } else {
      EXPECT_GT(rom.omega(i), wb);
    }
  }
  // The peak: a_max from (c W) a = F on the backbone W^2 = 1 + 3/4 gamma a^2 (where the two
  // sides meet). With 16 subdivisions of the 0.05-decade backbone intervals the amplitude
  // grid is 0.72 % wide, so the model's peak lies within 0.8 % below it; above it only by
  // the error of omega interpolated linearly in log a (~ (0.05 ln 10)^2 / 8 ~ 2e-3 of its
  // curvature term, at most 1e-3 of a_max here).
  double lo = 0.0, hi = 10.0;
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (lo + hi);
    (c * std::sqrt(1.0 + 0.75 * gamma * m * m) * m > F ? hi : lo) = m;
  }
  const ModeRomCurve fine = nonlinear_mode_rom(hb, mode, f, {0});
  EXPECT_LE(fine.peak_amplitude, lo * (1.0 + 1e-3));
  EXPECT_GT(fine.peak_amplitude, lo / 1.008);
  EXPECT_LE(rom.peak_amplitude, lo * (1.0 + 1e-9));  // the coarse grid: below
  // A force too small for the backbone's first amplitude (a = 0.01 needs F >= c w a =
  // 5e-4): no point, and a warning that says what to change.
  const ModeRomCurve none = nonlinear_mode_rom(hb, mode, 1e-6 * f, {0});
  EXPECT_EQ(none.omega.size(), 0);
  ASSERT_EQ(none.warnings.size(), 1U);
  EXPECT_NE(none.warnings[0].find("drives no amplitude"), std::string::npos);
}

TEST(VibrationModeRom, BadInputIsRefused) {
  const HarmonicBalance hb(
      Structure{Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd::Constant(1, 1, 1.0), {}}, {},
      HarmonicBalanceOptions{{0, 1}, 8});
  NonlinearModeResult empty;
  EXPECT_NE(testing::invalid_input_message([&] {
              (void)nonlinear_mode_rom(hb, empty, Eigen::VectorXd::Ones(hb.unknowns()), {0});
            }).find("no points"),
            std::string::npos);
}

}  // namespace
}  // namespace asperity::vibration
