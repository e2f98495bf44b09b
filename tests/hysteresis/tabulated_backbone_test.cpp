// The tabulated backbone on curves with closed forms: its verified bound, the fast
// look-up against the reference interpolant, integrals, the inverse, knots, and bad input.
#include "asperity/hysteresis/tabulated_backbone.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../support.hpp"
#include "asperity/core/error.hpp"

namespace asperity::hysteresis {
namespace {

using asperity::testing::rel;

// Cattaneo-Mindlin loading (B.15 inverted): Q = F (1 - (1 - x/s)^{3/2}) up to the slip
// displacement s, F beyond; its integral F (x - 2s/5 (1 - (1 - x/s)^{5/2})).
struct Mindlin {
  double F = 2.0;
  double s = 3e-6;
  // expm1/log1p: 1 - (1 - x/s)^{3/2} loses digits as x/s -> 0.
  double Q(double x) const { return x >= s ? F : -F * std::expm1(1.5 * std::log1p(-x / s)); }
  double integral(double x) const {
    return x >= s ? F * (0.6 * s + (x - s))
                  : F * (x - 0.4 * s * (1.0 - std::pow(1.0 - x / s, 2.5)));
  }
  BackboneTabulation tabulation() const {
    BackboneTabulation in;
    in.sample = [*this](double x) {
      const double r = std::sqrt(1.0 - x / s);
      return BackboneSample{Q(x), 1.5 * F / s * r, -0.75 * F / (s * s) / r};  // B.15
    };
    in.initial_stiffness = 1.5 * F / s;
    in.initial_curvature = -0.75 * F / (s * s);
    in.limit = F;
    in.x_end = s;
    return in;
  }
};

// Log-spaced points from 1e-9 of the end to twice beyond it.
template <class F>
double worst_relative_error(const TabulatedBackbone& t, F exact) {
  double worst = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double x = t.table_end() * std::pow(10.0, -9.0 + 9.3 * i / 400.0);
    worst = std::max(worst, rel(t.force(x), exact(x)));
  }
  return worst;
}

TEST(TabulatedBackbone, MindlinWithinItsVerifiedBound) {
  const Mindlin m;
  const TabulatedBackbone t(m.tabulation());
  EXPECT_LE(t.verified_error(), 2e-9);  // reference (1e-9) + fast cells (1e-9)
  // The bound is checked at midpoints only; the quintic Hermite error peaks there, so the
  // whole range stays within a small multiple of it (the target: 1e-8).
  EXPECT_LE(worst_relative_error(t, [&](double x) { return m.Q(x); }), 1e-8);
  for (double x : {1e-9, 0.3e-6, 1.5e-6, 2.999e-6, 3e-6, 7e-6}) {
    // Int Q: 5-point Gauss-Legendre is exact on each cell's polynomial, so the integral
    // carries the interpolant's relative error.
    EXPECT_LT(rel(t.integral(x), m.integral(x)), 1e-8) << x;
    if (x < m.s) {
      // The inverse is ill-conditioned only next to s, where Q_l' -> 0.
      EXPECT_LT(rel(t.displacement(m.Q(x)), x), 1e-7) << x;
    }
  }
  EXPECT_EQ(t.force(0.0), 0.0);
  EXPECT_EQ(t.force(1.0), m.F);
  EXPECT_EQ(t.force(std::numeric_limits<double>::infinity()), m.F);
}

TEST(TabulatedBackbone, FastCellsAgreeWithTheReferenceInterpolant) {
  const TabulatedBackbone t(Mindlin{}.tabulation());
  EXPECT_GT(t.fast_cells(), 0u);
  double worst = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double x = t.table_end() * std::pow(10.0, -12.0 + 12.3 * i / 2000.0);
    worst = std::max(worst, rel(t.evaluate_non_negative(x), t.evaluate_reference(x)));
  }
  EXPECT_LE(worst, 2e-9);
}

