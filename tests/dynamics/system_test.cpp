// The base-excited single-DOF system of Eq. 7.1 / Table 7.1 (dynamics/system.hpp).
#include "asperity/dynamics/system.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "asperity/core/error.hpp"
#include "asperity/dynamics/epb.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "linear_reference.hpp"

namespace asperity::dynamics {
namespace {

constexpr double kEps = 0.032;  // Table 7.2

SimulationOptions tight(double duration, Method m = Method::dormand_prince_54) {
  SimulationOptions o;
  o.duration = duration;
  o.integrator.method = m;
  o.integrator.rtol = 1e-11;
  o.integrator.atol = {1e-13};
  return o;
}

double max_relative_deviation(const Trajectory& tr,
                              const std::function<testing::State(double)>& exact) {
  double scale = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < tr.size(); ++i) scale = std::max(scale, std::abs(exact(tr.tau[i]).u));
  for (std::size_t i = 0; i < tr.size(); ++i) {
    worst = std::max(worst, std::abs(tr.u[i] - exact(tr.tau[i]).u));
  }
  return worst / scale;
}

// Shown by: "Frictionless runs match the closed-form impulse and harmonic responses of
// the damped oscillator to 1e-6 relative" (issue 6). Relative to the largest |u|.
TEST(DynamicsSystemTest, FrictionlessImpulseMatchesClosedForm) {
  const ImpulseExcitation imp{};  // Omega = 10 pi: a 0.1 pulse (section 7.4)
  for (Method m : {Method::dormand_prince_54, Method::bogacki_shampine_32}) {
    auto o = tight(60.0, m);
    if (m == Method::bogacki_shampine_32) o.integrator.rtol = 1e-10;
    const auto tr = simulate({.epsilon = kEps}, imp, NoFriction{}, o);
    const double dev = max_relative_deviation(
        tr, [&](double t) { return testing::impulse_response(kEps, 1.0, imp.Omega, t); });
    EXPECT_LT(dev, 1e-6) << to_string(m);
  }
}

TEST(DynamicsSystemTest, FrictionlessHarmonicMatchesClosedForm) {
  for (double f : {1.0, 0.15, 0.05}) {  // above, near and below resonance (f_n = 1/2pi)
    const HarmonicExcitation h{.frequency = f, .amplitude = 1.0};
    auto o = tight(80.0);
    o.output_interval = 0.01;  // also checks the continuous extension
    const auto tr = simulate({.epsilon = kEps}, h, NoFriction{}, o);
    const double dev = max_relative_deviation(tr, [&](double t) {
      return testing::harmonic_response(kEps, 1.0, 2.0 * std::numbers::pi * f, t);
    });
    EXPECT_LT(dev, 1e-6) << "f = " << f;
  }
}

TEST(DynamicsSystemTest, FrictionlessRampMatchesClosedForm) {
  // y = alpha tau: u = alpha tau - (free response from u0 = 0 - 0, v0 = -alpha... )
  // The particular solution of u'' + eps u' + u = alpha tau + eps alpha is alpha tau,
  // so u = alpha tau + free(-0, -alpha).
  const double alpha = 1.0;
  const auto tr = simulate({.epsilon = kEps}, RampExcitation{alpha}, NoFriction{}, tight(30.0));
  const double dev = max_relative_deviation(tr, [&](double t) {
    const auto h = testing::free_response(kEps, 0.0, -alpha, t);
    return testing::State{alpha * t + h.u, alpha + h.v};
  });
  EXPECT_LT(dev, 1e-6);
}

std::vector<std::pair<std::string, std::unique_ptr<FrictionModel>>> all_models() {
  std::vector<std::pair<std::string, std::unique_ptr<FrictionModel>>> m;
  m.emplace_back("none", std::make_unique<NoFriction>());
  m.emplace_back("coulomb", std::make_unique<RegularizedCoulomb>(RegularizedCoulombParameters{}));
  m.emplace_back("dankowicz", std::make_unique<Dankowicz>(DankowiczParameters{}));
  m.emplace_back("jenkins", make_jenkins(136.0, 1.5));
  m.emplace_back("iwan", make_segalman_iwan({.F_S = 1.5, .K_T = 136.0, .chi = -0.5, .beta = 0.1}));
  // A CFC-like saturating backbone (Cattaneo-Mindlin shape, Q = F (1 - (1 - x/s)^{3/2}))
  // standing in for the rough flat, with both memory rules.
  auto mindlin_like = std::make_shared<hysteresis::FunctionBackbone>(
      [](double x) { return x >= 0.02 ? 1.5 : 1.5 * (1.0 - std::pow(1.0 - x / 0.02, 1.5)); }, 1.5,
      1.5 * 1.5 / 0.02);
  m.emplace_back("physics-masing", std::make_unique<HysteresisFriction>(mindlin_like));
  m.emplace_back("physics-eq7.10", std::make_unique<HysteresisFriction>(
                                       mindlin_like, hysteresis::MemoryRule::reset_at_reversal));
  // The rough flat of Table 7.2 (rough), A0 = 1 cm^2, A = 18 um, P = 5 k A.
  auto rough = table_7_2_rough();
  rough.A0 = 1e-4;
  rough.P = 5.0 * 1e5 * 18e-6;
  const auto bb = epb_backbone(rough);
  m.emplace_back("physics-rough-flat", make_physics_based(bb, 1e5, 18e-6));
  m.emplace_back("physics-rough-flat-eq7.10",
                 make_physics_based(bb, 1e5, 18e-6, hysteresis::MemoryRule::reset_at_reversal));
  return m;
}

// Shown by: "Energy balance closes to 1e-6 of the input work for every friction model".
TEST(DynamicsSystemTest, EnergyBalanceClosesForEveryModelAndExcitation) {
  const std::vector<std::pair<std::string, Excitation>> cases{
      {"impulse", ImpulseExcitation{}},
      {"ramp", RampExcitation{1.0}},
      {"harmonic", HarmonicExcitation{}},
  };
  for (const auto& [mname, model] : all_models()) {
    for (const auto& [ename, exc] : cases) {
      auto o = tight(30.0);
      o.integrator.rtol = 1e-10;
      o.integrator.atol = {1e-12};
      const auto tr = simulate({.epsilon = kEps}, exc, *model, o);
      EXPECT_LT(tr.energy_balance_error(), 1e-6) << mname << " / " << ename;
      EXPECT_GT(tr.work_base.back(), 0.0) << mname << " / " << ename;
    }
  }
}

// The same target at the thesis's tolerances (rtol 1e-6, atol 1e-7), the settings of
// the shipped examples, with the default Dormand-Prince 5(4). MATLAB ode23's
// Bogacki-Shampine 3(2) at those tolerances leaves ~1e-6 (measured 0.9-1.1e-6 for the
// harmonic cases): its third-order global error in u enters the mechanical energy
// through the spring stretch u - y ~ 1 (the W states' own tolerance does not matter);
// ten times tighter tolerances bring it to 1e-7.
TEST(DynamicsSystemTest, EnergyBalanceClosesAtTheThesisTolerances) {
  const std::vector<std::pair<std::string, Excitation>> cases{
      {"impulse", ImpulseExcitation{}},
      {"ramp", RampExcitation{1.0}},
      {"harmonic", HarmonicExcitation{}},
  };
  for (const auto& [mname, model] : all_models()) {
    for (const auto& [ename, exc] : cases) {
      SimulationOptions o;
      o.duration = 30.0;
      const auto tr = simulate({.epsilon = kEps}, exc, *model, o);
      EXPECT_LT(tr.energy_balance_error(), 1e-6) << mname << " / " << ename << " dp54";
      o.integrator.method = Method::bogacki_shampine_32;
      o.integrator.rtol = 1e-7;
      o.integrator.atol = {1e-8};
      const auto tb = simulate({.epsilon = kEps}, exc, *model, o);
      EXPECT_LT(tb.energy_balance_error(), 1e-6) << mname << " / " << ename << " bs23";
    }
  }
}

// Eq. 7.6 keeps |z| <= delta; the integrated z overshoots by the integration error only
// (no projection hides it). With one atol, z is integrated with atol * delta
// (FrictionModel::internal_state_scale), so the overshoot is at the level of the
// tolerances: below 10 rtol, and smaller for tighter tolerances.
TEST(DynamicsSystemTest, DankowiczStateStaysWithinDeltaToTheTolerance) {
  // Large excitation: the contact slides back and forth, z approaches delta each time.
  const Dankowicz model({.F_max = 1.5, .delta = 0.011});
  for (Method m : {Method::bogacki_shampine_32, Method::dormand_prince_54}) {
    double previous = INFINITY;
    for (double rtol : {1e-6, 1e-9}) {
      SimulationOptions o;
      o.duration = 40.0;
      o.integrator.method = m;
      o.integrator.rtol = rtol;
      o.integrator.atol = {rtol / 10};
      const auto tr = simulate({.epsilon = kEps},
                               HarmonicExcitation{.frequency = 0.15, .amplitude = 20.0}, model, o);
      ASSERT_EQ(tr.internal.size(), 1u);
      ASSERT_EQ(tr.internal[0].size(), tr.size());
      double zmax = 0.0, Fmax = 0.0;
      for (std::size_t i = 0; i < tr.size(); ++i) {
        zmax = std::max(zmax, std::abs(tr.internal[0][i]));
        Fmax = std::max(Fmax, std::abs(tr.friction[i]));
        EXPECT_EQ(tr.friction[i], 1.5 * tr.internal[0][i] / 0.011);  // Eq. 7.7, unprojected
      }
      const double overshoot = zmax / 0.011 - 1.0;
      EXPECT_GT(zmax, 0.011 * (1 - 1e-3)) << to_string(m);  // it does slide
      EXPECT_LT(overshoot, 10 * rtol) << to_string(m) << " rtol " << rtol;
      EXPECT_LT(overshoot, previous) << to_string(m);
      previous = std::max(overshoot, 0.0);
      EXPECT_LE(Fmax, 1.5 * (1 + std::max(overshoot, 0.0)) * (1 + 1e-15));
    }
  }
}

// Events are located on the discrete solution: the state at an event has v = 0 to
// round-off, and it is the state at the event's time (not at a time shifted by an
// unfinished Newton correction).
TEST(DynamicsSystemTest, HysteresisModelsCommitAtEveryReversal) {
  const auto model = make_jenkins(136.0, 1.5);
  for (Method m : {Method::bogacki_shampine_32, Method::dormand_prince_54}) {
    SimulationOptions o;
    o.duration = 20.0;
    o.integrator.method = m;
    const auto tr = simulate({.epsilon = kEps}, HarmonicExcitation{}, *model, o);
    ASSERT_GT(tr.event_tau.size(), 30u);  // two reversals per cycle, 20 cycles
    // v at round-off: within 32 eps of max |v| + max |u''| tau_end (the location stops
    // when |v| is at 32 eps of its scale, or when the step's end is resolved to a few ulps
    // of tau, over which v changes by |u''| ulp; u'' from Eq. 7.1).
    double vmax = 0.0, amax = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < tr.size(); ++i) {
      vmax = std::max(vmax, std::abs(tr.v[i]));
      amax = std::max(amax,
                      std::abs(tr.y[i] - tr.u[i] + kEps * (tr.dy[i] - tr.v[i]) - tr.friction[i]));
      if (tr.is_event[i]) worst = std::max(worst, std::abs(tr.v[i]));
    }
    EXPECT_LE(worst, 32 * std::numeric_limits<double>::epsilon() * (vmax + amax * tr.tau.back()))
        << to_string(m);
    EXPECT_EQ(tr.event_tau.size(), tr.stats.events);
  }
}

