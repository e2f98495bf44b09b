// Quasi-static fretting of a gripped joint (vibration/quasi_static_fretting.hpp) on a model
// with a closed-form answer: one rough-contact element in series with a body spring k_b and
// the apparatus spring k, the tangential motion along t1 only. Then the element's loop is the
// rough flat's Masing loop at its prestress pressure, and the series gives
//   Delta_0 = Q_0 / k + Q_0 / k_b + x_0(Q_0)   (x_0: the virgin curve's inverse, Masing's
//                                                loop tip on the virgin curve),
//   W = 8 int_0^x0 Q_b dx - 4 x_0 Q_0           (Masing's energy identity),
// the springs being elastic (they add no area).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>

#include "../support.hpp"
#include "asperity/core/error.hpp"
#include "asperity/vibration/quasi_static_fretting.hpp"
#include "asperity/vibration/rough_contact.hpp"
#include "element_test_support.hpp"

namespace asperity::vibration {
namespace {

using testing::rel;

constexpr double kPressure = 20e6;  // [Pa]
constexpr double kArea = 4e-6;      // [m^2]
constexpr double kDrive = 38e6;     // [N/m], Fig. 5.7's PZT side
constexpr double kBody = 100e6;     // [N/m], the bodies between the interface and z

std::shared_ptr<const RoughContactElement> element() {
  const RoughInterfaceParameters p = test_support::table_7_2();
  const auto s = std::make_shared<const RoughContactSurface>(p, kPressure / 4.0, kPressure * 4.0);
  return std::make_shared<const RoughContactElement>(s, kArea, kPressure, "test element");
}

// x = [g_t1, g_t2, g_n, z]: the body spring between z and g_t1, stiff springs on g_t2 and
// g_n (their loads stay zero: a tangential push along t1 changes no normal load).
fem::GrippedJoint series_joint() {
  fem::GrippedJoint j;
  j.drive_dof = 3;
  j.drive_stiffness = kDrive;
  auto& m = j.model;
  m.K = Eigen::MatrixXd::Zero(4, 4);
  m.K(0, 0) = m.K(3, 3) = kBody;
  m.K(0, 3) = m.K(3, 0) = -kBody;
  m.K(3, 3) += kDrive;
  m.K(1, 1) = m.K(2, 2) = 1e9;
  m.M = Eigen::MatrixXd::Identity(4, 4);
  m.Q = Eigen::MatrixXd::Identity(3, 4);
  return j;
}

std::vector<PlacedElement> placed(const std::shared_ptr<const RoughContactElement>& e) {
  PlacedElement pe;
  pe.element = e;
  pe.T = Eigen::MatrixXd::Zero(3, 4);
  pe.T(0, 0) = pe.T(1, 1) = 1.0;
  pe.T(2, 2) = -1.0;
  pe.name = "joint";
  return {pe};
}

double virgin(const RoughContactElement& e, double x) {
  Eigen::VectorXd f;
  Eigen::MatrixXd K;
  e.static_response(Eigen::Vector3d(x, 0.0, 0.0), f, K);
  return f[0];
}

TEST(QuasiStaticFretting, SeriesJointFollowsTheRoughFlatsMasingLoop) {
  const auto e = element();
  const double Q_max = e->slip_force();
  // Tip amplitudes from a small loop to one near gross slip (Q_0/Q_max from ~0.05 to ~0.9).
  const double k_series = 1.0 / (1.0 / kDrive + 1.0 / kBody);
  std::vector<double> tips, Q0s, x0s;
  for (const double r : {0.05, 0.3, 0.6, 0.9}) {
    const double Q0 = r * Q_max;
    const double x0 =
        boost::math::tools::bisect([&](double x) { return virgin(*e, x) - Q0; }, 0.0, 1e-3,
                                   [](double a, double b) { return std::abs(b - a) < 1e-18; })
            .first;
    tips.push_back(Q0 / k_series + x0);
    Q0s.push_back(Q0);
    x0s.push_back(x0);
  }
  QuasiStaticFrettingOptions o;
  o.harmonics = 31;
  o.time_points = 512;
  o.tolerance = 1e-10;  // one element on a line: its response is smooth, Newton converges fully
  const auto r = quasi_static_fretting(series_joint(), placed(e), tips, o);
  // Stuck stiffness: k_b in series with the element's initial tangential stiffness.
  const double k_el = e->initial_stiffness()(0, 0);
  EXPECT_LT(rel(r.stiffness, 1.0 / (1.0 / kBody + 1.0 / k_el)), 1e-9);
  ASSERT_EQ(r.cycles.size(), tips.size());
  boost::math::quadrature::gauss_kronrod<double, 61> gk;
  for (std::size_t i = 0; i < tips.size(); ++i) {
    const auto& c = r.cycles[i];
    const double Q0 = Q0s[i], x0 = x0s[i];
    SCOPED_TRACE(::testing::Message() << "Q_0/Q_max = " << Q0 / Q_max);
    EXPECT_LE(c.residual, o.tolerance);
    // Never beyond the static limit, never negative work.
    EXPECT_LE(c.force.cwiseAbs().maxCoeff(), Q_max * (1.0 + 1e-9));
    EXPECT_GT(c.energy, 0.0);
    // Masing's energy identity. W depends only on the first harmonic of delta (W = -pi k
    // Delta_0 a_1); the truncation to H = 31 disturbs it through the harmonics it drops.
    // The loop's tip is read from samples of the truncated series, whose corner at each
    // reversal (coefficients ~ 1/h^2) it rounds. Measured: W within 4.0e-5, Q_0 within
    // 4.4e-5, delta_0 within 3.1e-5 (largest at Q_0/Q_max = 0.6-0.9); 2e-4 leaves a factor
    // of 5 for other platforms' rounding of the element's tables.
    const double W =
        8.0 * gk.integrate([&](double x) { return virgin(*e, x); }, 0.0, x0) - 4.0 * x0 * Q0;
    EXPECT_LT(rel(c.energy, W), 2e-4);
    EXPECT_LT(rel(c.force_amplitude, Q0), 2e-4);
    // delta = Q / k_b + g: the element's loop, sheared by the body spring.
    EXPECT_LT(rel(c.displacement_amplitude, Q0 / kBody + x0), 2e-4);
  }
}

// The same series joint at five harmonics, small enough to run under the sanitizers
// (scripts/test-full.sh leaves the H = 31 test above to the Release run): two cycles, from
// the stuck start and continued, that meet what every loop must.
TEST(QuasiStaticFretting, FewHarmonicsGiveClosedDissipatingCycles) {
  const auto e = element();
  const double Q_max = e->slip_force();
  QuasiStaticFrettingOptions o;
  o.harmonics = 5;
  o.time_points = 32;
  const double k_series = 1.0 / (1.0 / kDrive + 1.0 / kBody);
  const auto r = quasi_static_fretting(series_joint(), placed(e),
                                       {0.2 * Q_max / k_series, 0.5 * Q_max / k_series}, o);
  ASSERT_EQ(r.cycles.size(), 2u);
  for (const auto& c : r.cycles) {
    EXPECT_LE(c.residual, o.tolerance);
    EXPECT_GT(c.energy, 0.0);
    EXPECT_LE(c.force.cwiseAbs().maxCoeff(), Q_max * (1.0 + 1e-9));
    EXPECT_EQ(c.delta.size(), 32);
  }
  EXPECT_GT(r.cycles[1].energy, r.cycles[0].energy);
  EXPECT_GT(r.cycles[1].force_amplitude, r.cycles[0].force_amplitude);
}

TEST(QuasiStaticFretting, BadInputIsRefused) {
  const auto e = element();
  EXPECT_THROW((void)quasi_static_fretting(series_joint(), placed(e), {-1e-6}), InvalidInput);
  EXPECT_THROW((void)quasi_static_fretting(series_joint(), placed(e), {std::nan("")}),
               InvalidInput);
  QuasiStaticFrettingOptions o;
  o.harmonics = 0;
  EXPECT_THROW((void)quasi_static_fretting(series_joint(), placed(e), {1e-6}, o), InvalidInput);
  o.harmonics = 7;
  o.time_points = 10;
  EXPECT_THROW((void)quasi_static_fretting(series_joint(), placed(e), {1e-6}, o), InvalidInput);
}

}  // namespace
}  // namespace asperity::vibration
