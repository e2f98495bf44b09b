// Quadrature and root-finding wrappers (core/numerics.hpp) against closed forms.
// Reference values are elementary antiderivatives and roots, written next to each
// check. Tolerances: the wrappers are asked for 1e-12 relative; smooth integrands
// reach it, so the checks use 1e-11 (a factor 10 for the error estimate's slack).
#include <gtest/gtest.h>

#include "../support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"

namespace asperity::core {
namespace {

using asperity::testing::rel;

using std::numbers::pi;

TEST(Integrate, GaussKronrodPolynomialAndTranscendental) {
  // int_0^2 x^3 dx = 4; int_0^pi sin = 2; int_0^1 e^x = e - 1.
  EXPECT_LT(rel(integrate([](double x) { return x * x * x; }, 0.0, 2.0).value, 4.0), 1e-14);
  EXPECT_LT(rel(integrate([](double x) { return std::sin(x); }, 0.0, pi).value, 2.0), 1e-11);
  EXPECT_LT(
      rel(integrate([](double x) { return std::exp(x); }, 0.0, 1.0).value, std::numbers::e - 1.0),
      1e-11);
}

TEST(Integrate, GaussKronrodInfiniteInterval) {
  // int_0^inf e^{-x^2} dx = sqrt(pi)/2 (the Gaussian integral of chapter 4's heights).
  const auto r = integrate([](double x) { return std::exp(-x * x); }, 0.0,
                           std::numeric_limits<double>::infinity());
  EXPECT_LT(rel(r.value, std::sqrt(pi) / 2.0), 1e-11);
  EXPECT_LT(r.error, 1e-9);
}

TEST(Integrate, ErrorEstimateIsReturnedAndSmall) {
  const auto r = integrate([](double x) { return 1.0 / (1.0 + x * x); }, 0.0, 1.0);
  EXPECT_LT(rel(r.value, pi / 4.0), 1e-11);  // atan(1)
  EXPECT_GE(r.error, 0.0);
  EXPECT_LT(r.error, 1e-10);
}

TEST(Integrate, EmptyAndReversedIntervals) {
  EXPECT_EQ(integrate([](double) { return 1.0; }, 3.0, 3.0).value, 0.0);
  EXPECT_THROW((void)integrate([](double) { return 1.0; }, 1.0, 0.0), NumericalError);
  EXPECT_THROW((void)integrate([](double) { return 1.0; }, std::nan(""), 1.0), NumericalError);
}

TEST(Integrate, NonFiniteIntegrandThrows) {
  EXPECT_THROW(
      (void)integrate([](double) { return std::numeric_limits<double>::quiet_NaN(); }, 0.0, 1.0),
      NumericalError);
}

TEST(IntegrateTanhSinh, EndpointSingularities) {
  // int_0^1 x^{-1/2} dx = 2 (integrable singularity); int_0^1 (1-x)^{1/2} = 2/3
  // (derivative singularity, the shape of the Mindlin branches); int_0^1 ln x = -1.
  EXPECT_LT(
      rel(integrate_tanh_sinh([](double x) { return 1.0 / std::sqrt(x); }, 0.0, 1.0).value, 2.0),
      1e-11);
  EXPECT_LT(rel(integrate_tanh_sinh([](double x) { return std::sqrt(1.0 - x); }, 0.0, 1.0).value,
                2.0 / 3.0),
            1e-11);
  EXPECT_LT(rel(integrate_tanh_sinh([](double x) { return std::log(x); }, 0.0, 1.0).value, -1.0),
            1e-11);
}

TEST(IntegrateTanhSinh, SingularitiesAtEndpointsAwayFromZero) {
  // int_2^3 (x-2)^{-1/2} dx = 2 and int_{-3}^{-2} (-2-x)^{-1/2} dx = 2: the same
  // singularities as above on intervals with |a|, |b| >= 0.5. Boost 1.74's one-argument
  // tanh_sinh mishandles the left end there (a missing `else` overwrites the accurate
  // abscissa, so f can be called at x = a: inf in release, an assertion in debug).
  // Tolerance: a one-argument f only sees x, which resolves the distance to an end at
  // |a| only to ~eps |a|; the unresolved piece of x^{-1/2} is 2 sqrt(eps |a|), 2e-8
  // relative here, so 1e-7. For ln the missing piece is ~eps |a| ln(eps |a|): 1e-11.
  const auto left = [](double x) { return 1.0 / std::sqrt(x - 2.0); };
  EXPECT_LT(rel(integrate_tanh_sinh(left, 2.0, 3.0).value, 2.0), 1e-7);
  const auto right = [](double x) { return 1.0 / std::sqrt(-2.0 - x); };
  EXPECT_LT(rel(integrate_tanh_sinh(right, -3.0, -2.0).value, 2.0), 1e-7);
  // int_{10}^{11} ln(x - 10) dx = -1; int_{1e3}^{1e3+1} sqrt(1e3 + 1 - x) dx = 2/3.
  EXPECT_LT(
      rel(integrate_tanh_sinh([](double x) { return std::log(x - 10.0); }, 10.0, 11.0).value, -1.0),
      1e-11);
  EXPECT_LT(
      rel(integrate_tanh_sinh([](double x) { return std::sqrt(1001.0 - x); }, 1000.0, 1001.0).value,
          2.0 / 3.0),
      1e-11);
}

TEST(IntegrateTanhSinh, NeverEvaluatesAtAnEndpoint) {
  // An interval found by a random search on which the unpatched Boost 1.74 path calls
  // f(a) exactly. int_a^b sqrt(x - a) dx = 2/3 (b - a)^{3/2}; the relative tolerance
  // 1e-6 covers the ~eps a / (b - a) = 1e-9 resolution of x - a near the ends.
  const double a = 9.0786803595606358;
  const double b = 9.0786826265127534;
  bool outside = false;
  const auto f = [&](double x) {
    if (!(x > a && x < b)) outside = true;
    return std::sqrt(std::max(x - a, 0.0));
  };
  const double value = integrate_tanh_sinh(f, a, b, 1e-10).value;
  EXPECT_FALSE(outside);
  EXPECT_LT(rel(value, 2.0 / 3.0 * std::pow(b - a, 1.5)), 1e-6);
}

TEST(IntegrateTanhSinh, InvalidInterval) {
  EXPECT_EQ(integrate_tanh_sinh([](double) { return 1.0; }, 2.0, 2.0).value, 0.0);
  EXPECT_THROW((void)integrate_tanh_sinh([](double) { return 1.0; }, 1.0, 0.0), NumericalError);
}

TEST(FindRoot, ClosedFormRoots) {
  // x^2 - 2 on [0, 2]: sqrt(2); cos x - x on [0, 1]: the Dottie number 0.7390851332151607.
  EXPECT_LT(rel(find_root([](double x) { return x * x - 2.0; }, 0.0, 2.0), std::sqrt(2.0)), 1e-14);
  EXPECT_LT(rel(find_root([](double x) { return std::cos(x) - x; }, 0.0, 1.0), 0.7390851332151607),
            1e-14);
  // A decreasing function works as well: 1/x - 4 on [0.1, 1] has the root 0.25.
  EXPECT_LT(rel(find_root([](double x) { return 1.0 / x - 4.0; }, 0.1, 1.0), 0.25), 1e-14);
}

TEST(FindRoot, RootAtAnEndpointIsReturnedExactly) {
  EXPECT_EQ(find_root([](double x) { return x - 1.0; }, 1.0, 3.0), 1.0);
  EXPECT_EQ(find_root([](double x) { return x - 3.0; }, 1.0, 3.0), 3.0);
}

TEST(FindRoot, NoBracketThrowsNamingWhatWasTried) {
  try {
    (void)find_root([](double x) { return x * x + 1.0; }, -1.0, 1.0, "test solve");
    FAIL() << "no exception for an interval without a sign change";
  } catch (const NumericalError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("test solve"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no sign change"), std::string::npos) << msg;
  }
  // A non-finite value at an end is not a bracket either.
  EXPECT_THROW((void)find_root([](double x) { return std::log(x); }, 0.0, -1.0), NumericalError);
}

TEST(FindRoot, IterationLimitThrows) {
  // Two iterations cannot reach 50 bits for this root.
  EXPECT_THROW(
      (void)find_root([](double x) { return std::exp(x) - 10.0; }, 0.0, 100.0, "capped", 50, 2),
      NumericalError);
}

}  // namespace
}  // namespace asperity::core
