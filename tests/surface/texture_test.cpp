// ISO 21920-2 profile and ISO 25178-2 areal parameters against closed forms on sampled
// sines and against the moments of Gaussian heights; the areal Gaussian filter against
// the profile filter; the PSD's normalisation (Parseval); spike removal; the cut-off
// pair named by the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "asperity/core/error.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/scan_set.hpp"
#include "asperity/surface/texture.hpp"

namespace asperity::surface {
namespace {

constexpr double um = 1e-6;
constexpr double kPi = std::numbers::pi;

Profile sine_profile(std::size_t n, double dx, double A, double lambda) {
  Profile p{.dx = dx, .source = "sine"};
  for (std::size_t i = 0; i < n; ++i)
    p.z.push_back(A * std::sin(2 * kPi * static_cast<double>(i) * dx / lambda));
  return p;
}

// sin(u)/u: the factor by which the forward difference reads a sinusoid's slope, exactly
// ((z[i+1] - z[i])/dx = A k sinc(k dx/2) cos(k (x_i + dx/2))).
double sinc(double u) {
  return std::sin(u) / u;
}

// A sine of N = 40 points a wavelength over m = 25 whole wavelengths (n = m N points): the
// discrete means of sin^2, sin^3, sin^4 over whole periods equal the continuous ones
// exactly (discrete orthogonality, N > 4), so Rq = A/sqrt 2, Rsk = 0, Rku = 3/8 / (1/4) =
// 1.5 to round-off (1e-12). Ra is the discrete mean of |sin|, 2 cot(pi/N)/N (the sum of
// sin(2 pi i/N) over a half period is cot(pi/N)), which is 2/pi (1 - pi^2/(3 N^2) + O(N^-4)).
TEST(ProfileParameters, SineClosedForms) {
  const double A = 1.5 * um, dx = 0.5 * um;
  const std::size_t N = 40, m = 25;
  const double lambda = static_cast<double>(N) * dx;
  const auto p = profile_parameters(sine_profile(m * N, dx, A, lambda), 0.0);
  const double Nd = static_cast<double>(N);
  EXPECT_NEAR(p.Rq / (A / std::sqrt(2.0)), 1.0, 1e-12);
  EXPECT_NEAR(p.Rsk, 0.0, 1e-12);
  EXPECT_NEAR(p.Rku / 1.5, 1.0, 1e-12);
  EXPECT_NEAR(p.Ra / (A * 2.0 / (std::tan(kPi / Nd) * Nd)), 1.0, 1e-12);
  // Against the continuous 2A/pi: the sampling error pi^2/(3 N^2) = 0.21 %, bounded with
  // 1 % margin for the O(N^-4) rest.
  const double ra_error = kPi * kPi / (3 * Nd * Nd);
  EXPECT_LT(std::abs(p.Ra / (2 * A / kPi) - 1.0), 1.01 * ra_error);
  EXPECT_GT(std::abs(p.Ra / (2 * A / kPi) - 1.0), 0.99 * ra_error);
  // One section (no lc): Rz = Rt = 2A (N a multiple of 4: the crests are sampled).
  EXPECT_EQ(p.sections, 1u);
  EXPECT_NEAR(p.Rz / (2 * A), 1.0, 1e-12);
}

// Rdq of a sine: the rms of the slope A k cos(k x) is A k/sqrt 2 = sqrt(2) pi A/lambda (its
// peak is 2 pi A/lambda); the forward difference reads it low by sinc(k dx/2) exactly. With
// n = m N + 1 points the n - 1 differences cover whole periods, so the discrete mean of
// cos^2 is 1/2 exactly: the closed form holds to round-off.
TEST(ProfileParameters, SineRmsSlopeWithItsDiscretisation) {
  const double A = 2 * um, dx = 1 * um;
  for (std::size_t N : {8u, 20u, 100u}) {
    SCOPED_TRACE(N);
    const double lambda = static_cast<double>(N) * dx, k = 2 * kPi / lambda;
    const auto p = profile_parameters(sine_profile(30 * N + 1, dx, A, lambda), 0.0);
    const double continuous = 2 * kPi * A / lambda / std::sqrt(2.0);
    EXPECT_NEAR(p.Rdq / (continuous * sinc(k * dx / 2)), 1.0, 1e-12);
    // The error of the difference, 1 - sinc(k dx/2) ~ (k dx)^2/24: 6 % at N = 8, 0.016 % at 100.
    EXPECT_NEAR(1.0 - p.Rdq / continuous, 1.0 - sinc(k * dx / 2), 1e-12);
  }
}

// Rz is the mean of the sections' peak-to-valley heights: two sections of length lc, the
// first a sine of amplitude A1, the second of A2, give Rz = A1 + A2 (crests sampled).
TEST(ProfileParameters, RzAveragesSectionsOfLengthLc) {
  const double dx = 1 * um, A1 = 1 * um, A2 = 3 * um;
  const std::size_t N = 20, per = 10 * N;  // a section holds 10 wavelengths
  auto p = sine_profile(2 * per + 7, dx, A1, static_cast<double>(N) * dx);
  for (std::size_t i = per; i < p.z.size(); ++i) p.z[i] *= A2 / A1;
  const auto r = profile_parameters(p, static_cast<double>(per) * dx);
  EXPECT_EQ(r.sections, 2u);  // the 7 points left over are not a section
  EXPECT_NEAR(r.section_length, static_cast<double>(per) * dx, 1e-18);
  EXPECT_NEAR(r.Rz / (A1 + A2), 1.0, 1e-12);
}

// Independent Gaussian heights: the sample skewness and kurtosis of n values have standard
// deviations sqrt(6/n) and sqrt(24/n) (normal theory, Kendall & Stuart); Rq^2 has a relative
// sd sqrt(2/n), Ra a relative sd sqrt((pi/2 - 1)/n) about sigma sqrt(2/pi). Bounds of 5 sd:
// a false failure has probability < 1e-6 per check.
TEST(ProfileParameters, GaussianHeightsMoments) {
  const std::size_t n = 1u << 16;
  const double s = 0.8 * um;
  std::mt19937_64 rng(2026);
  std::normal_distribution<double> g(0.0, s);
  Profile p{.dx = 1 * um, .source = "gauss"};
  for (std::size_t i = 0; i < n; ++i) p.z.push_back(g(rng));
  const auto r = profile_parameters(p, 0.0);
  const double dn = static_cast<double>(n);
  EXPECT_NEAR(r.Rsk, 0.0, 5 * std::sqrt(6 / dn));
  EXPECT_NEAR(r.Rku / 3.0, 1.0, 5 * std::sqrt(24 / dn) / 3.0);
  EXPECT_NEAR(r.Rq / s, 1.0, 5 * 0.5 * std::sqrt(2 / dn));
  EXPECT_NEAR(r.Ra / (s * std::sqrt(2 / kPi)), 1.0, 5 * std::sqrt((kPi / 2 - 1) / dn));
}

HeightMap map_of(std::size_t nx, std::size_t ny, double dx, double dy, auto f) {
  HeightMap m{.nx = nx, .ny = ny, .dx = dx, .dy = dy, .source = "map"};
  for (std::size_t iy = 0; iy < ny; ++iy)
    for (std::size_t ix = 0; ix < nx; ++ix)
      m.z.push_back(f(static_cast<double>(ix) * dx, static_cast<double>(iy) * dy));
  return m;
}

// Gaussian surface of independent heights, 256 x 256: the same 5-sd bounds as above.
TEST(ArealParameters, GaussianSurfaceSkewnessAndKurtosis) {
  std::mt19937_64 rng(7);
  const double s = 0.3 * um;
  std::normal_distribution<double> g(0.0, s);
  const auto m = map_of(256, 256, 1 * um, 2 * um, [&](double, double) { return g(rng); });
  const auto a = areal_parameters(m);
  const double dn = 256.0 * 256.0;
  EXPECT_NEAR(a.Ssk, 0.0, 5 * std::sqrt(6 / dn));
  EXPECT_NEAR(a.Sku / 3.0, 1.0, 5 * std::sqrt(24 / dn) / 3.0);
  EXPECT_NEAR(a.Sq / s, 1.0, 5 * 0.5 * std::sqrt(2 / dn));
  EXPECT_NEAR(a.Sa / (s * std::sqrt(2 / kPi)), 1.0, 5 * std::sqrt((kPi / 2 - 1) / dn));
}

// z = A sin(kx x), constant along y, over whole periods: Sa, Sq, Ssk, Sku equal the
// profile's closed forms to round-off.
TEST(ArealParameters, SineHeightsClosedForms) {
  const double A = 1 * um, dx = 0.5 * um, lambda = 32 * dx;
  const auto m = map_of(32 * 8, 11, dx, 0.7 * um,
                        [&](double x, double) { return A * std::sin(2 * kPi * x / lambda); });
  const auto a = areal_parameters(m);
  EXPECT_NEAR(a.Sq / (A / std::sqrt(2.0)), 1.0, 1e-12);
  EXPECT_NEAR(a.Ssk, 0.0, 1e-12);
  EXPECT_NEAR(a.Sku / 1.5, 1.0, 1e-12);
  EXPECT_NEAR(a.Sa / (A * 2.0 / (std::tan(kPi / 32.0) * 32.0)), 1.0, 1e-12);
}

// Sdq^2 = <(dz/dx)^2> + <(dz/dy)^2>; for z = A sin(kx x) + B sin(ky y) with the x- and
// y-differences over whole periods (n = m N + 1), each is (amplitude k sinc(k d/2))^2/2
// exactly (the other sine cancels in a difference along the first).
TEST(ArealParameters, SdqOfTwoCrossedSines) {
  const double A = 1 * um, B = 0.4 * um, dx = 0.5 * um, dy = 1.5 * um;
  const double lx = 16 * dx, ly = 10 * dy, kx = 2 * kPi / lx, ky = 2 * kPi / ly;
  const auto m = map_of(16 * 6 + 1, 10 * 5 + 1, dx, dy, [&](double x, double y) {
    return A * std::sin(kx * x) + B * std::sin(ky * y);
  });
  const auto a = areal_parameters(m);
  const double gx = A * kx * sinc(kx * dx / 2), gy = B * ky * sinc(ky * dy / 2);
  EXPECT_NEAR(a.Sdq / std::sqrt(0.5 * gx * gx + 0.5 * gy * gy), 1.0, 1e-12);
}

// The areal Gaussian filter is separable (ISO 16610-61 weights s(x) s(y)): on a map whose
// rows are all the same profile, every row of the S-L surface is that profile through the
// profile filter (the column pass sees constants, which the unit-sum weights keep), and
// likewise for columns (the map is square so that the filter fits both ways). Round-off: sums over
// a few thousand terms, 1e-12 of the heights.
TEST(ArealFilter, SeparableAsTheProfileFilter) {
  const GaussianFilter f{.lc = 80 * um, .ls = 2.5 * um};
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1 * um);
  const std::size_t n = 700;
  Profile line{.dx = 0.5 * um, .source = "line"};
  for (std::size_t i = 0; i < n; ++i) line.z.push_back(g(rng));
  const auto want = f.apply(line);
  for (bool along_x : {true, false}) {
    SCOPED_TRACE(along_x);
    const auto m = map_of(n, n, 0.5 * um, 0.5 * um, [&](double x, double y) {
      return line.z[static_cast<std::size_t>(std::llround((along_x ? x : y) / (0.5 * um)))];
    });
    const auto sl = scale_limited_surface(m, Levelling::none, f);
    const std::size_t len = along_x ? sl.nx : sl.ny;
    ASSERT_EQ(len, want.z.size());
    for (std::size_t i = 0; i < len; i += 7) {
      const std::size_t j = sl.nx / 2, k = sl.ny / 2;
      const double v = along_x ? sl.z[i + sl.nx * k] : sl.z[j + sl.nx * i];
      EXPECT_NEAR(v, want.z[i], 1e-12 * um);
    }
  }
}

// Parseval: sum P df = mean z^2 for the one-sided PSD, to round-off of the FFT (a few eps
// log2 n), checked to 1e-12 for even and odd n; a sine of amplitude A at a bin frequency
// puts A^2/2 into that bin (the rest is round-off).
TEST(PowerSpectrum, ParsevalAndSineBin) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g(0.0, 1 * um);
  for (std::size_t n : {1000u, 999u}) {
    SCOPED_TRACE(n);
    Profile p{.dx = 0.25 * um, .source = "noise"};
    double ms = 0;
    for (std::size_t i = 0; i < n; ++i) {
      p.z.push_back(g(rng));
      ms += p.z.back() * p.z.back();
    }
    ms /= static_cast<double>(n);
    const auto s = power_spectrum(p);
    ASSERT_EQ(s.f.size(), n / 2 + 1);
    double sum = 0;
    for (double v : s.psd) sum += v * s.df;
    EXPECT_NEAR(sum / ms, 1.0, 1e-12);
    EXPECT_NEAR(s.df, 1.0 / (static_cast<double>(n) * p.dx), 1e-12 * s.df);
  }
  const double A = 2 * um, dx = 1 * um;
  const auto s = power_spectrum(sine_profile(640, dx, A, 64 * dx));  // bin 10
  EXPECT_NEAR(s.f[10], 1.0 / (64 * dx), 1e-9 * s.f[10]);
  EXPECT_NEAR(s.psd[10] * s.df / (A * A / 2), 1.0, 1e-12);
  EXPECT_LT(s.psd[11] * s.df, 1e-20 * A * A);
}