// Velocity zeros below the tolerance are not reversals: the unit-pulse Coulomb mass
// creeps back to rest and then dithers at |v| ~ atol, which used to be located as
// hundreds of "reversals" at |u| ~ 1e-14. A reversal counts only once |v| has exceeded
// 10 atol since the previous one (integrator.hpp).
TEST(DynamicsSystemTest, NoSpuriousReversalsAtRest) {
  SimulationOptions o;
  o.duration = 400.0;
  o.output_interval = 0.05;
  o.locate_reversals = true;
  auto check_between = [](const Trajectory& tr, const std::string& what) {
    std::size_t last = 0;
    for (std::size_t i = 0; i < tr.size(); ++i) {
      if (!tr.is_event[i]) continue;
      double vmax = 0.0;
      for (std::size_t j = last; j < i; ++j) vmax = std::max(vmax, std::abs(tr.v[j]));
      // Samples every 0.05 miss the peak of |v| between them by at most
      // 1 - cos(pi f dt) = 4 % at f = 1.86: 0.9 of the 10 atol threshold.
      EXPECT_GT(vmax, 0.9 * 10 * 1e-7) << what << ": event at " << tr.tau[i];
      last = i;
    }
  };
  const auto tc = simulate({.epsilon = kEps}, ImpulseExcitation{}, RegularizedCoulomb({}), o);
  EXPECT_LT(tc.stats.events, 10u);  // overdamped creep: a few genuine reversals
  check_between(tc, "coulomb");
  // A hysteretic law that comes to rest: a Jenkins element (F_max 1.5, stiffness 136)
  // with heavy damping eps = 0.5. Its small-amplitude motion, at
  // sqrt(137)/(2 pi) = 1.86 cycles per unit tau, decays as exp(-eps tau/2) from |v| ~ 1
  // to 1e-6 by tau ~ 55; after that the mass is at rest and no reversal may be located.
  const auto jenkins = make_jenkins(136.0, 1.5);
  o.duration = 200.0;
  const auto tj = simulate({.epsilon = 0.5}, ImpulseExcitation{.amplitude = 5.0}, *jenkins, o);
  check_between(tj, "jenkins");
  ASSERT_GT(tj.event_tau.size(), 20u);
  EXPECT_LT(tj.event_tau.back(), 70.0);
  EXPECT_LT(static_cast<double>(tj.stats.events), 2 * 1.86 * 70.0);
}

