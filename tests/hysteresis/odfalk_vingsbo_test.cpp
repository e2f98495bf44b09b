// The Odfalk-Vingsbo elastic-plastic law (thesis Eq. 3.10) on a Cattaneo-Mindlin contact,
// the superposition of Fig. 3.3.
#include "asperity/hysteresis/odfalk_vingsbo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "asperity/contact/mindlin.hpp"
#include "asperity/core/error.hpp"
#include "asperity/hysteresis/backbones.hpp"

namespace asperity::hysteresis {
namespace {

// Micro-scale experiment 1 of Table 3.2 with CEB's mu (as masing_test.cpp): Q_max = 18.5 N.
contact::MindlinContact mindlin() {
  return contact::MindlinContact(0.528, 35.0, 24.32e9, 83.25e-6);
}

// Q_ty at 30 % of mu P, k_p at a tenth of the elastic stiffness 8 G* a (16.2 N/um): the
// plastic slip is then of the order of the elastic one (Fig. 3.3's proportions).
OdfalkVingsboParameters parameters() {
  const auto c = mindlin();
  return {.fretting_yield_point = 0.3 * c.Q_max(), .hardening_coefficient = 0.1 * c.stiffness()};
}

// Eq. 3.10 as printed, on the unloading branch of a cycle of amplitude Q_m (dQ/dt < 0).
double eq_3_10_unloading(double Q, double Q_m, double Q_ty, double k_p) {
  const double beta = Q_m > Q_ty ? 1.0 : 0.0;
  const double dQdt = -1.0;
  const double gamma = (std::abs(Q) > Q_ty && dQdt * Q > 0.0) ? 1.0 : 0.0;
  return beta * (gamma * (Q + Q_ty) / k_p + (Q_m - Q_ty) / (2.0 * k_p));
}

std::vector<double> segment(double a, double b, int n) {
  std::vector<double> out;
  for (int i = 1; i <= n; ++i) out.push_back(a + (b - a) * i / n);
  return out;
}

TEST(OdfalkVingsbo, ForceCycleIsMindlinPlusEq3_10) {
  // Fig. 3.3: the elastic-plastic loop sums Mindlin's displacement (Eq. 3.8/3.9, B.16/B.17)
  // and the parallelogram (Eq. 3.10) at the same force. Reference: both closed forms; 1e-12
  // of the amplitude covers the rounding of the Masing branches.
  const auto c = mindlin();
  const auto p = parameters();
  const double Q_m = 0.8 * c.Q_max();
  OdfalkVingsboHysteresis h(std::make_shared<MindlinBackbone>(c), p);
  for (double Q : segment(0.0, Q_m, 40)) h.update_force(Q);
  const double x_m = h.x();
  for (double Q : segment(Q_m, -Q_m, 80)) {
    const double expected =
        c.unloading_displacement(Q, Q_m) +
        eq_3_10_unloading(Q, Q_m, p.fretting_yield_point, p.hardening_coefficient);
    EXPECT_NEAR(h.update_force(Q), expected, 1e-12 * x_m) << "unloading, Q = " << Q;
    EXPECT_NEAR(odfalk_vingsbo_plastic_slip(p, Q, Q_m, true),
                eq_3_10_unloading(Q, Q_m, p.fretting_yield_point, p.hardening_coefficient),
                1e-15 * x_m);
  }
  // Reloading: Eq. 3.9 and Eq. 3.10's mirror image (gamma = 1 for Q > Q_ty, dQ/dt > 0).
  for (double Q : segment(-Q_m, Q_m, 80)) {
    const double expected =
        c.reloading_displacement(Q, Q_m) -
        eq_3_10_unloading(-Q, Q_m, p.fretting_yield_point, p.hardening_coefficient);
    EXPECT_NEAR(h.update_force(Q), expected, 1e-12 * x_m) << "reloading, Q = " << Q;
  }
  // The plastic range is (Q_m - Q_ty)/k_p, centred (Eq. 3.10 at Q = +-Q_m).
  EXPECT_NEAR(h.x(), x_m, 1e-12 * x_m);
  EXPECT_GT(h.plastic_slip(), 0.0);
}

TEST(OdfalkVingsbo, DisplacementCycleMatchesTheClosedForms) {
  // Displacement-driven: the force amplitude solves x_m = x_l(Q_m) + (Q_m - Q_ty)/(2 k_p)
  // and the loop's area is Mindlin's energy (B.18 at the elastic amplitude) plus the
  // parallelogram's (Q_m^2 - Q_ty^2)/k_p; in partial slip and in gross slip (Q_m = mu P).
  const auto c = mindlin();
  const auto p = parameters();
  const double Q_ty = p.fretting_yield_point, k_p = p.hardening_coefficient;
  const auto bb = std::make_shared<MindlinBackbone>(c);
  for (const double plastic : {0.2, 0.5}) {
    SCOPED_TRACE(plastic);
    const double x_m = 0.6 * c.slip_displacement() + plastic * c.Q_max() / k_p;
    const auto cycle = odfalk_vingsbo_cycle(*bb, p, x_m);
    ASSERT_GT(cycle.Q_m, Q_ty);
    const bool gross = plastic == 0.5;  // (0.5 - 0.35) Q_max/k_p > 0.4 slip displacements
    if (gross) {
      EXPECT_EQ(cycle.Q_m, c.Q_max());
    } else {
      // The amplitude equation, through the closed-form inverse of B.15 (1e-12: rounding).
      EXPECT_NEAR(c.loading_displacement(cycle.Q_m) + (cycle.Q_m - Q_ty) / (2.0 * k_p), x_m,
                  1e-12 * x_m);
    }
    const double x_e = x_m - (cycle.Q_m - Q_ty) / (2.0 * k_p);
    const double W = c.energy_per_cycle(x_e) + (cycle.Q_m * cycle.Q_m - Q_ty * Q_ty) / k_p;
    EXPECT_NEAR(cycle.energy, W, 1e-10 * W);  // energy_per_cycle's quadrature, ~1e-12

    OdfalkVingsboHysteresis h(bb, p);
    for (double x : segment(0.0, x_m, 200)) h.update(x);
    EXPECT_NEAR(h.Q(), cycle.Q_m, 1e-12 * cycle.Q_m);
    // One closed loop, its area by the trapezoidal rule: 4000 points per branch put the
    // error of the kinks at Q = -+Q_ty and of the curvature below 1e-5 of W.
    double area = 0.0, x0 = h.x(), Q0 = h.Q();
    for (const auto& [a, b] : {std::pair{x_m, -x_m}, std::pair{-x_m, x_m}}) {
      for (double x : segment(a, b, 4000)) {
        const double Q = h.update(x);
        area += 0.5 * (Q + Q0) * (x - x0);
        x0 = x;
        Q0 = Q;
      }
      if (a > 0.0) {
        EXPECT_NEAR(h.Q(), -cycle.Q_m, 1e-12 * cycle.Q_m);  // symmetric loop
      }
    }
    EXPECT_NEAR(std::abs(area), W, 1e-5 * W);
    EXPECT_NEAR(h.Q(), cycle.Q_m, 1e-12 * cycle.Q_m);
  }
}

TEST(OdfalkVingsbo, BelowTheYieldPointItIsMindlin) {
  // beta = 0 for Q_m <= Q_ty: the loop is Mindlin's (Masing on B.15), to rounding.
  const auto c = mindlin();
  const auto p = parameters();
  const double x_m = 0.5 * c.loading_displacement(p.fretting_yield_point);
  const auto bb = std::make_shared<MindlinBackbone>(c);
  OdfalkVingsboHysteresis h(bb, p);
  Hysteresis m(bb);
  std::vector<double> path = segment(0.0, x_m, 20);
  for (double x : segment(x_m, -x_m, 40)) path.push_back(x);
  for (double x : path) EXPECT_NEAR(h.update(x), m.update(x), 1e-12 * c.Q_max()) << x;
  EXPECT_EQ(h.plastic_slip(), 0.0);
}

TEST(OdfalkVingsbo, ParametersMustBeGiven) {
  // The law has no default for its experimental parameters: zero (unset) is refused,
  // naming the field.
  const auto bb = std::make_shared<MindlinBackbone>(mindlin());
  try {
    OdfalkVingsboHysteresis h(bb, OdfalkVingsboParameters{.fretting_yield_point = 1.0});
    FAIL() << "k_p = 0 accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("hardening_coefficient"), std::string::npos) << e.what();
  }
  EXPECT_THROW(
      OdfalkVingsboHysteresis(bb, {.fretting_yield_point = -1.0, .hardening_coefficient = 1e6}),
      InvalidInput);
  OdfalkVingsboHysteresis h(bb, parameters());
  EXPECT_THROW(h.update(std::numeric_limits<double>::quiet_NaN()), InvalidInput);
}

}  // namespace
}  // namespace asperity::hysteresis