// The mean PSD of a map's rows integrates to the map's mean square (each row's Parseval).
TEST(PowerSpectrum, ArealRowsAndColumnsIntegrateToSq) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 1 * um);
  const auto m = map_of(128, 96, 1 * um, 2 * um, [&](double, double) { return g(rng); });
  const double sq = areal_parameters(m).Sq;
  for (bool along_x : {true, false}) {
    const auto s = power_spectrum(m, along_x);
    EXPECT_EQ(s.profiles, along_x ? 96u : 128u);
    double sum = 0;
    for (double v : s.psd) sum += v * s.df;
    EXPECT_NEAR(sum / (sq * sq), 1.0, 1e-12);
  }
}

// Spikes of 50 sd on a sine with noise are replaced and the rest is untouched; off by
// default; a spike-free profile loses no point at threshold 5 (the largest excursion of
// 2000 Gaussian residuals from a 5-point median is about 4.5 sd, the threshold 5 robust sd).
TEST(SpikeRemoval, RemovesIsolatedSpikesOnly) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> g(0.0, 0.01 * um);
  auto p = sine_profile(2000, 1 * um, 1 * um, 100 * um);
  for (auto& v : p.z) v += g(rng);
  const auto clean = p;
  EXPECT_EQ(remove_spikes(p, SpikeRemoval{}), 0u);
  auto q = clean;
  EXPECT_EQ(remove_spikes(q, {.threshold = 5.0}), 0u);
  EXPECT_EQ(q.z, clean.z);
  for (std::size_t i : {100u, 101u, 777u, 1500u}) p.z[i] += 50 * um;
  EXPECT_EQ(remove_spikes(p, {.threshold = 5.0}), 4u);
  for (std::size_t i = 0; i < p.z.size(); ++i) {
    // Replaced points lie on the chord of their neighbours: within the sine's change over
    // 3 dx (2 pi A 3 dx / lambda = 0.19 um) of the clean value.
    EXPECT_NEAR(p.z[i], clean.z[i], 0.2 * um) << i;
  }
  EXPECT_THROW(remove_spikes(p, {.threshold = 1.0}), InvalidInput);
  EXPECT_THROW(remove_spikes(p, {.threshold = 5.0, .half_window = 0}), InvalidInput);
}

