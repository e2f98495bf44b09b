// The adaptive Runge-Kutta integrators with event location (dynamics/integrator.hpp).
#include "asperity/dynamics/integrator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "asperity/core/error.hpp"

namespace asperity::dynamics {
namespace {

// y' = lambda y.
class Decay final : public OdeProblem {
 public:
  explicit Decay(double lambda) : lambda_(lambda) {}
  [[nodiscard]] std::size_t size() const override { return 1; }
  void rhs(double, std::span<const double> y, std::span<double> dy) const override {
    dy[0] = lambda_ * y[0];
  }

 private:
  double lambda_;
};

// u'' = -u with events at v = 0; counts the events.
class Oscillator final : public OdeProblem {
 public:
  [[nodiscard]] std::size_t size() const override { return 2; }
  void rhs(double, std::span<const double> y, std::span<double> dy) const override {
    dy[0] = y[1];
    dy[1] = -y[0];
  }
  [[nodiscard]] std::size_t event_state() const override { return 1; }
  void on_event(double t, std::span<const double> y) override {
    event_t.push_back(t);
    event_v.push_back(y[1]);
  }
  std::vector<double> event_t;
  std::vector<double> event_v;
};

// y' = y^2 blows up at t = 1 from y(0) = 1.
class BlowUp final : public OdeProblem {
 public:
  [[nodiscard]] std::size_t size() const override { return 1; }
  void rhs(double, std::span<const double> y, std::span<double> dy) const override {
    dy[0] = y[0] * y[0];
  }
};

// y' = 1 for t < 1, y' = -1 after: a breakpoint at t = 1.
class Kink final : public OdeProblem {
 public:
  [[nodiscard]] std::size_t size() const override { return 1; }
  void rhs(double t, std::span<const double>, std::span<double> dy) const override {
    dy[0] = t < 1.0 ? 1.0 : -1.0;
  }
  [[nodiscard]] std::vector<double> breakpoints() const override { return {1.0}; }
};

double end_value(OdeProblem& p, std::vector<double> y0, double t1, const IntegratorOptions& o,
                 IntegratorStats* stats = nullptr) {
  std::vector<double> y = y0;
  auto s =
      integrate(p, y0, 0.0, t1, o, [&](const StepView& v) { y.assign(v.y.begin(), v.y.end()); });
  if (stats) *stats = s;
  return y[0];
}

TEST(IntegratorTest, BothMethodsMeetTheToleranceOnExponentialDecay) {
  for (Method m : {Method::bogacki_shampine_32, Method::dormand_prince_54}) {
    Decay p(-1.0);
    IntegratorOptions o{.method = m, .rtol = 1e-9, .atol = {1e-12}};
    const double y = end_value(p, {1.0}, 5.0, o);
    // Global error of a few hundred local errors of size rtol: 1e-7 relative is generous.
    EXPECT_NEAR(y / std::exp(-5.0), 1.0, 1e-7) << to_string(m);
  }
}

TEST(IntegratorTest, ErrorFallsWithTheToleranceAtTheMethodsOrder) {
  // Tolerance proportionality: ten times tighter rtol gives about ten times smaller
  // global error (within a factor of ~3) for both pairs, the behaviour of ode23/ode45.
  for (Method m : {Method::bogacki_shampine_32, Method::dormand_prince_54}) {
    Decay p1(-1.0), p2(-1.0);
    IntegratorOptions o1{.method = m, .rtol = 1e-6, .atol = {1e-12}};
    IntegratorOptions o2{.method = m, .rtol = 1e-8, .atol = {1e-12}};
    const double e1 = std::abs(end_value(p1, {1.0}, 5.0, o1) - std::exp(-5.0)) / std::exp(-5.0);
    const double e2 = std::abs(end_value(p2, {1.0}, 5.0, o2) - std::exp(-5.0)) / std::exp(-5.0);
    EXPECT_LT(e2, e1 / 10.0) << to_string(m);
    EXPECT_LT(e1, 1e-4) << to_string(m);
  }
}

TEST(IntegratorTest, HigherOrderTakesFewerSteps) {
  Decay p1(-1.0), p2(-1.0);
  IntegratorStats s1, s2;
  end_value(p1, {1.0}, 5.0, {.method = Method::bogacki_shampine_32, .rtol = 1e-9, .atol = {1e-12}},
            &s1);
  end_value(p2, {1.0}, 5.0, {.method = Method::dormand_prince_54, .rtol = 1e-9, .atol = {1e-12}},
            &s2);
  EXPECT_LT(s2.steps * 3, s1.steps);
}

TEST(IntegratorTest, ContinuousExtensionIsContinuousAndAccurate) {
  for (Method m : {Method::bogacki_shampine_32, Method::dormand_prince_54}) {
    Decay p(-1.0);
    IntegratorOptions o{.method = m, .rtol = 1e-10, .atol = {1e-14}};
    double worst_end = 0.0, worst_mid = 0.0;
    std::vector<double> out(1);
    integrate(p, std::vector<double>{1.0}, 0.0, 3.0, o, [&](const StepView& v) {
      v.dense(v.t, out);
      worst_end = std::max(worst_end, std::abs(out[0] - v.y[0]) / std::abs(v.y[0]));
      const double mid = 0.5 * (v.t_prev + v.t);
      v.dense(mid, out);
      worst_mid = std::max(worst_mid, std::abs(out[0] - std::exp(-mid)) / std::exp(-mid));
    });
    EXPECT_LT(worst_end, 1e-14) << to_string(m);  // the extension ends on the step's value
    EXPECT_LT(worst_mid, 1e-7) << to_string(m);
  }
}

TEST(IntegratorTest, EventsAreLocatedAtVelocityZeros) {
  for (Method m : {Method::bogacki_shampine_32, Method::dormand_prince_54}) {
    Oscillator p;
    IntegratorOptions o{.method = m, .rtol = 1e-10, .atol = {1e-12}};
    std::vector<double> event_u;
    const auto stats =
        integrate(p, std::vector<double>{0.0, 1.0}, 0.0, 20.0, o, [&](const StepView& v) {
          if (v.is_event) event_u.push_back(v.y[0]);
        });
    // v = cos t vanishes at pi/2 + k pi: six zeros in [0, 20].
    ASSERT_EQ(p.event_t.size(), 6u) << to_string(m);
    EXPECT_EQ(stats.events, 6u);
    for (std::size_t k = 0; k < p.event_t.size(); ++k) {
      EXPECT_NEAR(p.event_t[k], std::numbers::pi * (0.5 + static_cast<double>(k)), 1e-8);
      // The step is redone to end on the discrete solution's zero: v at round-off
      // (a few eps of |v| ~ 1).
      EXPECT_LE(std::abs(p.event_v[k]), 8 * std::numeric_limits<double>::epsilon());
      // The state is the one at the event's time: u = sin t = +-1 there, to the
      // integration tolerance (a step whose length was corrected after it was computed
      // would leave u from another time).
      EXPECT_NEAR(std::abs(event_u[k]), 1.0, 1e-8);
    }
  }
}

// v = -(t - 2)^3 (u' = v, v' = -3 (t - 2)^2) has a triple zero at t = 2: Newton's method
// converges only linearly there, so the location falls back on bisection of its bracket.
// The event still ends on v = 0 to round-off, at t = 2 to the cube root of the
// resolution in v, and u is the solution's value there.
class TripleZero final : public OdeProblem {
 public:
  [[nodiscard]] std::size_t size() const override { return 2; }
  void rhs(double t, std::span<const double>, std::span<double> dy) const override {
    dy[0] = -std::pow(t - 2.0, 3);
    dy[1] = -3.0 * (t - 2.0) * (t - 2.0);
  }
  [[nodiscard]] std::size_t event_state() const override { return 1; }
  void on_event(double t, std::span<const double> y) override {
    event_t.push_back(t);
    event_y.assign(y.begin(), y.end());
  }
  std::vector<double> event_t, event_y;
};

TEST(IntegratorTest, EventAtATripleZeroIsLocatedOnTheDiscreteSolution) {
  for (Method m : {Method::bogacki_shampine_32, Method::dormand_prince_54}) {
    TripleZero p;
    IntegratorOptions o{.method = m, .rtol = 1e-10, .atol = {1e-12}};
    // u = -(t - 2)^4/4 + 4, v = -(t - 2)^3 from t = 0: v(0) = 8.
    integrate(p, std::vector<double>{0.0, 8.0}, 0.0, 3.0, o, {});
    ASSERT_EQ(p.event_t.size(), 1u) << to_string(m);
    EXPECT_LE(std::abs(p.event_y[1]), 64 * std::numeric_limits<double>::epsilon() * 8.0);
    EXPECT_NEAR(p.event_t[0], 2.0, 1e-4);  // (64 eps 8)^(1/3) = 3e-5
    EXPECT_NEAR(p.event_y[0], 4.0 - std::pow(p.event_t[0] - 2.0, 4) / 4.0, 1e-9);
  }
}

// The rest rule: u' = v, v' = -50 v + 1e-9 sin(40 t) (t < 1), -50 v - 5 after, from
// v = -1. The kick decays and v crosses zero near t = 0.5 after u has moved by 0.02: a
// genuine reversal. Then v follows the forcing, changing sign every 0.08 with
// |v| ~ 1.6e-11 (resolved: atol_v = 1e-14) while u swings by ~8e-13, far below
// 10 atol_u = 1e-9: the mass is at rest and none of those zeros is an event, nor the
// start of the pull at t = 1.
class RestingMass final : public OdeProblem {
 public:
  [[nodiscard]] std::size_t size() const override { return 2; }
  void rhs(double t, std::span<const double> y, std::span<double> dy) const override {
    dy[0] = y[1];
    dy[1] = -50.0 * y[1] + (t < 1.0 ? 1e-9 * std::sin(40.0 * t) : -5.0);
  }
  [[nodiscard]] std::size_t event_state() const override { return 1; }
  [[nodiscard]] std::size_t event_rest_state() const override { return rest ? 0 : size(); }
  [[nodiscard]] std::vector<double> breakpoints() const override { return {1.0}; }
  void on_event(double t, std::span<const double>) override { event_t.push_back(t); }
  bool rest = true;
  std::vector<double> event_t;
};

TEST(IntegratorTest, VelocityZerosAtRestAreNotEvents) {
  const IntegratorOptions o{.rtol = 1e-6, .atol = {1e-10, 1e-14}};
  RestingMass p;
  integrate(p, std::vector<double>{0.0, -1.0}, 0.0, 2.0, o, {});
  ASSERT_EQ(p.event_t.size(), 1u);
  EXPECT_NEAR(p.event_t[0], 0.5, 0.1);  // e^{-50 t} = 1.6e-11 at t = 0.49
  // Without a rest state every resolved sign change of v is an event: the forced
  // dithering at rest gives about one every 0.08 between t = 0.5 and 1.
  RestingMass q;
  q.rest = false;
  integrate(q, std::vector<double>{0.0, -1.0}, 0.0, 2.0, o, {});
  EXPECT_GT(q.event_t.size(), 3u);
}

// y' = -1e4 (y - cos t): the solution follows cos t, so accuracy allows steps of ~0.01
// while stability (h |lambda| < 3.3 for DP54) holds them at ~3e-4: the stiffness test
// flags nearly all steps. y' = -y is not stiff: none.
class StiffRelaxation final : public OdeProblem {
 public:
  [[nodiscard]] std::size_t size() const override { return 1; }
  void rhs(double t, std::span<const double> y, std::span<double> dy) const override {
    dy[0] = -1e4 * (y[0] - std::cos(t));
  }
};

TEST(IntegratorTest, StiffnessTestFlagsStepsHeldByStability) {
  StiffRelaxation p;
  const auto s =
      integrate(p, std::vector<double>{1.0}, 0.0, 2.0, {.rtol = 1e-6, .atol = {1e-7}}, {});
  EXPECT_GT(static_cast<double>(s.stiff_steps), 0.9 * static_cast<double>(s.steps));
  Decay d(-1.0);
  const auto n =
      integrate(d, std::vector<double>{1.0}, 0.0, 5.0, {.rtol = 1e-9, .atol = {1e-12}}, {});
  EXPECT_EQ(n.stiff_steps, 0u);
}

TEST(IntegratorTest, StepsEndOnBreakpoints) {
  Kink p;
  IntegratorOptions o{.rtol = 1e-8, .atol = {1e-12}};
  bool hit = false;
  const double y = end_value(p, {0.0}, 2.0, o);
  integrate(p, std::vector<double>{0.0}, 0.0, 2.0, o,
            [&](const StepView& v) { hit = hit || v.t == 1.0; });
  EXPECT_TRUE(hit);
  EXPECT_NEAR(y, 0.0, 1e-12);  // exact: linear pieces, the kink on a step boundary
}

TEST(IntegratorTest, StepCollapseIsANumericalError) {
  BlowUp p;
  IntegratorOptions o{.rtol = 1e-6, .atol = {1e-7}};
  try {
    (void)end_value(p, {1.0}, 2.0, o);
    FAIL() << "no error";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("t = "), std::string::npos) << e.what();
  }
}

TEST(IntegratorTest, MaxStepIsRespected) {
  Decay p(-1.0);
  IntegratorOptions o{.rtol = 1e-3, .atol = {1e-3}, .max_step = 0.01};
  double worst = 0.0;
  integrate(p, std::vector<double>{1.0}, 0.0, 1.0, o,
            [&](const StepView& v) { worst = std::max(worst, v.t - v.t_prev); });
  EXPECT_LE(worst, 0.01 * (1.0 + 1e-12));
}

TEST(IntegratorTest, BadOptionsAreInvalidInput) {
  Decay p(-1.0);
  const std::vector<double> y0{1.0};
  EXPECT_THROW(integrate(p, y0, 0.0, 1.0, {.rtol = 0.0}, {}), InvalidInput);
  EXPECT_THROW(integrate(p, y0, 0.0, 1.0, {.rtol = 0.5}, {}), InvalidInput);
  EXPECT_THROW(integrate(p, y0, 0.0, 1.0, {.atol = {-1.0}}, {}), InvalidInput);
  EXPECT_THROW(integrate(p, y0, 0.0, 1.0, {.atol = {1e-7, 1e-7}}, {}), InvalidInput);
  EXPECT_THROW(integrate(p, y0, 1.0, 1.0, {}, {}), InvalidInput);
  EXPECT_THROW((void)parse_method("rk4"), InvalidInput);
  EXPECT_EQ(parse_method("ode23"), Method::bogacki_shampine_32);
}

}  // namespace
}  // namespace asperity::dynamics
