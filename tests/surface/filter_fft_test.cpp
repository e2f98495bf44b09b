// The FFT path of the ISO 16610-21 Gaussian filter (overlap-save, KISS FFT) against the
// direct convolution it replaces, which stays as the reference path
// (Convolution::direct). Both compute the same sums; they differ by round-off only,
// bounded here by 1e-12 of the rms of the heights filtered (about zero): the FFT's
// round-off is a few eps log2(N) (N <= 2^14 here: ~1e-14) times the window sums, the
// direct sums' eps sqrt(h), both of the size of the input heights. (For the raw Dektak
// scan, 16.6 um of tilt over 0.011 um of roughness, the scale matters: the paths differ
// by 3e-12 of the filtered profile's own rms, 4e-15 of the input's.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "../../src/surface/detail/convolution.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/roughness.hpp"

namespace asperity::surface {
namespace {

constexpr double um = 1e-6;
constexpr double mm = 1e-3;
const std::string kData = std::string(ASPERITY_TEST_DATA_DIR);
const std::string kExamples = kData + "/../../examples/roughness/";

double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

// max |a - b| / scale, with equal sizes required.
double relative_difference(const Profile& a, const Profile& b, double scale) {
  EXPECT_EQ(a.z.size(), b.z.size());
  EXPECT_DOUBLE_EQ(a.x0, b.x0);
  double d = 0;
  for (std::size_t i = 0; i < std::min(a.z.size(), b.z.size()); ++i) {
    d = std::max(d, std::abs(a.z[i] - b.z[i]));
  }
  return d / scale;
}

std::vector<Profile> shipped_profiles() {
  std::vector<Profile> out;
  for (const char* name : {"pzt_max", "pzt_min", "lc_max", "lc_min"}) {
    out.push_back(read_profile_text(kExamples + name + ".csv"));
  }
  out.push_back(read_profile_text(kData + "/dektak-1.csv"));
  return out;
}

TEST(FilterFft, EqualsDirectOnShippedProfilesBothEndEffects) {
  for (const auto& raw : shipped_profiles()) {
    for (auto levelling : {Levelling::none, Levelling::line}) {
      const Profile p = level(raw, levelling);
      for (auto end : {EndEffects::discard, EndEffects::regression}) {
        for (double ct : {0.5, 1.0, 3.0}) {
          GaussianFilter fft{.truncation = ct, .end = end};
          GaussianFilter direct = fft;
          direct.convolution = Convolution::direct;
          // Shorter profiles than a filter needs are refused by both paths alike.
          if (p.z.size() < fft.min_points(p.dx)) continue;
          SCOPED_TRACE(p.source + " end " + std::string(to_string(end)) + " ct " +
                       std::to_string(ct));
          EXPECT_LT(relative_difference(fft.apply(p), direct.apply(p), rms(p.z)), 1e-12);
          // The mean line alone (lc only).
          EXPECT_LT(relative_difference(
                        gaussian_mean_line(p, 0.8 * mm, ct, end, Convolution::fft),
                        gaussian_mean_line(p, 0.8 * mm, ct, end, Convolution::direct), rms(p.z)),
                    1e-12);
        }
      }
    }
  }
}

TEST(FilterFft, EqualsDirectOnAnArealMap) {
  const auto map = read_x3p(kData + "/mountainsmap-650x650.x3p");
  GaussianFilter fft{.lc = 20 * um, .ls = 2.5 * um};
  GaussianFilter direct = fft;
  direct.convolution = Convolution::direct;
  const auto a = areal_moments(map, Levelling::line, fft);
  const auto b = areal_moments(map, Levelling::line, direct);
  EXPECT_EQ(a.x_profiles, b.x_profiles);
  EXPECT_EQ(a.y_profiles, b.y_profiles);
  // Moments are quadratic in the heights: twice the heights' relative difference.
  for (auto [x, y] :
       {std::pair{a.x.m0, b.x.m0}, std::pair{a.x.m2, b.x.m2}, std::pair{a.x.m4, b.x.m4},
        std::pair{a.y.m0, b.y.m0}, std::pair{a.y.m2, b.y.m2}, std::pair{a.y.m4, b.y.m4}}) {
    EXPECT_NEAR(x, y, 2e-12 * y);
  }
}

// Regression with a window longer than the profile (lc up to the profile length is
// allowed): every point's window is cut at both ends.
TEST(FilterFft, RegressionWithWindowLongerThanTheProfile) {
  Profile p;
  p.dx = 1 * um;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1 * um);
  for (int i = 0; i < 900; ++i) p.z.push_back(g(rng) + 2e-3 * i * um);
  const auto a = gaussian_mean_line(p, 0.8 * mm, 1.0, EndEffects::regression, Convolution::fft);
  const auto b = gaussian_mean_line(p, 0.8 * mm, 1.0, EndEffects::regression, Convolution::direct);
  EXPECT_LT(relative_difference(a, b, rms(p.z)), 1e-12);
}

// The correlation itself, for kernel half-widths from 0 to beyond n and every output
// range shape (one block, many blocks, ranges touching either end).
TEST(FilterFft, CorrelationEqualsDirectSummation) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (std::size_t n : {1u, 7u, 300u, 5000u}) {
    std::vector<double> z(n);
    for (double& v : z) v = uni(rng);
    for (std::size_t h : {0u, 1u, 5u, 64u, 700u}) {
      std::vector<double> u(2 * h + 1);
      for (double& v : u) v = uni(rng);  // not symmetric: the kernel's orientation counts
      for (auto [b, e] : {std::pair<std::size_t, std::size_t>{0, n},
                          std::pair<std::size_t, std::size_t>{n / 3, n - n / 4}}) {
        std::vector<double> f(e - b), d(e - b);
        detail::correlate_fft(z.data(), n, u, b, e, f.data());
        detail::correlate_direct(z.data(), n, u, b, e, d.data());
        // Scale: sum |u| max|z| (<= 2h + 1); round-off a few eps log2 N of it.
        double scale = 0;
        for (double v : u) scale += std::abs(v);
        for (std::size_t i = 0; i < f.size(); ++i) {
          ASSERT_NEAR(f[i], d[i], 1e-13 * scale) << "n " << n << " h " << h << " i " << b + i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace asperity::surface
