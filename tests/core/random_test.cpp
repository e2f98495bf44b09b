// core::StandardNormal: a specified generator and transform (core/random.hpp).
#include "asperity/core/random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

namespace {

using asperity::core::StandardNormal;

TEST(StandardNormal, EngineIsTheStandardsMt19937_64) {
  // [rand.predef]: the 10000th output of a default-constructed std::mt19937_64.
  std::mt19937_64 e;
  for (int i = 1; i < 10000; ++i) (void)e();
  EXPECT_EQ(e(), 9981545732273789042ULL);
}

TEST(StandardNormal, FollowsMarsagliasPolarMethodOnThe53TopBits) {
  // The transform written out again from its definition, on the raw engine.
  std::mt19937_64 e(42);
  auto u = [&] { return static_cast<double>(e() >> 11) / 9007199254740992.0; };  // 2^53
  StandardNormal n(42);
  for (int pair = 0; pair < 1000; ++pair) {
    double v1 = 0.0, v2 = 0.0, s = 0.0;
    do {
      v1 = 2.0 * u() - 1.0;
      v2 = 2.0 * u() - 1.0;
      s = v1 * v1 + v2 * v2;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    EXPECT_EQ(n(), v1 * f);  // same operations in the same order: bit for bit
    EXPECT_EQ(n(), v2 * f);
  }
}

TEST(StandardNormal, MomentsOfAMillionValues) {
  // n = 1e6: standard errors 1e-3 (mean), sqrt(2/n) = 1.4e-3 (variance), sqrt(6/n) =
  // 2.4e-3 (skewness), sqrt(24/n) = 4.9e-3 (excess kurtosis); tolerances 5 of them.
  StandardNormal n(7);
  const int N = 1'000'000;
  double m1 = 0, m2 = 0, m3 = 0, m4 = 0;
  for (int i = 0; i < N; ++i) {
    const double x = n();
    m1 += x;
    m2 += x * x;
    m3 += x * x * x;
    m4 += x * x * x * x;
  }
  m1 /= N;
  m2 /= N;
  m3 /= N;
  m4 /= N;
  EXPECT_NEAR(m1, 0.0, 5e-3);
  EXPECT_NEAR(m2, 1.0, 7e-3);
  EXPECT_NEAR(m3, 0.0, 1.2e-2);
  EXPECT_NEAR(m4 - 3.0, 0.0, 2.5e-2);
}

TEST(StandardNormal, SameSeedSameSequenceOtherSeedOther) {
  StandardNormal a(1), b(1), c(2);
  int differ = 0;
  for (int i = 0; i < 100; ++i) {
    const double x = a();
    EXPECT_EQ(x, b());
    differ += x != c();
  }
  EXPECT_EQ(differ, 100);
}

}  // namespace
