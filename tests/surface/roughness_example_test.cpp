// The shipped example (examples/roughness): synthetic scans of the two milled halves
// turn into the "before experiments" columns of Table 5.4 through the same pipeline
// as `asperity roughness` (line levelling, lc = 0.8 mm, ls = 20 um, Eq. 5.1 with the
// geometric rule, moments added).
#include <gtest/gtest.h>

#include <string>

#include "asperity/contact/material.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/roughness.hpp"

namespace asperity::surface {
namespace {

constexpr double um = 1e-6;
const std::string kExamples = std::string(ASPERITY_TEST_DATA_DIR) + "/../../examples/roughness/";

SpectralMoments half(const std::string& name) {
  const GaussianFilter f{};
  const auto mx =
      process_profile(read_profile_text(kExamples + name + "_max.csv"), Levelling::line, f);
  const auto mn =
      process_profile(read_profile_text(kExamples + name + "_min.csv"), Levelling::line, f);
  EXPECT_GT(mx.moments.m2, mn.moments.m2);  // the max-slope scan is across the milling marks
  return equivalent_isotropic(mx.moments, mn.moments, IsotropicRule::geometric);
}

TEST(RoughnessExample, MilledHalvesReproduceTable54) {
  const auto pzt = half("pzt");
  const auto lc = half("lc");
  EXPECT_NEAR(pzt.sigma() / um, 1.763, 0.0005);
  EXPECT_NEAR(pzt.eta() * um * um, 3.34e-4, 0.005e-4);
  EXPECT_NEAR(pzt.R() / um, 40.76, 0.005);
  EXPECT_NEAR(lc.sigma() / um, 2.015, 0.0005);
  EXPECT_NEAR(lc.eta() * um * um, 2.51e-4, 0.005e-4);
  EXPECT_NEAR(lc.R() / um, 44.77, 0.005);
  const auto comb = combine(pzt, lc);
  EXPECT_NEAR(comb.sigma() / um, 2.677, 0.0005);
  EXPECT_NEAR(comb.R() / um, 30.14, 0.005);
  const contact::Material steel{.E = 200e9, .nu = 0.24, .G = 80.7e9, .H = 5.8e9};
  EXPECT_NEAR(plasticity_index(contact::ContactPair::combine(steel, steel, 1.0), comb), 4.725,
              0.01 * 4.725);
}

}  // namespace
}  // namespace asperity::surface