TEST(DynamicsSystemTest, DimensionalScalesFollowSection72) {
  const DimensionalScales s{.m = 10.0, .k = 1e5, .A = 1e-3};
  EXPECT_DOUBLE_EQ(s.time(), 0.01);
  EXPECT_DOUBLE_EQ(s.force(), 100.0);
  EXPECT_DOUBLE_EQ(s.energy(), 0.1);
  EXPECT_DOUBLE_EQ(s.epsilon(32.0), 0.032);
  const auto c = s.coulomb(150.0, 6320.0);  // k~tan = k_tan A sqrt(k/m)
  EXPECT_DOUBLE_EQ(c.F_max, 1.5);
  EXPECT_NEAR(c.k_tan, 632.0, 1e-9);
  const auto d = s.dankowicz(150.0, 11e-6);
  EXPECT_DOUBLE_EQ(d.delta, 0.011);
}

TEST(DynamicsSystemTest, BadInputIsRejected) {
  SimulationOptions o;
  EXPECT_THROW((void)simulate({.epsilon = -0.1}, FreeVibration{}, NoFriction{}, o), InvalidInput);
  EXPECT_THROW((void)simulate({}, HarmonicExcitation{.frequency = 0.0}, NoFriction{}, o),
               InvalidInput);
  EXPECT_THROW((void)simulate({}, ImpulseExcitation{.Omega = -1.0}, NoFriction{}, o), InvalidInput);
  EXPECT_THROW((void)simulate({}, RampExcitation{0.0}, NoFriction{}, o), InvalidInput);
  o.duration = -1.0;
  EXPECT_THROW((void)simulate({}, FreeVibration{}, NoFriction{}, o), InvalidInput);
  EXPECT_THROW(DimensionalScales({.m = -1.0}).validate(), InvalidInput);
  EXPECT_THROW(Dankowicz({.F_max = 1.0, .delta = 0.0}), InvalidInput);
  EXPECT_THROW(RegularizedCoulomb({.F_max = -1.0}), InvalidInput);
}

}  // namespace
}  // namespace asperity::dynamics

