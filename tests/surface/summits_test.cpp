// Summits identified on areal maps (eight-neighbour maxima), their statistics and the
// summit-height table that the rough flat sums over.
#include <gtest/gtest.h>

#include "../support.hpp"

#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/random.hpp"
#include "asperity/surface/summits.hpp"

namespace asperity::surface {
namespace {

using asperity::testing::rel;

HeightMap grid(std::size_t nx, std::size_t ny, double dx, double dy) {
  HeightMap m;
  m.nx = nx;
  m.ny = ny;
  m.dx = dx;
  m.dy = dy;
  m.z.assign(nx * ny, 0.0);
  m.source = "test map";
  return m;
}

TEST(Summits, EggCrateHasItsPeaksWithTheDiscreteCurvature) {
  // z = A cos(k x) cos(k y), wavelength L = 16 dx: peaks (z = A) where both cosines are 1 or
  // both -1, i.e. at multiples j L/2 (j = 1..7 inside a 4 L map without its edge) with j_x,
  // j_y both odd (16 peaks) or both even (9): 25. At a peak the neighbours along x are
  // A cos(k dx), so z_xx = 2 A (cos(k dx) - 1)/dx^2 exactly and the mean curvature is
  // 2 A (1 - cos(k dx))/dx^2 (-> A k^2 as dx -> 0).
  const double A = 1e-6, dx = 0.5e-6, L = 16 * dx, k = 2 * std::numbers::pi / L;
  HeightMap m = grid(65, 65, dx, dx);
  for (std::size_t iy = 0; iy < m.ny; ++iy)
    for (std::size_t ix = 0; ix < m.nx; ++ix)
      m.z[ix + m.nx * iy] = A * std::cos(k * static_cast<double>(ix) * dx) *
                            std::cos(k * static_cast<double>(iy) * dx);
  const SummitSet s = find_summits(m);
  ASSERT_EQ(s.summits.size(), 25u);
  EXPECT_EQ(s.points, 63u * 63u);
  EXPECT_LT(rel(s.area, 63 * dx * 63 * dx), 1e-15);
  EXPECT_LT(rel(s.density(), 25.0 / s.area), 1e-15);
  const double kappa = 2 * A * (1 - std::cos(k * dx)) / (dx * dx);
  for (const auto& p : s.summits) {
    EXPECT_LT(rel(p.z, A), 1e-15);
    EXPECT_LT(rel(p.curvature, kappa), 1e-12);
    // On the lattice of half-wavelengths.
    const double jx = p.x / (0.5 * L), jy = p.y / (0.5 * L);
    EXPECT_LT(std::abs(jx - std::round(jx)), 1e-9);
    EXPECT_EQ(std::lround(jx) % 2, std::lround(jy) % 2);
  }
  EXPECT_LT(rel(s.radius(), 1 / kappa), 1e-12);
  EXPECT_LT(rel(s.mean_height(), A), 1e-15);
  EXPECT_LT(s.height_standard_deviation(), 1e-15 * A);
  // The discrete curvature against A k^2: relative (k dx)^2 / 12 = 1.3 %.
  EXPECT_LT(std::abs(kappa / (A * k * k) - 1 + std::pow(k * dx, 2) / 12), 1e-4);
}

TEST(Summits, IndependentHeightsGiveTheMaximumOfNine) {
  // Independent N(0, 1) heights: each interior point is the highest of its 3 x 3 block with
  // probability 1/9, and a summit's height is the largest of 9 normals, whose mean is
  // 1.48501 (expected largest of n = 9 standard normal values; Harter 1961, Table 1).
  // Tolerances: 5 standard errors. The count is a sum of 39204 indicators (negatively
  // correlated between neighbours, which only lowers its spread below the binomial
  // sqrt(n p (1 - p)) = 62, 1.4 %); a summit's height has standard deviation 0.598 (largest
  // of 9), so the mean of ~4356 has a standard error of 0.0091 (0.61 %).
  HeightMap m = grid(200, 200, 1e-6, 2e-6);
  core::StandardNormal normal(20261127);
  for (double& z : m.z) z = normal();
  const SummitSet s = find_summits(m);
  const double n = static_cast<double>(s.points), p = 1.0 / 9.0;
  EXPECT_LT(std::abs(static_cast<double>(s.summits.size()) - n * p),
            5 * std::sqrt(n * p * (1 - p)));
  EXPECT_LT(std::abs(s.mean_height() - 1.48501), 5 * 0.598 / std::sqrt(n * p));
  EXPECT_LT(rel(s.density(), static_cast<double>(s.summits.size()) / (198e-6 * 396e-6)), 1e-14);
}

TEST(Summits, AFlatPairIsOneSummit) {
  // Two equal neighbouring points above the rest: the earlier one in raster order is the
  // summit (its later neighbour may be equal, an earlier one may not).
  for (const bool along_x : {true, false}) {
    HeightMap m = grid(5, 5, 1e-6, 2e-6);
    m.z[2 + 5 * 2] = 1e-6;
    m.z[along_x ? 3 + 5 * 2 : 2 + 5 * 3] = 1e-6;
    const SummitSet s = find_summits(m);
    ASSERT_EQ(s.summits.size(), 1u);
    EXPECT_EQ(s.summits[0].x, 2e-6);
    EXPECT_EQ(s.summits[0].y, 4e-6);
    // Mean curvature from the central second differences through the pair's other point.
    const double zxx = along_x ? -1e-6 / 1e-12 : -2e-6 / 1e-12;
    const double zyy = along_x ? -2e-6 / 4e-12 : -1e-6 / 4e-12;
    EXPECT_LT(rel(s.summits[0].curvature, -0.5 * (zxx + zyy)), 1e-14);
  }
}

TEST(Summits, MapsWithoutSummitsOrWithHolesAreRefusedByName) {
  using asperity::testing::invalid_input_message;
  HeightMap plane = grid(10, 10, 1e-6, 1e-6);
  for (std::size_t iy = 0; iy < 10; ++iy)
    for (std::size_t ix = 0; ix < 10; ++ix) plane.z[ix + 10 * iy] = 1e-7 * static_cast<double>(ix);
  EXPECT_NE(invalid_input_message([&] { (void)find_summits(plane); })
                .find("no summit (a point higher than its eight neighbours) in the map's 64 "
                      "interior points"),
            std::string::npos);
  HeightMap holes = grid(4, 4, 1e-6, 1e-6);
  holes.valid.assign(16, 1);
  holes.valid[5] = 0;
  holes.z[5] = std::nan("");
  EXPECT_NE(invalid_input_message([&] {
              (void)find_summits(holes);
            }).find("and 1 of the 16 points are invalid"),
            std::string::npos);
  const HeightMap line = grid(10, 2, 1e-6, 1e-6);
  EXPECT_NE(invalid_input_message([&] {
              (void)find_summits(line);
            }).find("3 x 3 points or more; it has 10 x 2"),
            std::string::npos);
}

SummitSet heights(const std::vector<double>& z) {
  SummitSet s;
  for (double v : z) s.summits.push_back({0, 0, v, 1.0});
  s.area = 1.0;
  return s;
}

TEST(SummitHistogram, IsAFrequencyPolygonWithItsExactMoments) {
  // Bins of h = 1 over [0, 4]: counts 2, 1, 0, 3 at centres 0.5 .. 3.5 (the top summit
  // closes the last bin), zero rows at -0.5 and 4.5.
  const SummitSet s = heights({0.0, 0.2, 1.5, 3.1, 3.9, 4.0, 0.0, 0.0, 0.0, 0.0});
  // Counts 6, 1, 0, 3 with the four extra zeros.
  const SummitHistogram h = summit_histogram(s, 4);
  EXPECT_EQ(h.bin_width, 1.0);
  ASSERT_EQ(h.height.size(), 6u);
  const std::vector<double> centres{-0.5, 0.5, 1.5, 2.5, 3.5, 4.5};
  const std::vector<double> density{0, 0.6, 0.1, 0, 0.3, 0};
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_DOUBLE_EQ(h.height[k], centres[k]);
    EXPECT_DOUBLE_EQ(h.density[k], density[k]);
  }
  // Linear between the points: integral 1, mean = count-weighted centres, variance = theirs
  // plus h^2/6.
  const SummitHeightTable t = summit_height_table(h, "test");
  const double mean = 0.6 * 0.5 + 0.1 * 1.5 + 0.3 * 3.5;
  const double var = 0.6 * 0.25 + 0.1 * 2.25 + 0.3 * 12.25 - mean * mean + 1.0 / 6.0;
  EXPECT_LT(rel(t.mean(), mean), 1e-14);
  EXPECT_LT(rel(t.standard_deviation(), std::sqrt(var)), 1e-14);
}

TEST(SummitHistogram, RiceBinsOverAGaussianSampleKeepItsSpreadToSheppardsTerm) {
  // n = 20000 Gaussian quantiles z_i = Phi^-1((i + 1/2)/n) (a sample with no sampling
  // noise): Rice's rule gives ceil(2 n^(1/3)) = 55 bins. The frequency polygon's variance is
  // the binned one plus h^2/6, and binning a smooth density adds Sheppard's h^2/12 to the
  // sample's, so the table's standard deviation is sqrt(s^2 + h^2/4) with s the sample's;
  // what remains is the quantile sample's discreteness (measured: 3.4e-5), held to 1e-4.
  const std::size_t n = 20000;
  std::vector<double> z(n);
  for (std::size_t i = 0; i < n; ++i)
    z[i] = std::numbers::sqrt2 *
           boost::math::erf_inv(2 * (static_cast<double>(i) + 0.5) / static_cast<double>(n) - 1);
  const SummitSet s = heights(z);
  const SummitHistogram h = summit_histogram(s);
  EXPECT_EQ(h.height.size(), 55u + 2u);
  const SummitHeightTable t = summit_height_table(h, "gaussian sample");
  const double sd = s.height_standard_deviation();
  EXPECT_LT(rel(t.standard_deviation(), std::sqrt(sd * sd + h.bin_width * h.bin_width / 4)), 1e-4);
  EXPECT_LT(std::abs(t.mean()), 1e-4);
}

TEST(SummitHistogram, TooFewSummitsOrOneHeightAreRefused) {
  using asperity::testing::invalid_input_message;
  EXPECT_NE(invalid_input_message([&] {
              (void)summit_histogram(heights({1, 2, 3}));
            }).find("needs 10 summits or more; the map has 3"),
            std::string::npos);
  EXPECT_NE(invalid_input_message([&] {
              (void)summit_histogram(heights(std::vector(12, 1.0)));
            }).find("all 12 summits are at one height"),
            std::string::npos);
  EXPECT_NE(invalid_input_message([&] {
              (void)summit_histogram(heights({0, 1, 2, 3, 4, 5, 6, 7, 8, 9}), 10001);
            }).find("bins = 10001: allowed are 1 to 10000"),
            std::string::npos);
}

TEST(SummitHeightTableFile, IsReadInItsUnitsWithDensitiesOrCounts) {
  // The triangle of SummitHeightTable.TriangleHasItsClosedFormMoments in um and as counts:
  // mean 1 um, standard deviation 1/sqrt(6) um; a histogram as written round-trips.
  const auto dir = std::filesystem::temp_directory_path() / "asperity-summit-table-test";
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) {
    const auto path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
  };
  const SummitHeightTable t =
      read_summit_height_table(write("t.csv", "# a triangle\nheight[um],count\n0,0\n1,7\n2,0\n"));
  EXPECT_LT(rel(t.mean(), 1e-6), 1e-15);
  EXPECT_LT(rel(t.standard_deviation(), 1e-6 / std::sqrt(6.0)), 1e-14);
  const std::string missing = asperity::testing::invalid_input_message(
      [&] { (void)read_summit_height_table(write("z.csv", "z[um],density\n0,0\n1,7\n2,0\n")); });
  EXPECT_NE(missing.find("a summit-height table has the columns height[unit] and density"),
            std::string::npos)
      << missing;
  const std::string negative = asperity::testing::invalid_input_message([&] {
    (void)read_summit_height_table(write("n.csv", "height[nm],density\n0,0\n1,-7\n2,0\n"));
  });
  EXPECT_NE(negative.find("n.csv\" is not a distribution: density -7 at point 2"),
            std::string::npos)
      << negative;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace asperity::surface
