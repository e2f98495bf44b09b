// Friction-force models of chapter 7 (dynamics/friction_model.hpp).
#include "asperity/dynamics/friction_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/dynamics/analysis.hpp"
#include "asperity/dynamics/epb.hpp"
#include "asperity/dynamics/system.hpp"
#include "asperity/hysteresis/backbones.hpp"

namespace asperity::dynamics {
namespace {

TEST(FrictionModelTest, RegularizedCoulombIsEq73) {
  const RegularizedCoulomb c({.F_max = 1.5, .k_tan = 6.32});  // Table 7.2
  EXPECT_DOUBLE_EQ(c.force(0.3, 0.0, {}), 0.0);
  EXPECT_DOUBLE_EQ(c.force(0.0, 0.1, {}), 1.5 * std::tanh(0.632));
  EXPECT_DOUBLE_EQ(c.force(0.0, -0.1, {}), -1.5 * std::tanh(0.632));
  EXPECT_NEAR(c.force(0.0, 100.0, {}), 1.5, 1e-15);
  EXPECT_FALSE(c.uses_reversal_events());
}

TEST(FrictionModelTest, DankowiczRatesAreEq76) {
  const Dankowicz d({.F_max = 1.5, .delta = 0.011});
  std::vector<double> z{0.005}, dz(1);
  d.internal_rates(0.0, 2.0, z, dz);
  EXPECT_DOUBLE_EQ(dz[0], 2.0 * (1.0 - 0.005 / 0.011));
  d.internal_rates(0.0, -2.0, z, dz);
  EXPECT_DOUBLE_EQ(dz[0], -2.0 * (1.0 + 0.005 / 0.011));
  EXPECT_DOUBLE_EQ(d.force(0.0, 0.0, z), 1.5 * 0.005 / 0.011);  // Eq. 7.7
  // At z = delta the internal state stops growing: |z| <= delta is invariant.
  z[0] = 0.011;
  d.internal_rates(0.0, 3.0, z, dz);
  EXPECT_DOUBLE_EQ(dz[0], 0.0);
  // Beyond delta (an integration error) Eq. 7.6 pulls z back: z' = -|v| (z/delta - 1),
  // and Eq. 7.7 is evaluated as printed, so the overshoot shows in the force.
  z[0] = 0.0111;
  d.internal_rates(0.0, 3.0, z, dz);
  EXPECT_NEAR(dz[0], -3.0 * (0.0111 / 0.011 - 1.0), 1e-15);
  EXPECT_DOUBLE_EQ(d.force(0.0, 0.0, z), 1.5 * 0.0111 / 0.011);
  EXPECT_EQ(d.internal_states(), 1u);
  EXPECT_DOUBLE_EQ(d.internal_state_scale(0), 0.011);
}

TEST(FrictionModelTest, HysteresisFrictionFollowsMasingAndCommitsReversals) {
  HysteresisFriction h(std::make_shared<hysteresis::JenkinsBackbone>(100.0, 1.0));
  EXPECT_DOUBLE_EQ(h.force(0.005, 1.0, {}), 0.5);
  EXPECT_DOUBLE_EQ(h.force(0.05, 1.0, {}), 1.0);  // slid
  h.commit_reversal(0.05);
  EXPECT_NEAR(h.force(0.045, -1.0, {}), 0.5, 1e-12);  // unloading with the initial stiffness
  EXPECT_DOUBLE_EQ(h.force(0.0, -1.0, {}), -1.0);     // slides the other way
  auto copy = h.clone();
  h.reset();
  EXPECT_DOUBLE_EQ(h.force(0.0, -1.0, {}), 0.0);
  EXPECT_DOUBLE_EQ(copy->force(0.0, -1.0, {}), -1.0);  // a clone keeps its memory
}

TEST(FrictionModelTest, ReversalRuleOfEq710ForgetsOlderLoops) {
  // Masing memory keeps the outer loop; Eq. 7.10 restarts at the last reversal from the
  // backbone value there, as after a virgin loading to it (masing.hpp).
  auto Ql = [](double x) { return 1.0 - std::exp(-x); };
  auto bb = std::make_shared<hysteresis::FunctionBackbone>(Ql, 1.0, 1.0);
  HysteresisFriction masing(bb), reset(bb, hysteresis::MemoryRule::reset_at_reversal);
  for (auto* m : {&masing, &reset}) {
    m->commit_reversal(2.0);
    m->commit_reversal(-1.0);
  }
  // Masing: the reloading branch from (-1, Q_l(2) - 2 Q_l(1.5)), closing at 2.
  const double Q_r = Ql(2.0) - 2.0 * Ql(1.5);
  EXPECT_NEAR(masing.force(0.5, 1.0, {}), Q_r + 2.0 * Ql(0.75), 1e-12);
  EXPECT_NEAR(masing.force(1.5, 1.0, {}), Q_r + 2.0 * Ql(1.25), 1e-12);
  // Eq. 7.10 with u_max = 1: -Q(-u, u_max) = -Q_l(1) + 2 Q_l((1 + u)/2) on [-1, 1], then
  // the virgin curve.
  EXPECT_NEAR(reset.force(0.5, 1.0, {}), -Ql(1.0) + 2.0 * Ql(0.75), 1e-12);
  EXPECT_NEAR(reset.force(1.5, 1.0, {}), Ql(1.5), 1e-12);
}

// Segalman (2005), J. Appl. Mech. 72:752-760, Eq. 20-23: phi_max, R, S from
// (F_S, K_T, chi, beta); the backbone has slope K_T at 0 and reaches F_S at phi_max.
TEST(FrictionModelTest, SegalmanIwanBackboneIsConsistent) {
  const SegalmanIwanParameters p{.F_S = 2.0, .K_T = 50.0, .chi = -0.5, .beta = 0.3};
  const SegalmanBackbone b(p);
  const double h = 1e-9;
  EXPECT_NEAR(b.force(h) / h, 50.0, 50.0 * 1e-4);  // K_T (slope ~ u^{chi+1} correction)
  EXPECT_NEAR(b.force(b.phi_max() * (1 - 1e-12)), 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(b.force(2.0 * b.phi_max()), 2.0);
  // The density integrates to the stiffness: Int rho = R phi_max^{chi+1}/(chi+1) + S.
  EXPECT_NEAR(b.R() * std::pow(b.phi_max(), 0.5) / 0.5 + b.S(), 50.0, 1e-10);
  // Analytic integral against quadrature.
  for (double x : {0.3 * b.phi_max(), b.phi_max(), 1.7 * b.phi_max()}) {
    const double q = core::integrate([&](double s) { return b.force(s); }, 0.0, x, 1e-13).value;
    EXPECT_NEAR(b.integral(x), q, 1e-10 * q) << x;
  }
  EXPECT_NEAR(b.force(b.displacement(1.3)), 1.3, 1e-10);
  EXPECT_THROW(SegalmanBackbone({.chi = -1.0}), InvalidInput);
  EXPECT_THROW(SegalmanBackbone({.beta = -0.1}), InvalidInput);
}

TEST(FrictionModelTest, SegalmanIwanDissipationPowerLaw) {
  // Segalman 2005, Eq. 29: at small amplitude the energy per cycle grows as
  // F0^{3+chi}, equivalently displacement^{3+chi}. Local slope over a decade at
  // 1e-4 phi_max: within 1e-3 of 3 + chi.
  const SegalmanBackbone b({.F_S = 1.0, .K_T = 1.0, .chi = -0.4, .beta = 0.2});
  const double x1 = 1e-4 * b.phi_max(), x2 = 1e-3 * b.phi_max();
  const double slope =
      std::log(hysteresis::energy_per_cycle(b, x2) / hysteresis::energy_per_cycle(b, x1)) /
      std::log(10.0);
  EXPECT_NEAR(slope, 2.6, 1e-3);
}

// Issue 6, "Coulomb and Jenkins limits": the physics-based law with CFC asperities
// (constant mu) saturates at mu P; far beyond its slip displacement it acts as the
// Jenkins element with the same sliding force and initial stiffness. Shown by time
// integration of Eq. 7.1 with both laws under the same large harmonic base motion.
TEST(FrictionModelTest, RoughFlatWithCfcApproachesJenkinsAtLargeAmplitude) {
  auto c = table_7_2_rough();
  c.model = contact::ModelName::cfc;
  c.friction.mu_cfc = 0.3;
  c.A0 = 1e-4;  // the assumptions of docs/dynamics.md: A0 = 1 cm^2, P = 9 N,
  c.P = 9.0;    // k = 1e5 N/m, A = 18 um
  const auto bb = epb_backbone(c);
  EXPECT_NEAR(bb->limit() / (0.3 * 9.0), 1.0, 1e-3);  // Q*_max = 0.3 P* for CFC (SEED_NOTES)
  const double k = 1e5, A = 18e-6;
  const auto physics = make_physics_based(bb, k, A);
  const auto jenkins = make_jenkins(bb->initial_stiffness() / k, bb->limit() / (k * A));
  const double F = jenkins->max_force();                  // 1.5
  const double slip = F / (bb->initial_stiffness() / k);  // Jenkins slip displacement 0.0081

  SimulationOptions o;
  o.output_interval = 0.01;
  o.integrator.rtol = 1e-8;
  o.integrator.atol = {1e-10};
  // Base motion at f~ = 0.1 (below resonance), amplitudes 5, 50, 500: the mass slides
  // back and forth over ~1e3, 1e4 and 1e5 slip displacements.
  double previous_dev = 1.0, previous_energy = 1.0;
  for (double a : {5.0, 50.0, 500.0}) {
    const HarmonicExcitation h{.frequency = 0.1, .amplitude = a};
    o.duration = 60.0;  // the last 2 of 6 periods (the same for both laws)
    const auto tp = simulate({.epsilon = 0.032}, h, *physics, o);
    const auto tj = simulate({.epsilon = 0.032}, h, *jenkins, o);
    const auto lp = steady_loop(tp, 10.0, 2);
    const auto lj = steady_loop(tj, 10.0, 2);
    ASSERT_GT(lj.displacement_amplitude, 10 * slip) << a;  // gross slip each cycle
    // Loop force deviation: the two friction forces compared along the path in the
    // F-u plane over the last two periods, sum |F_p - F_j| |du| / sum |F_j| |du| on the
    // uniform samples (both runs sample the same times). The forces differ only within
    // a few slip displacements of each reversal, where the rough flat's CFC backbone
    // rounds the Jenkins corner, so the deviation scales as slip/amplitude.
    auto on_grid = [](const Trajectory& tr) {  // (u, F) at the uniform samples from 40
      std::vector<std::pair<double, double>> f;
      for (std::size_t i = 0; i < tr.size(); ++i) {
        if (tr.is_event[i] || tr.tau[i] < 40.0) continue;
        const double n = tr.tau[i] / 0.01;
        if (std::abs(n - std::round(n)) < 1e-6) f.emplace_back(tr.u[i], tr.friction[i]);
      }
      return f;
    };
    const auto fp = on_grid(tp), fj = on_grid(tj);
    ASSERT_EQ(fp.size(), fj.size());
    ASSERT_GT(fp.size(), 1000u);
    double num = 0.0, den = 0.0;
    for (std::size_t i = 1; i < fp.size(); ++i) {
      const double du = std::abs(fj[i].first - fj[i - 1].first);
      num += std::abs(fp[i].second - fj[i].second) * du;
      den += std::abs(fj[i].second) * du;
    }
    const double dev = num / den;
    const double amp = std::abs(lp.displacement_amplitude / lj.displacement_amplitude - 1.0);
    const double energy = std::abs(lp.energy_per_cycle / lj.energy_per_cycle - 1.0);
    // The corner spans ~1-2 slip displacements at each of the two reversals of a path
    // 4 x amplitude long, with a force difference below F: dev < 2 slip/amplitude
    // (measured 0.6-0.8 slip/amplitude at amplitudes of 8, 96 and 1040).
    EXPECT_LT(dev, 2.0 * slip / lj.displacement_amplitude) << a;
    // Response amplitude and dissipation of the two laws agree to 1 % already at ~1000
    // slip displacements (measured 0.5 %) and approach each other as the amplitude grows.
    EXPECT_LT(amp, 0.01) << a;
    EXPECT_LT(energy, 0.01) << a;
    EXPECT_LT(dev, previous_dev) << a;
    EXPECT_LT(energy, previous_energy) << a;
    previous_dev = dev;
    previous_energy = energy;
  }
}

TEST(FrictionModelTest, PhysicsBasedScalesAnSiBackbone) {
  // Q(x) in SI: Jenkins 1e7 N/m, 150 N. With k = 1e5 N/m and A = 1e-3 m the model sees
  // F_s(u) = Q(A u)/(k A): stiffness 1e7 A / (k A) = 100, limit 150/(k A) = 1.5.
  auto si = std::make_shared<hysteresis::JenkinsBackbone>(1e7, 150.0);
  const auto m = make_physics_based(si, 1e5, 1e-3);
  EXPECT_NEAR(m->force(0.01, 1.0, {}), 1.0, 1e-12);
  EXPECT_NEAR(m->max_force(), 1.5, 1e-12);
  EXPECT_THROW((void)make_physics_based(si, -1.0, 1.0), InvalidInput);
}

}  // namespace
}  // namespace asperity::dynamics
