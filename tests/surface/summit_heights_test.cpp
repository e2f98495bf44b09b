// A measured summit-height table in the Greenwood-Williamson sums (Eq. 4.4-4.14 with the
// table's density in place of Eq. 4.2): the table's own statistics, closed forms over a
// uniform density, and a finely sampled Gaussian against the Gaussian sums.
#include <gtest/gtest.h>

#include "../support.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/fem/reduced_model.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "asperity/surface/summit_heights.hpp"

namespace asperity::surface {
namespace {

using asperity::testing::rel;
using contact::ModelName;

TEST(SummitHeightTable, TriangleHasItsClosedFormMoments) {
  // Triangle on [0, 2] um peaking at 1: mean 1, variance (0 + 4 + 1 - 0 - 0 - 2)/18 = 1/6
  // (the triangular distribution's closed form); the density may be given in any scale.
  const SummitHeightTable t({0.0, 1e-6, 2e-6}, {0.0, 7.0, 0.0}, "triangle");
  EXPECT_LT(rel(t.mean(), 1e-6), 1e-15);
  EXPECT_LT(rel(t.standard_deviation(), 1e-6 / std::sqrt(6.0)), 1e-14);
  // Standardized: unit integral and the peak density sd * 1/(1 um).
  EXPECT_LT(rel(t.density(0.0), 1.0 / std::sqrt(6.0)), 1e-14);
  EXPECT_LT(rel(t.survival(0.0), 0.5), 1e-14);
  EXPECT_EQ(t.survival(t.bottom() - 1.0), 1.0);
  EXPECT_EQ(t.survival(t.top()), 0.0);
  EXPECT_EQ(t.density(t.top() + 1e-9), 0.0);
  // Survival of the upper half-triangle from z: (1 - s)^2 / 2 with s = (z - 1 um)/(1 um).
  const double z_star = 0.5 * std::sqrt(6.0);  // z = 1.5 um
  EXPECT_LT(rel(t.survival(z_star), 0.125), 1e-14);
}

TEST(SummitHeightTable, ZeroRunsAtTheEndsAreDroppedButNotInsideTheSupport) {
  // Zero runs at either end go (one zero row kept); zeros next to a positive end row stay.
  const SummitHeightTable ends({0, 1, 2, 3, 4, 5, 6}, {0, 0, 1, 1, 0, 0, 0}, "ends");
  ASSERT_EQ(ends.z_star().size(), 4u);
  EXPECT_EQ(ends.density_star().front(), 0.0);
  EXPECT_EQ(ends.density_star().back(), 0.0);
  const SummitHeightTable inside({0, 1, 2, 3}, {1, 0, 0, 1}, "inside");
  ASSERT_EQ(inside.z_star().size(), 4u);
  // Symmetric: mean 1.5; the density is 0 on [1, 2] and the survival at the mean is 1/2.
  EXPECT_EQ(inside.density(0.0), 0.0);
  EXPECT_GT(inside.density(inside.top()), 0.0);
  EXPECT_LT(rel(inside.survival(0.0), 0.5), 1e-14);
}

TEST(SummitHeightTable, WhatIsNotADistributionIsRefusedByName) {
  auto message = [](const std::vector<double>& z, const std::vector<double>& p) {
    return asperity::testing::invalid_input_message(
        [&] { const SummitHeightTable t(z, p, "\"s.mat\""); });
  };
  auto contains = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  };
  EXPECT_TRUE(contains(message({0, 1}, {1, 1}), "\"s.mat\" is not a distribution: 2 points"))
      << message({0, 1}, {1, 1});
  EXPECT_TRUE(contains(message({0, 1, 2}, {1, 1}), "3 heights but 2 densities"))
      << message({0, 1, 2}, {1, 1});
  EXPECT_TRUE(contains(message({0, 1, 1}, {1, 1, 1}), "heights must increase"))
      << message({0, 1, 1}, {1, 1, 1});
  EXPECT_TRUE(contains(message({0, 2, 1}, {1, 1, 1}), "heights must increase"))
      << message({0, 2, 1}, {1, 1, 1});
  EXPECT_TRUE(contains(message({0, 1, 2}, {1, -0.5, 1}), "density -0.5 at point 2"))
      << message({0, 1, 2}, {1, -0.5, 1});
  EXPECT_TRUE(contains(message({0, 1, 2}, {0, 0, 0}), "zero everywhere"))
      << message({0, 1, 2}, {0, 0, 0});
  EXPECT_TRUE(contains(message({0, NAN, 2}, {1, 1, 1}), "point 2"))
      << message({0, NAN, 2}, {1, 1, 1});
  EXPECT_TRUE(contains(message({0, 1, 2}, {1, INFINITY, 1}), "not finite"))
      << message({0, 1, 2}, {1, INFINITY, 1});
}

// CEB flat over a uniform density on [-sqrt 3, sqrt 3] (unit standard deviation): while
// every contacting asperity is elastic (z* - d* <= omega_c*), P/P_c = w^{3/2} and
// (a/a_c)^2 = w (B.2, B.6), so Eq. 4.4 integrates in closed form:
// P* = (2 pi/3) beta omega_c* Int_0^{s} (u/omega_c*)^{3/2} du / (2 sqrt 3)
//    = (2 pi/3) beta omega_c*^{-1/2} (2/5) s^{5/2} / (2 sqrt 3),  s = sqrt 3 - d*,
// A_r/A0 = pi beta omega_c* Int_0^s (u/omega_c*) du / (2 sqrt 3) = pi beta s^2 / (4 sqrt 3).
RoughFlat uniform_flat(ModelName model) {
  const double r3 = std::sqrt(3.0);
  RoughFlatParameters p{.model = model,
                        .beta = 0.04,
                        .psi = 0.5,  // omega_c* = 4 > 2 sqrt 3: all elastic for d* >= -sqrt 3
                        .nu = 0.3,
                        .G_over_E = 0.7 / 3.4,
                        .friction = {.mu_cfc = 0.3},
                        .summit_sigma = true};
  p.summit_heights = std::make_shared<const SummitHeightTable>(
      std::vector<double>{-r3, 0.0, r3}, std::vector<double>{1.0, 1.0, 1.0}, "uniform");
  return RoughFlat(p);
}

TEST(SummitHeightTableFlat, UniformCebNormalLoadAndAreaAreTheClosedForms) {
  const auto flat = uniform_flat(ModelName::ceb);
  const double wc = flat.omega_c_star();
  ASSERT_DOUBLE_EQ(wc, 4.0);
  for (double d : {-1.5, -0.5, 0.0, 1.0, 1.65}) {
    const double s = std::sqrt(3.0) - d;
    const double P = 2.0 * std::numbers::pi / 3.0 * 0.04 / std::sqrt(wc) * 0.4 * std::pow(s, 2.5) /
                     (2.0 * std::sqrt(3.0));
    EXPECT_LT(rel(flat.normal_load_star(d), P), 1e-12) << d;
    EXPECT_LT(
        rel(flat.contact_area_ratio(d), std::numbers::pi * 0.04 * s * s / (4.0 * std::sqrt(3.0))),
        1e-12)
        << d;
    EXPECT_LT(rel(flat.contact_fraction(d), s / (2.0 * std::sqrt(3.0))), 1e-14) << d;
    // An elastic flat unloads along its loading curve (normal_load_after_set_star).
    EXPECT_LT(rel(flat.normal_load_after_set_star(d + 0.05, d), flat.normal_load_star(d + 0.05)),
              1e-12)
        << d;
  }
  // Above the highest summit nothing touches.
  EXPECT_EQ(flat.normal_load_star(1.8), 0.0);
  EXPECT_EQ(flat.static_friction_star(1.8), 0.0);
  EXPECT_EQ(flat.contact_fraction(1.8), 0.0);
}

TEST(SummitHeightTableFlat, CfcStaticFrictionIsMuTimesLoad) {
  // Eq. 4.7 with a constant mu = 0.3 (CFC): Q*_max = 0.3 P* over any height density.
  const auto flat = uniform_flat(ModelName::cfc);
  for (double d : {-1.0, 0.5}) {
    EXPECT_LT(rel(flat.static_friction_star(d), 0.3 * flat.normal_load_star(d)), 1e-12);
  }
}

// The Gaussian of Eq. 4.2 sampled every h = 0.002 on [-8.5, 8.5] as a table: the linear
// interpolation's error, h^2/8 |phi''|, is ~5e-7 of phi near the peak and grows like z^2
// in the tail (~1e-5 at z* = 4, 3e-5 at z* = 6), so the sums over the upper tail the
// contact samples agree with the Gaussian ones to ~1e-5 relative.
RoughFlat gaussian_flat(ModelName model, bool as_table) {
  RoughFlatParameters p{.model = model,
                        .beta = 0.04,
                        .psi = 0.5,
                        .nu = 0.3,
                        .G_over_E = 0.7 / 3.4,
                        .friction = {.mu_cfc = 0.3},
                        .summit_sigma = true};
  if (as_table) {
    std::vector<double> z, phi;
    for (int k = -4250; k <= 4250; ++k) {
      z.push_back(0.002 * k);
      phi.push_back(std::exp(-0.5 * z.back() * z.back()));
    }
    p.summit_heights = std::make_shared<const SummitHeightTable>(z, phi, "sampled Gaussian");
  }
  return RoughFlat(p);
}

TEST(SummitHeightTableFlat, SampledGaussianGivesTheGaussianSums) {
  for (auto model : {ModelName::ceb, ModelName::bke}) {
    const auto exact = gaussian_flat(model, false);
    const auto table = gaussian_flat(model, true);
    EXPECT_LT(std::abs(table.summit_heights()->standard_deviation() - 1.0), 1e-6);
    const double d = exact.separation_star(1e-3);
    EXPECT_LT(rel(table.separation_star(1e-3), d), 1e-5);
    constexpr double kTol = 3e-5;  // the interpolation error above, at z* up to 6
    EXPECT_LT(rel(table.normal_load_star(d), exact.normal_load_star(d)), kTol);
    EXPECT_LT(rel(table.static_friction_star(d), exact.static_friction_star(d)), kTol);
    EXPECT_LT(rel(table.contact_area_ratio(d), exact.contact_area_ratio(d)), kTol);
    EXPECT_LT(rel(table.contact_fraction(d), exact.contact_fraction(d)), kTol);
    EXPECT_LT(rel(table.stiffness_star(d), exact.stiffness_star(d)), kTol);
    for (double delta : {0.01, 0.1, 0.5}) {
      EXPECT_LT(rel(table.loading_force_star(delta, d), exact.loading_force_star(delta, d)), kTol);
      EXPECT_LT(rel(table.energy_star(delta, d), exact.energy_star(delta, d)), kTol);
    }
    EXPECT_LT(rel(table.normal_load_after_set_star(d + 0.2, d),
                  exact.normal_load_after_set_star(d + 0.2, d)),
              kTol);
    // The tabulated backbone (the fixed-rule sums) over the table against the table's own
    // adaptive sums: the table's verified bound, 1e-9.
    const auto backbone = table.backbone(d, 1e-9);
    for (double delta : {0.003, 0.05, 0.4}) {
      EXPECT_LT(rel(backbone->force(delta), table.loading_force_star(delta, d)), 2e-9) << delta;
    }
  }
}

// A measured table is a histogram: its density has a kink at every node. Where a slip
// boundary crosses a node the fixed-rule sums of the tabulated backbone change their pieces;
// the backbone must still verify its 1e-9 bound and agree with the adaptive sums. (With
// Gauss-Legendre on the piece next to a cut, which missed the root singularity just
// outside it, the sums jumped by 5e-9 and the table over the measured BRB surface with
// steel at 5.8 GPa could not be built.)
TEST(SummitHeightTableFlat, MeasuredTableGivesVerifiedBackbones) {
  const std::string path =
      std::string(ASPERITY_TEST_DATA_DIR) + "/../../examples/brb/brb_surface_data.mat";
  const auto column = [&](const char* name) {
    const Eigen::MatrixXd m = fem::read_mat_matrix(path, name);
    return std::vector<double>(m.reshaped().begin(), m.reshaped().end());
  };
  std::vector<double> z = column("normzinterp");
  const double z_max = fem::read_mat_matrix(path, "z_max")(0, 0);
  for (double& v : z) v *= z_max;
  auto table = std::make_shared<const SummitHeightTable>(z, column("pzinterp"), "BRB");
  const contact::Material steel{.E = 200e9, .nu = 0.29, .G = 0.0, .H = 5.8e9};
  const double Re = fem::read_mat_matrix(path, "Re")(0, 0);
  const double eta = fem::read_mat_matrix(path, "area_density")(0, 0);
  const auto flat = RoughFlat::from_summit_heights(steel, steel, table->standard_deviation(), eta,
                                                   Re, 1.0, ModelName::bke, {}, table);
  for (double p_Pa : {1e5, 1e6, 4e6, 1e7, 3.5e7}) {
    const double d = flat.separation_star(p_Pa / flat.scales()->force);
    const auto backbone = flat.backbone(d, 1e-9);
    for (double delta : {0.002, 0.02, 0.07, 0.3}) {
      EXPECT_LT(rel(backbone->force(delta), flat.loading_force_star(delta, d)), 2e-9)
          << p_Pa << " Pa, delta* " << delta;
    }
    EXPECT_LT(rel(backbone->limit(), flat.static_friction_star(d)), 1e-12) << p_Pa;
  }
}

TEST(SummitHeightTableFlat, TableNeedsTheSummitLengthScale) {
  RoughFlatParameters p = gaussian_flat(ModelName::bke, true).parameters();
  p.summit_sigma = false;
  p.beta = 0.04;
  EXPECT_THROW(RoughFlat{p}, InvalidInput);
}

}  // namespace
}  // namespace asperity::surface
