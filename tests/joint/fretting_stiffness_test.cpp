// The pooled fit of the branches after the reversals (section 6.3, AnalysisOptions):
// branches that are exactly v = a_rev + b_cycle u + c2 u^2 + c3 u^3 give back b_cycle, and a
// cycle whose branches cannot determine a slope leaves the others fitted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "../../src/joint/fretting_stiffness.hpp"

namespace asperity::joint::detail {
namespace {

struct Branches {
  std::vector<double> x, y, x0, Qs;
  std::vector<Reversal> revs;
};

// One branch of n samples after a reversal at x_r: u = dir (x - x_r) from 0 to u_max
// (moving = false: the displacement stays at x_r), y = dir v(u) with v the polynomial.
void add_branch(Branches& b, std::size_t cycle, int dir, double x_r, double a, double slope,
                double c2, double c3, bool moving) {
  constexpr std::size_t n = 40;
  constexpr double u_max = 2e-6;  // [m], a fretting branch's displacement scale
  const std::size_t r = b.x.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double u = moving ? u_max * static_cast<double>(i) / (n - 1) : 0.0;
    b.x.push_back(x_r + dir * u);
    b.y.push_back(dir * (a + slope * u + c2 * u * u + c3 * u * u * u));
    b.x0.push_back(x_r);
    b.Qs.push_back(0.0);  // every sample within the window's force span
  }
  b.revs.push_back(Reversal{r, r + n - 1, dir, 1.0, cycle});
}

// Common shape (c2, c3) and per-cycle slopes of the order of a steel joint's 5e8 N/m.
constexpr double kC2 = -4e13, kC3 = 3e18;

TEST(FrettingStiffnessFit, ExactBranchesGiveTheirSlopes) {
  const std::vector<double> slopes = {5e8, 4.5e8, 5.5e8};
  Branches b;
  for (std::size_t c = 0; c < slopes.size(); ++c) {
    add_branch(b, c, -1, 1e-6, 80.0, slopes[c], kC2, kC3, true);
    add_branch(b, c, +1, -1e-6, -80.0 + double(c), slopes[c], kC2, kC3, true);
  }
  const auto fit = fit_reversals(b.x, b.y, b.x0, b.Qs, b.revs, slopes.size(), 3);
  // The data are the model exactly; what is left is the rounding of the QR solves on u in
  // [0, 1] (measured below 1e-13 of the slope, the standard error likewise): 1e-11 relative.
  for (std::size_t c = 0; c < slopes.size(); ++c) {
    EXPECT_NEAR(fit.cycle_slope[c], slopes[c], 1e-11 * slopes[c]) << "cycle " << c;
    EXPECT_NEAR(fit.reversal_slope[2 * c], slopes[c], 1e-11 * slopes[c]);
    EXPECT_NEAR(fit.reversal_slope[2 * c + 1], slopes[c], 1e-11 * slopes[c]);
    // Zero residuals: the slope's standard error is rounding.
    EXPECT_LT(std::sqrt(fit.cycle_slope_var[c]), 1e-11 * slopes[c]);
  }
}

TEST(FrettingStiffnessFit, CycleWithoutMotionLeavesTheOthersFitted) {
  Branches b;
  add_branch(b, 0, -1, 1e-6, 80.0, 5e8, kC2, kC3, true);
  add_branch(b, 0, +1, -1e-6, -80.0, 5e8, kC2, kC3, true);
  // Cycle 1: the displacement does not move after either reversal (u = 0 throughout), so
  // its slope is not determined (its local design has rank 2 of 3).
  add_branch(b, 1, -1, 1e-6, 80.0, 5e8, kC2, kC3, false);
  add_branch(b, 1, +1, -1e-6, -80.0, 5e8, kC2, kC3, false);
  const auto fit = fit_reversals(b.x, b.y, b.x0, b.Qs, b.revs, 2, 3);
  EXPECT_NEAR(fit.cycle_slope[0], 5e8, 1e-11 * 5e8);  // as in ExactBranchesGiveTheirSlopes
  EXPECT_TRUE(std::isnan(fit.cycle_slope[1]));
  EXPECT_TRUE(std::isnan(fit.reversal_slope[2]));
  EXPECT_TRUE(std::isnan(fit.reversal_slope[3]));
}

}  // namespace
}  // namespace asperity::joint::detail
