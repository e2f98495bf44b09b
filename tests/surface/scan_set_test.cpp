// surface::equivalent_isotropic_surface: the rules that turn a set of scans into the
// equivalent isotropic surface (Eq. 5.1), shared by the CLI, case files and Python.
#include "asperity/surface/scan_set.hpp"

#include <gtest/gtest.h>

#include <string>

#include "asperity/core/error.hpp"
#include "asperity/joint/case.hpp"

namespace {

using namespace asperity::surface;

const std::string kEx = std::string(ASPERITY_TEST_DATA_DIR) + "/../../examples/roughness/";

SpectralMoments one(const std::string& f) {
  return process_profile(read_height_file(kEx + f).as_profile(), Levelling::line, GaussianFilter{})
      .moments;
}

TEST(ScanSet, TwoUntaggedScansOrderedByM2InEitherOrder) {
  const auto mx = one("pzt_max.csv"), mn = one("pzt_min.csv");
  ASSERT_GT(mx.m2, mn.m2);  // the file names say which is which; m2 must agree
  const auto expected = equivalent_isotropic(mx, mn, IsotropicRule::geometric);
  for (const auto& files :
       {std::vector<ScanFile>{{kEx + "pzt_max.csv", ""}, {kEx + "pzt_min.csv", ""}},
        std::vector<ScanFile>{{kEx + "pzt_min.csv", ""}, {kEx + "pzt_max.csv", ""}}}) {
    const auto r = equivalent_isotropic_surface(files, {});
    // The same functions on the same data: equal bit for bit.
    EXPECT_EQ(r.moments.m0, expected.m0);
    EXPECT_EQ(r.moments.m2, expected.m2);
    EXPECT_EQ(r.moments.m4, expected.m4);
  }
}

TEST(ScanSet, TagsAverageEachDirectionWeightedByPoints) {
  const auto r = equivalent_isotropic_surface(
      {{kEx + "pzt_max.csv", "max"}, {kEx + "lc_max.csv", "max"}, {kEx + "pzt_min.csv", "min"}},
      {});
  const auto a = one("pzt_max.csv"), b = one("lc_max.csv");
  const double wa = static_cast<double>(r.scans[0].points),
               wb = static_cast<double>(r.scans[1].points);
  const auto mx = average_moments({a, b}, {wa, wb});
  const auto expected = equivalent_isotropic(mx, one("pzt_min.csv"), IsotropicRule::geometric);
  EXPECT_DOUBLE_EQ(r.moments.m2, expected.m2);
  EXPECT_DOUBLE_EQ(r.moments.m4, expected.m4);
  EXPECT_EQ(r.scans[2].direction, "min_slope");
}

TEST(ScanSet, RefusesMixedTagsThreeUntaggedScansAndUnknownTags) {
  EXPECT_THROW((void)equivalent_isotropic_surface(
                   {{kEx + "pzt_max.csv", "max"}, {kEx + "pzt_min.csv", ""}}, {}),
               asperity::InvalidInput);
  EXPECT_THROW(
      (void)equivalent_isotropic_surface(
          {{kEx + "pzt_max.csv", ""}, {kEx + "pzt_min.csv", ""}, {kEx + "lc_max.csv", ""}}, {}),
      asperity::InvalidInput);
  EXPECT_THROW((void)parse_scan_file(kEx + "pzt_max.csv@diagonal"), asperity::InvalidInput);
  const auto f = parse_scan_file("a.csv@min");
  EXPECT_EQ(f.path, "a.csv");
  EXPECT_EQ(f.tag, "min");
}

TEST(ScanSet, CaseFilesUseTheSameFunction) {
  const auto half = asperity::joint::half_roughness_from_files(
      {kEx + "pzt_min.csv@min", kEx + "pzt_max.csv@max", kEx + "lc_max.csv@max"}, {});
  const auto r = equivalent_isotropic_surface(
      {{kEx + "pzt_min.csv", "min"}, {kEx + "pzt_max.csv", "max"}, {kEx + "lc_max.csv", "max"}},
      {});
  EXPECT_EQ(half.moments.m2, r.moments.m2);
  EXPECT_EQ(half.moments.m4, r.moments.m4);
  EXPECT_EQ(half.directions, (std::vector<std::string>{"min_slope", "max_slope", "max_slope"}));
}

}  // namespace