const std::string kData = ASPERITY_TEST_DATA_DIR;

// The refusal of the default filter on the shipped 650 x 650 X3P names a pair, and that
// pair works for the moments and the areal parameters.
TEST(CutoffPair, RefusalOfTheShippedX3pNamesAWorkingPair) {
  const std::string file = kData + "/mountainsmap-650x650.x3p";
  const auto map = read_x3p(file);
  std::string message;
  try {
    (void)equivalent_isotropic_surface({{file, ""}}, ScanSettings{});
  } catch (const InvalidInput& e) {
    message = e.what();
  }
  ASSERT_NE(message.find("a cut-off pair that fits"), std::string::npos) << message;
  const auto pair = working_cutoff_pair(GaussianFilter{}, map.nx, map.dx, map.ny, map.dy);
  ASSERT_FALSE(pair.is_none());
  EXPECT_GE(pair.ls, 5 * std::max(map.dx, map.dy));
  EXPECT_GE(pair.lc, 5 * pair.ls);
  ScanSettings s;
  s.filter = pair;
  s.psd = true;
  const auto r = equivalent_isotropic_surface({{file, ""}}, s);
  ASSERT_TRUE(r.areal_parameters.has_value());
  EXPECT_GT(r.areal_parameters->Sq, 0.0);
  EXPECT_EQ(r.psd.size(), 2u);
  // Sq of the S-L surface is at most that about the plane (the filter removes variance).
  EXPECT_LT(r.areal_parameters->Sq, r.Sq);
}

// A short line scan: the refusal names a standard pair when one fits (the Dektak export,
// 1.5 mm at 0.156 um: (0.25 mm, 2.5 um) fits with discard, 0.8 mm does not).
TEST(CutoffPair, ShortProfileNamesTheLongestStandardPairThatFits) {
  const auto f = working_cutoff_pair(GaussianFilter{}, 9600, 0.15625 * um);
  EXPECT_EQ(f.lc, 0.25e-3);
  EXPECT_EQ(f.ls, 2.5e-6);
  EXPECT_NE(cutoff_pair_advice(GaussianFilter{}, 9600, 0.15625 * um).find("--lc 250um --ls 2.5um"),
            std::string::npos);
}

}  // namespace
}  // namespace asperity::surface