namespace asperity::dynamics {
namespace {

// SEED_NOTES.md: the thesis's Eq. 7.10 (u_max reset at every reversal) equals Masing's
// rules for steady symmetric cycles, not for transients.
TEST(DynamicsSystemTest, Eq710EqualsMasingInSteadyCyclesOnly) {
  auto bb = std::make_shared<hysteresis::FunctionBackbone>(
      [](double x) { return x >= 0.02 ? 1.5 : 1.5 * (1.0 - std::pow(1.0 - x / 0.02, 1.5)); }, 1.5,
      1.5 * 1.5 / 0.02);
  const HysteresisFriction masing(bb), eq710(bb, hysteresis::MemoryRule::reset_at_reversal);
  SimulationOptions o;
  o.duration = 60.0;
  o.output_interval = 0.001;
  o.integrator.rtol = 1e-9;
  o.integrator.atol = {1e-11};
  auto loop_energy = [&](const FrictionModel& m) {
    double W = 0.0, u = 0.0;
    const auto tr = simulate({.epsilon = kEps}, HarmonicExcitation{}, m, o);
    // Work of the friction force over the last 5 periods (from the integrated state).
    const std::size_t n = tr.size() - 1;
    std::size_t i0 = n;
    while (tr.tau[i0] > tr.tau[n] - 5.0) --i0;
    W = (tr.work_friction[n] - tr.work_friction[i0]) / 5.0;
    for (std::size_t i = i0; i <= n; ++i) u = std::max(u, std::abs(tr.u[i]));
    return std::pair{W, u};
  };
  const auto [Wm, um] = loop_energy(masing);
  const auto [We, ue] = loop_energy(eq710);
  EXPECT_NEAR(We / Wm, 1.0, 1e-3);
  EXPECT_NEAR(ue / um, 1.0, 1e-3);
  // Transient: the decaying impulse response differs (Eq. 7.10 forgets the previous
  // branch and restarts from the backbone at each reversal).
  // A pulse of 10 A drives the contact into macro-slip (|u| > the slip displacement).
  o.duration = 10.0;
  const ImpulseExcitation pulse{.amplitude = 10.0};
  const auto tm = simulate({.epsilon = kEps}, pulse, masing, o);
  const auto te = simulate({.epsilon = kEps}, pulse, eq710, o);
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < std::min(tm.size(), te.size()); ++i) {
    if (tm.is_event[i] || te.is_event[i]) continue;
    diff = std::max(diff, std::abs(tm.u[i] - te.u[i]));
    scale = std::max(scale, std::abs(tm.u[i]));
  }
  EXPECT_GT(diff / scale, 0.01);
}

}  // namespace
}  // namespace asperity::dynamics