// Q = F (1 - e^{-x/a}) up to the knot x_k, then C1 with a new length b: the second
// derivative jumps at x_k.
struct Kinked {
  double F = 1.0, a = 1.0, xk = 0.7, b = 0.25;
  double Qk() const { return F * (1.0 - std::exp(-xk / a)); }
  double slope_k() const { return F / a * std::exp(-xk / a); }
  double Q(double x) const {
    if (x <= xk) return F * (1.0 - std::exp(-x / a));
    return Qk() + slope_k() * b * -std::expm1(-(x - xk) / b);
  }
  BackboneSample sample(double x) const {
    if (x <= xk) {
      const double e = std::exp(-x / a);
      return {F * (1.0 - e), F / a * e, -F / (a * a) * e};
    }
    const double e = std::exp(-(x - xk) / b);
    return {Q(x), slope_k() * e, -slope_k() / b * e};
  }
  BackboneTabulation tabulation(std::vector<double> knots) const {
    BackboneTabulation in;
    in.sample = [*this](double x) { return sample(x); };
    in.initial_stiffness = F / a;
    in.initial_curvature = -F / (a * a);
    in.limit = Qk() + slope_k() * b;
    in.x_end = xk + 40.0 * b;  // e^{-40} = 4e-18: saturated
    in.knots = std::move(knots);
    return in;
  }
};

TEST(TabulatedBackbone, KnotsKeepTheBoundAcrossAJumpOfTheCurvature) {
  const Kinked k;
  const TabulatedBackbone t(k.tabulation({k.xk}));
  EXPECT_LE(worst_relative_error(t, [&](double x) { return k.Q(x); }), 1e-8);
  for (double x : {k.xk * (1 - 1e-9), k.xk, k.xk * (1 + 1e-9)}) {
    EXPECT_LT(rel(t.force(x), k.Q(x)), 1e-8);
  }
}

TEST(TabulatedBackbone, CellsHoldingTwoKnotsDeferToTheReference) {
  // Two knots 1e-5 apart (the curve is smooth at the second; a knot is only allowed to be
  // where it is not): at most 2^6 cells per octave cannot separate them.
  const Kinked k;
  const TabulatedBackbone t(k.tabulation({k.xk, k.xk * (1 + 1e-5)}));
  EXPECT_GE(t.fallback_cells(), 1u);
  EXPECT_LE(worst_relative_error(t, [&](double x) { return k.Q(x); }), 1e-8);
  for (double f : {1.0, 1.0 + 3e-6, 1.0 + 1e-5, 1.0 + 2e-5}) {
    EXPECT_LT(rel(t.force(k.xk * f), k.Q(k.xk * f)), 1e-8) << f;
  }
}

TEST(TabulatedBackbone, BadInputIsRefused) {
  const auto good = Kinked{}.tabulation({});
  auto with = [&](auto change) {
    auto in = good;
    change(in);
    return in;
  };
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) { in.sample = nullptr; })), InvalidInput);
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) { in.limit = 0.0; })), InvalidInput);
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) { in.initial_stiffness = -1.0; })),
               InvalidInput);
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) { in.x_end = std::nan(""); })), InvalidInput);
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) { in.knots = {20.0}; })), InvalidInput);
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) { in.x_end = 1e-300; })), InvalidInput);
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) { in.x_end = 1e150; })), InvalidInput);
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) { in.rel_tol = 0.1; })), InvalidInput);
  // A sample that is not finite is a numerical failure, not a table.
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) {
                 in.sample = [](double) { return BackboneSample{std::nan(""), 1.0, 0.0}; };
               })),
               NumericalError);
  // A curve the table cannot resolve within its size limit: a jump in value (Q_l must be
  // continuous) without a knot.
  EXPECT_THROW(TabulatedBackbone(with([](auto& in) {
                 in.sample = [](double x) {
                   return BackboneSample{x < 0.5 ? x : x + 0.1, 1.0, 0.0};
                 };
                 in.max_intervals = 256;
               })),
               NumericalError);
  const TabulatedBackbone t(good);
  EXPECT_THROW((void)t.force(-1.0), InvalidInput);
  EXPECT_THROW((void)t.force(std::nan("")), InvalidInput);
  EXPECT_TRUE(std::isnan(t.evaluate_non_negative(std::nan(""))));
  EXPECT_THROW((void)t.displacement(t.limit()), InvalidInput);
}

}  // namespace
}  // namespace asperity::hysteresis
