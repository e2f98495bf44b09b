// Reproduction of Tables 3.1-3.4 (micro- and nano-scale experiments of Varenberg et
// al., as modelled in chapter 3).
#include <gtest/gtest.h>

#include "../support.hpp"

#include <array>
#include <cmath>
#include <string>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/contact/material.hpp"

namespace asperity::contact {
namespace {

using asperity::testing::rel;

// Table 3.1: bearing-steel ball (R = 2.5 mm) on a hardened steel flat.
ContactPair micro_pair() {
  const Material ball{.E = 207e9, .nu = 0.3, .G = 82.7e9, .H = 6.83e9};
  const Material flat{.E = 207e9, .nu = 0.3, .G = 82.7e9, .H = 7.48e9};
  return ContactPair::combine(ball, flat, 2.5e-3);
}

// Table 3.3: silica microsphere (R = 1.55 um) on a silicon (100) flat.
ContactPair nano_pair() {
  const Material sphere{.E = 68.0e9, .nu = 0.19, .G = 28.0e9, .H = 4.8e9};
  const Material flat{.E = 112.4e9, .nu = 0.28, .G = 43.9e9, .H = 11.3e9};
  return ContactPair::combine(sphere, flat, 1.55e-6);
}

TEST(Table31, CombinedProperties) {
  const auto p = micro_pair();
  // Table 3.1 "Combined" row, printed to 3-4 digits.
  EXPECT_LT(rel(p.E_star, 113.8e9), 5e-3);
  EXPECT_LT(rel(p.G_star, 24.3e9), 5e-3);
  EXPECT_DOUBLE_EQ(p.R, 2.5e-3);
  EXPECT_DOUBLE_EQ(p.H, 6.83e9);  // softer material (the ball)
  EXPECT_DOUBLE_EQ(p.nu, 0.3);
}

TEST(Table32, CriticalValuesWithinHalfPercent) {
  // Section 3.5 text: omega_c = 7.41 um, a_c = 0.136 mm, P_c = 152.8 N (Eq. 3.5).
  const auto c = micro_pair().critical();
  EXPECT_LT(rel(c.omega_c, 7.41e-6), 5e-3);
  EXPECT_LT(rel(c.a_c, 0.136e-3), 5e-3);
  EXPECT_LT(rel(c.P_c, 152.8), 5e-3);
}

struct Table32Row {
  double P;
  double omega_star;
  std::array<double, 4> mu;  // CFC, CEB, KE, BKE
  double stiffness;          // 8 G* a [N/m], section 3.5 text
};

// The thesis evaluates every model at the Hertzian omega* of the row (0.374, 0.283),
// so the check uses that interference for all four.
class Table32 : public ::testing::TestWithParam<Table32Row> {};

TEST_P(Table32, FrictionCoefficientsWithinOnePercent) {
  const auto row = GetParam();
  const auto pair = micro_pair();
  const FrictionParameters params{.mu_cfc = 0.284};  // AISI 304N, s/H (section 3.3)
  const auto hertz = PartialSlipModel::from_load(pair, ModelName::cfc, row.P, params);
  EXPECT_LT(rel(hertz.omega_star(), row.omega_star), 5e-3);
  for (std::size_t i = 0; i < kAllModels.size(); ++i) {
    const auto m =
        PartialSlipModel::from_interference_star(pair, kAllModels[i], hertz.omega_star(), params);
    // KE: the thesis's values are ~0.7 % below B.12 (SEED_NOTES.md); 1 % covers it.
    EXPECT_LT(rel(m.mu(), row.mu[i]), 1e-2) << to_string(kAllModels[i]) << " mu = " << m.mu();
  }
}

TEST_P(Table32, StiffnessWithinOnePercent) {
  const auto row = GetParam();
  const auto m = PartialSlipModel::from_load(micro_pair(), ModelName::cfc, row.P,
                                             FrictionParameters{.mu_cfc = 0.284});
  EXPECT_LT(rel(m.K_T(), row.stiffness), 1e-2);
}

TEST_P(Table32, HertzReadingKeepsTheLoadAndGivesTheThesisStiffness) {
  // The reading `asperity sphere` uses by default (InterferenceReading::hertz): every
  // model at P as given with Hertz's omega and a (section 3.5: "the penetration for all
  // the models is estimated to be 2.77 um"), so mu is Table 3.2's and 8 G* a is the
  // text's 16.17 / 14.06 N/um for all four models, BKE included.
  const auto row = GetParam();
  const FrictionParameters params{.mu_cfc = 0.284};
  for (std::size_t i = 0; i < kAllModels.size(); ++i) {
    const auto m = PartialSlipModel::from_load(micro_pair(), kAllModels[i], row.P, params,
                                               InterferenceReading::hertz);
    EXPECT_EQ(m.reading(), InterferenceReading::hertz);
    EXPECT_EQ(m.P(), row.P);
    EXPECT_LT(rel(m.omega_star(), row.omega_star), 5e-3) << to_string(kAllModels[i]);
    EXPECT_LT(rel(m.mu(), row.mu[i]), 1e-2) << to_string(kAllModels[i]) << " mu = " << m.mu();
    EXPECT_LT(rel(m.K_T(), row.stiffness), 1e-2) << to_string(kAllModels[i]);
    // Same state from the interference: P back to the given load (B.1), to round-off.
    const auto again = PartialSlipModel::from_interference_star(
        micro_pair(), kAllModels[i], m.omega_star(), params, InterferenceReading::hertz);
    EXPECT_LT(rel(again.P(), row.P), 1e-14);
    EXPECT_LT(rel(again.a(), m.a()), 1e-14);
  }
}

TEST_P(Table32, OwnNormalLawStaysClose) {
  // With each model's own normal law the interference differs slightly (BKE's elastic
  // branch is scaled by l_c/delta_c^1.5 = 1.026); mu then moves by < 1.5 %.
  const auto row = GetParam();
  for (std::size_t i = 0; i < kAllModels.size(); ++i) {
    const auto m = PartialSlipModel::from_load(micro_pair(), kAllModels[i], row.P,
                                               FrictionParameters{.mu_cfc = 0.284});
    EXPECT_LT(rel(m.mu(), row.mu[i]), 1.5e-2) << to_string(kAllModels[i]);
    EXPECT_NEAR(m.P(), row.P, 1e-9 * row.P);
  }
}

TEST(InterferenceReading, ParsesItsNames) {
  EXPECT_EQ(parse_interference_reading("hertz"), InterferenceReading::hertz);
  EXPECT_EQ(parse_interference_reading("own"), InterferenceReading::own);
  EXPECT_EQ(to_string(InterferenceReading::hertz), "hertz");
  const auto msg =
      asperity::testing::invalid_input_message([] { (void)parse_interference_reading("Hertz"); });
  EXPECT_NE(msg.find("hertz, own"), std::string::npos) << msg;
}

INSTANTIATE_TEST_SUITE_P(
    MicroScale, Table32,
    ::testing::Values(Table32Row{35.0, 0.374, {0.284, 0.528, 0.858, 1.444}, 16.17e6},
                      Table32Row{23.0, 0.283, {0.284, 0.626, 0.992, 1.639}, 14.06e6}),
    [](const auto& param_info) { return param_info.index == 0 ? "Exp1_35N" : "Exp2_23N"; });

TEST(Table33, CriticalValues) {
  // Section 3.5 text: omega_c = 12.67 nm, a_c = 0.14 um, P_c = 105.9 uN.
  const auto c = nano_pair().critical();
  EXPECT_LT(rel(c.omega_c, 12.67e-9), 5e-2);
  EXPECT_LT(rel(c.a_c, 0.14e-6), 5e-2);
  EXPECT_LT(rel(c.P_c, 105.9e-6), 5e-2);
}

TEST(Table34, NanoScaleFrictionCoefficients) {
  // Table 3.4: omega* = 0.048 and 0.051 for P = 1.1 and 1.2 uN, mu (CFC, CEB, KE, BKE).
  // CFC uses mu = 0.259 (silica s/H, section 3.5). The thesis's combined E* (44.7 GPa)
  // and omega_c are reproduced within 5 %, mu within 5 % (docs/asperity_scale.md: the
  // thesis used nu = 0.2 here; with 0.19 KE and BKE are 2-3.4 % below the table).
  const auto pair = nano_pair();
  const FrictionParameters params{.mu_cfc = 0.259};
  struct Row {
    double P;
    double omega_star;
    std::array<double, 4> mu;
  };
  for (const Row& row : {Row{1.1e-6, 0.048, {0.259, 1.769, 2.498, 3.077}},
                         Row{1.2e-6, 0.051, {0.259, 1.714, 2.424, 2.996}}}) {
    const auto hertz = PartialSlipModel::from_load(pair, ModelName::cfc, row.P, params);
    EXPECT_LT(rel(hertz.omega_star(), row.omega_star), 5e-2) << hertz.omega_star();
    for (std::size_t i = 0; i < kAllModels.size(); ++i) {
      const auto m =
          PartialSlipModel::from_interference_star(pair, kAllModels[i], row.omega_star, params);
      EXPECT_LT(rel(m.mu(), row.mu[i]), 5e-2) << to_string(kAllModels[i]) << " mu = " << m.mu();
    }
  }
}

}  // namespace
}  // namespace asperity::contact
