// Masing hysteresis engine: branches against closed forms, loop closing, inverse,
// and properties over random histories.
#include <gtest/gtest.h>

#include "../support.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>

#include "asperity/contact/mindlin.hpp"
#include "asperity/core/error.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/hysteresis/masing.hpp"
#include "asperity/hysteresis/tabulated_backbone.hpp"

namespace asperity::hysteresis {
namespace {

// Micro-scale experiment 1 of Table 3.2 with CEB's mu: any Mindlin contact will do.
contact::MindlinContact mindlin() {
  return contact::MindlinContact(0.528, 35.0, 24.32e9, 83.25e-6);
}

std::shared_ptr<const Backbone> mindlin_backbone() {
  return std::make_shared<MindlinBackbone>(mindlin());
}

// Fine path from a to b (excluding a).
std::vector<double> segment(double a, double b, int n) {
  std::vector<double> out;
  for (int i = 1; i <= n; ++i) out.push_back(a + (b - a) * i / n);
  return out;
}

TEST(Masing, SymmetricCycleEqualsMindlinDeresiewicz) {
  // Unloading/reloading of Cattaneo-Mindlin (B.16/B.17 solved for Q) is the Masing
  // construction on the B.15 backbone.
  const auto c = mindlin();
  const double dm = 0.6 * c.slip_displacement();
  Hysteresis h(mindlin_backbone());
  for (double x : segment(0.0, dm, 50))
    EXPECT_NEAR(h.update(x), c.loading_force(x), 1e-12 * c.Q_max());
  for (double x : segment(dm, -dm, 100)) {
    EXPECT_NEAR(h.update(x), c.unloading_force(x, dm), 1e-12 * c.Q_max());
  }
  for (double x : segment(-dm, dm, 100)) {
    EXPECT_NEAR(h.update(x), c.reloading_force(x, dm), 1e-12 * c.Q_max());
  }
  // Independent check through B.16: the displacement for the force on the unloading branch.
  Hysteresis h2(mindlin_backbone());
  h2.update(dm);
  const double Qm = h2.Q();
  for (double x : segment(dm, -dm, 20)) {
    const double Q = h2.update(x);
    EXPECT_NEAR(c.unloading_displacement(Q, Qm), x, 1e-10 * dm);
  }
}

TEST(Masing, LoopClosingForgetsInnerLoop) {
  const auto bb = mindlin_backbone();
  const double s = mindlin().slip_displacement();
  Hysteresis h(bb);
  h.update(0.8 * s);   // virgin to A
  h.update(-0.7 * s);  // reversal at A, down to D (short of -A)
  h.update(0.3 * s);   // reversal at D, up to B
  h.update(-0.1 * s);  // reversal at B, down to C
  ASSERT_EQ(h.reversals().size(), 3u);
  // Up from C past B: the inner loop B-C closes and the path continues on the branch
  // that started at D.
  const double QA = bb->force(0.8 * s);
  const double QD = QA - 2.0 * bb->force(0.75 * s);  // unloading branch from A at D
  const double x = 0.5 * s;
  const double expected = QD + 2.0 * bb->force((x + 0.7 * s) / 2.0);
  EXPECT_NEAR(h.update(x), expected, 1e-12 * QA);
  EXPECT_EQ(h.reversals().size(), 2u);  // A and D remain
  // Past A: back on the virgin curve, nothing remembered.
  EXPECT_NEAR(h.update(0.9 * s), bb->force(0.9 * s), 1e-12 * QA);
  EXPECT_TRUE(h.reversals().empty());
}

TEST(Masing, ForceBetweenEventsMatchesUpdate) {
  // The dynamics interface: force(x) const between events, commit_reversal at events.
  Hysteresis a(mindlin_backbone());
  Hysteresis b(mindlin_backbone());
  const double s = mindlin().slip_displacement();
  const std::vector<double> turns{0.7 * s, -0.4 * s, 0.2 * s, -0.9 * s, 0.5 * s};
  double x0 = 0.0;
  for (double turn : turns) {
    for (double x : segment(x0, turn, 25)) {
      EXPECT_DOUBLE_EQ(b.force(x), a.update(x));
    }
    b.commit_reversal(turn);
    x0 = turn;
  }
}

TEST(Masing, PeekEqualsUpdateOnACopy) {
  // peek(x) is what update(x) returns, without changing the state: along a branch (the
  // inline fast path), at a reversal and through loop closing (the slow path on a copy).
  Hysteresis h(mindlin_backbone());
  const double s = mindlin().slip_displacement();
  const std::vector<double> path{0.3 * s,  0.7 * s, -0.4 * s, 0.1 * s, 0.2 * s,
                                 -0.1 * s, 0.5 * s, 0.8 * s,  -0.9 * s};
  for (double x : path) {
    for (double probe : {x, x + 0.05 * s, x - 0.05 * s, 1.5 * s, -1.5 * s}) {
      Hysteresis copy = h;
      const double q = h.peek(probe);
      EXPECT_EQ(q, copy.update(probe));
    }
    const double x_before = h.x(), q_before = h.Q();
    const std::size_t stack_before = h.reversals().size();
    (void)h.peek(-x);
    EXPECT_EQ(h.x(), x_before);
    EXPECT_EQ(h.Q(), q_before);
    EXPECT_EQ(h.reversals().size(), stack_before);
    h.update(x);
  }
}

// Cattaneo-Mindlin loading tabulated (B.15 inverted: Q = F (1 - (1 - x/s)^{3/2}) up to
// the slip displacement s), so that peek is also checked on the inline table look-up.
std::shared_ptr<const TabulatedBackbone> tabulated_mindlin() {
  constexpr double F = 2.0, s = 3e-6;
  BackboneTabulation in;
  in.sample = [](double x) {
    const double r = std::sqrt(1.0 - x / s);
    return BackboneSample{-F * std::expm1(1.5 * std::log1p(-x / s)), 1.5 * F / s * r,
                          -0.75 * F / (s * s) / r};
  };
  in.initial_stiffness = 1.5 * F / s;
  in.initial_curvature = -0.75 * F / (s * s);
  in.limit = F;
  in.x_end = s;
  return std::make_shared<TabulatedBackbone>(in);
}

// The three force paths of Hysteresis::backbone_force: 0 an analytic backbone (virtual
// call), 1 a table (inline look-up), 2 a table scaled to SI.
std::shared_ptr<const Backbone> force_path_backbone(int which) {
  if (which == 0) return mindlin_backbone();
  if (which == 1) return tabulated_mindlin();
  return std::make_shared<ScaledBackbone>(tabulated_mindlin(), 1e-3 / 3e-6, 5e2);
}

// peek(x) against update(x) on a copy, bit for bit (EXPECT_EQ: peek computes the same
// operations on the same doubles, it is not an approximation), for both memory rules on
// an analytic backbone, a table and a table scaled to SI (the three force paths), over
// random histories with many reversals. The probes include the points where the branch
// rules switch: the remembered reversals, their closing points and mirrors, the current
// point itself, and non-finite values (both must throw).
class PeekExactness : public ::testing::TestWithParam<std::tuple<int, MemoryRule>> {};

TEST_P(PeekExactness, EqualsUpdateOnACopyOverRandomHistories) {
  const auto [which, rule] = GetParam();
  const std::shared_ptr<const Backbone> bb = force_path_backbone(which);
  const double scale = 3.0 * bb->limit() / bb->initial_stiffness();
  std::mt19937_64 rng(4321 + static_cast<unsigned>(which) + (rule == MemoryRule::masing ? 0 : 7));
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Hysteresis h(bb, rule);
  std::size_t deepest = 0, reversal_probes = 0;
  for (int step = 0; step < 3000; ++step) {
    std::vector<double> probes{
        h.x(),       -h.x(),      scale * uni(rng), h.x() + 1e-3 * scale * uni(rng),
        2.0 * scale, -2.0 * scale};
    for (const ReversalPoint& r : h.reversals()) {
      probes.insert(probes.end(), {r.x, -r.x, r.closes_at, std::nextafter(r.x, 0.0),
                                   std::nextafter(r.closes_at, r.x)});
    }
    for (double p : probes) {
      Hysteresis copy = h;
      EXPECT_EQ(h.peek(p), copy.update(p)) << "step " << step << " probe " << p;
      if ((p - h.x()) * (h.x() - (h.reversals().empty() ? 0.0 : h.reversals().back().x)) < 0.0)
        ++reversal_probes;
    }
    for (double bad :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()}) {
      Hysteresis copy = h;
      EXPECT_THROW((void)h.peek(bad), InvalidInput);
      EXPECT_THROW((void)copy.update(bad), InvalidInput);
    }
    // Next point: mostly a fresh random reversal or continuation, sometimes exactly a
    // remembered reversal or closing point (where a loop closes).
    double next = scale * uni(rng);
    if (!h.reversals().empty() && step % 5 == 0) {
      const auto& rs = h.reversals();
      const auto& r = rs[std::uniform_int_distribution<std::size_t>(0, rs.size() - 1)(rng)];
      next = step % 10 == 0 ? r.x : r.closes_at;
    } else if (step % 3 == 0) {
      next = h.x() + 0.02 * scale * uni(rng);  // short steps keep many reversals on the stack
    }
    const double x_before = h.x(), q_before = h.Q();
    const std::size_t n_before = h.reversals().size();
    (void)h.peek(next);
    ASSERT_EQ(h.x(), x_before);
    ASSERT_EQ(h.Q(), q_before);
    ASSERT_EQ(h.reversals().size(), n_before);
    h.update(next);
    deepest = std::max(deepest, h.reversals().size());
  }
  // The walk must have exercised deep stacks (Masing) and many reversals.
  if (rule == MemoryRule::masing) {
    EXPECT_GE(deepest, 5u);
  }
  EXPECT_GT(reversal_probes, 1000u);
}

std::string peek_case_name(const ::testing::TestParamInfo<PeekExactness::ParamType>& param) {
  static const std::string backbones[] = {"analytic", "table", "scaled_table"};
  return backbones[std::get<0>(param.param)] +
         (std::get<1>(param.param) == MemoryRule::masing ? "_masing" : "_reset");
}

INSTANTIATE_TEST_SUITE_P(Backbones, PeekExactness,
                         ::testing::Combine(::testing::Range(0, 3),
                                            ::testing::Values(MemoryRule::masing,
                                                              MemoryRule::reset_at_reversal)),
                         peek_case_name);

// update_strided is update() in a loop with the fast path's state in registers: the same
// doubles, bit for bit (EXPECT_EQ), for the three force paths and both memory rules, over
// a random history with reversals, loop closings and exactly repeated points, read and
// written with unit, wide, negative and unaligned byte strides; the final state equals
// the loop's too. A non-finite point throws after the points before it were written, and
// leaves the state where update() leaves it.
class StridedExactness : public ::testing::TestWithParam<std::tuple<int, MemoryRule>> {};

TEST_P(StridedExactness, EqualsAnUpdateLoop) {
  const auto [which, rule] = GetParam();
  const std::shared_ptr<const Backbone> bb = force_path_backbone(which);
  const double scale = 3.0 * bb->limit() / bb->initial_stiffness();
  std::mt19937_64 rng(77 + static_cast<unsigned>(which));
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<double> history;
  double x = 0.0;
  while (history.size() < 4000) {
    const double target = scale * uni(rng);
    const int steps = 1 + static_cast<int>(history.size() % 7);
    for (int k = 1; k <= steps; ++k) history.push_back(x + (target - x) * k / steps);
    if (history.size() % 5 == 0) history.push_back(history.back());  // no motion
    x = target;
  }
  const std::size_t n = history.size();
  Hysteresis start(bb, rule);
  for (double p : {0.4 * scale, -0.3 * scale, 0.1 * scale}) start.update(p);
  Hysteresis loop = start;
  std::vector<double> expected(n);
  for (std::size_t k = 0; k < n; ++k) expected[k] = loop.update(history[k]);
  // Byte strides: contiguous, every third double, reversed, and 1 byte off alignment.
  for (const std::ptrdiff_t step : {std::ptrdiff_t{1}, std::ptrdiff_t{3}, std::ptrdiff_t{-2}}) {
    for (const std::ptrdiff_t offset : {std::ptrdiff_t{0}, std::ptrdiff_t{1}}) {
      const std::size_t span = n * static_cast<std::size_t>(std::abs(step)) + 2;
      std::vector<char> in_bytes(span * sizeof(double)), out_bytes(span * sizeof(double));
      const std::ptrdiff_t stride = step * static_cast<std::ptrdiff_t>(sizeof(double));
      const std::ptrdiff_t first =
          offset + (step < 0 ? static_cast<std::ptrdiff_t>(n - 1) * -stride : 0);
      for (std::size_t k = 0; k < n; ++k) {
        std::memcpy(in_bytes.data() + first + static_cast<std::ptrdiff_t>(k) * stride, &history[k],
                    sizeof(double));
      }
      Hysteresis h = start;
      h.update_strided(in_bytes.data() + first, stride, out_bytes.data() + first, stride, n);
      for (std::size_t k = 0; k < n; ++k) {
        double q = 0.0;
        std::memcpy(&q, out_bytes.data() + first + static_cast<std::ptrdiff_t>(k) * stride,
                    sizeof q);
        ASSERT_EQ(q, expected[k]) << "point " << k << ", stride " << stride;
      }
      EXPECT_EQ(h.x(), loop.x());
      EXPECT_EQ(h.Q(), loop.Q());
      ASSERT_EQ(h.reversals().size(), loop.reversals().size());
      for (std::size_t i = 0; i < h.reversals().size(); ++i) {
        EXPECT_EQ(h.reversals()[i].x, loop.reversals()[i].x);
        EXPECT_EQ(h.reversals()[i].Q, loop.reversals()[i].Q);
      }
    }
  }
  // peek_strided from states along the history: its leading run equals update() on a
  // copy, the state is unchanged, and a copy restarted at the run's last point gives the
  // rest (the Python package's forces() composes the two that way).
  Hysteresis walker = start;
  std::size_t runs = 0, longest = 0;
  for (std::size_t i = 0; i + 20 < n; ++i) {
    if (i % 13 == 0) {
      Hysteresis reference = walker;
      std::vector<double> want(20), got(20, -1.0);
      for (std::size_t k = 0; k < 20; ++k) want[k] = reference.update(history[i + k]);
      const double x_before = walker.x(), q_before = walker.Q();
      const std::size_t stack_before = walker.reversals().size();
      const std::size_t m =
          walker.peek_strided(reinterpret_cast<const char*>(&history[i]), sizeof(double),
                              reinterpret_cast<char*>(got.data()), sizeof(double), 20);
      ASSERT_LE(m, 20u);
      ASSERT_EQ(walker.x(), x_before);
      ASSERT_EQ(walker.Q(), q_before);
      ASSERT_EQ(walker.reversals().size(), stack_before);
      for (std::size_t k = 0; k < m; ++k) ASSERT_EQ(got[k], want[k]) << "point " << i + k;
      if (m < 20) {
        ASSERT_EQ(got[m], -1.0);  // nothing written past the run
        Hysteresis rest = walker;
        const std::size_t from = m > 0 ? m - 1 : 0;
        rest.update_strided(reinterpret_cast<const char*>(&history[i + from]), sizeof(double),
                            reinterpret_cast<char*>(got.data() + from), sizeof(double), 20 - from);
        for (std::size_t k = 0; k < 20; ++k) ASSERT_EQ(got[k], want[k]) << "point " << i + k;
      }
      runs += m > 0 ? 1 : 0;
      longest = std::max(longest, m);
    }
    (void)walker.update(history[i]);
  }
  EXPECT_GT(runs, 50u);  // many states where the history continues the branch
  EXPECT_GE(longest, 5u);
  // A NaN in the middle: the points before it written, the state that of update() there.
  std::vector<double> with_nan(history.begin(), history.begin() + 100);
  with_nan[60] = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> out(with_nan.size(), -1.0);
  Hysteresis h = start;
  Hysteresis reference = start;
  for (std::size_t k = 0; k < 60; ++k) (void)reference.update(with_nan[k]);
  EXPECT_THROW(
      h.update_strided(reinterpret_cast<const char*>(with_nan.data()), sizeof(double),
                       reinterpret_cast<char*>(out.data()), sizeof(double), with_nan.size()),
      InvalidInput);
  for (std::size_t k = 0; k < 60; ++k) EXPECT_EQ(out[k], expected[k]);
  EXPECT_EQ(out[60], -1.0);
  EXPECT_EQ(h.x(), reference.x());
  EXPECT_EQ(h.Q(), reference.Q());
  EXPECT_EQ(h.reversals().size(), reference.reversals().size());
}

INSTANTIATE_TEST_SUITE_P(Backbones, StridedExactness,
                         ::testing::Combine(::testing::Range(0, 3),
                                            ::testing::Values(MemoryRule::masing,
                                                              MemoryRule::reset_at_reversal)),
                         [](const ::testing::TestParamInfo<StridedExactness::ParamType>& param) {
                           return peek_case_name(::testing::TestParamInfo<PeekExactness::ParamType>(
                               param.param, param.index));
                         });

TEST(Masing, BorrowingCopyEqualsACopyAndOwnsNothing) {
  // A scratch reused over many states (each assigned from a different point of a random
  // history, with stacks deeper and shallower than the last) follows the same histories
  // as a plain copy, bit for bit, and never changes the backbone's reference count.
  for (MemoryRule rule : {MemoryRule::masing, MemoryRule::reset_at_reversal}) {
    std::shared_ptr<const Backbone> bb =
        std::make_shared<ScaledBackbone>(tabulated_mindlin(), 2.0, 3.0);
    const long uses = bb.use_count();
    const double scale = 3.0 * bb->limit() / bb->initial_stiffness();
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    Hysteresis h(bb, rule);
    Hysteresis scratch(std::make_shared<JenkinsBackbone>(1.0, 1.0));  // another backbone first
    std::size_t deepest = 0;
    for (int step = 0; step < 500; ++step) {
      h.update(scale * uni(rng) * (step % 7 == 0 ? 1.0 : 0.1));
      deepest = std::max(deepest, h.reversals().size());
      scratch.assign_borrowing(h);
      ASSERT_EQ(bb.use_count(), uses + 1);  // h's own reference only
      Hysteresis copy = h;
      for (int k = 0; k < 5; ++k) {
        const double x = scale * uni(rng);
        ASSERT_EQ(scratch.update(x), copy.update(x)) << step;
        const double Q = 0.5 * copy.Q();  // within the static limit on every branch
        ASSERT_EQ(scratch.update_force(Q), copy.update_force(Q)) << step;
      }
      ASSERT_EQ(scratch.reversals().size(), copy.reversals().size());
    }
    if (rule == MemoryRule::masing) {
      EXPECT_GE(deepest, 4u);
    }
  }
}

TEST(Masing, InverseRecoversDisplacementHistory) {
  const double s = mindlin().slip_displacement();
  Hysteresis h(mindlin_backbone());
  std::vector<double> xs;
  for (double turn : {0.7 * s, -0.4 * s, 0.2 * s, -0.6 * s, 0.65 * s}) {
    const auto seg = segment(xs.empty() ? 0.0 : xs.back(), turn, 40);
    xs.insert(xs.end(), seg.begin(), seg.end());
  }
  const auto Qs = h.forces(xs);
  const auto back = h.displacements(Qs);
  for (std::size_t i = 0; i < xs.size(); ++i) EXPECT_NEAR(back[i], xs[i], 1e-9 * s) << i;
}

TEST(Masing, ForceControlBeyondLimitIsAnError) {
  Hysteresis h(mindlin_backbone());
  EXPECT_THROW(h.update_force(1.01 * mindlin().Q_max()), InvalidInput);
}

TEST(Masing, EnergyPerCycleFormulaEqualsLoopArea) {
  // W = 8 Int Q_l - 4 x Q_l(x) against B.19 and against the trapezoidal loop area.
  const auto c = mindlin();
  const auto bb = mindlin_backbone();
  for (double frac : {0.05, 0.3, 0.9, 1.0, 3.0}) {
    const double dm = frac * c.slip_displacement();
    EXPECT_NEAR(energy_per_cycle(*bb, dm), c.energy_per_cycle(dm), 1e-12 * c.Q_max() * dm * 4);
    Hysteresis h(bb);
    h.update(dm);
    double area = 0.0;
    double xp = dm, Qp = h.Q();
    for (const auto& seg : {segment(dm, -dm, 20000), segment(-dm, dm, 20000)}) {
      for (double x : seg) {
        const double Q = h.update(x);
        area += 0.5 * (Q + Qp) * (x - xp);  // work done on the contact, Oint Q dx
        xp = x;
        Qp = Q;
      }
    }
    EXPECT_NEAR(area, c.energy_per_cycle(dm), 1e-6 * c.energy_per_cycle(dm) + 1e-15);
  }
}

TEST(Masing, ResetRuleEqualsMasingForSteadySymmetricCycles) {
  // Thesis Eq. 7.10 resets u_max at every reversal: the same loop when the cycles are
  // symmetric...
  const double s = mindlin().slip_displacement();
  Hysteresis masing(mindlin_backbone());
  Hysteresis reset(mindlin_backbone(), MemoryRule::reset_at_reversal);
  std::vector<double> xs = segment(0.0, 0.5 * s, 30);
  for (int k = 0; k < 3; ++k) {
    for (double x : segment(0.5 * s, -0.5 * s, 60)) xs.push_back(x);
    for (double x : segment(-0.5 * s, 0.5 * s, 60)) xs.push_back(x);
  }
  const auto a = masing.forces(xs);
  const auto b = reset.forces(xs);
  for (std::size_t i = 0; i < xs.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-12 * mindlin().Q_max());
  // ...but not for a decaying (transient) history, where the rule's reversal force
  // Q_l(u_max) differs from the actual force.
  std::vector<double> decay = segment(0.0, 0.8 * s, 30);
  for (double x : segment(0.8 * s, -0.5 * s, 60)) decay.push_back(x);
  for (double x : segment(-0.5 * s, 0.3 * s, 60)) decay.push_back(x);
  const auto c = masing.forces(decay);
  const auto d = reset.forces(decay);
  EXPECT_GT(std::abs(c.back() - d.back()), 1e-3 * mindlin().Q_max());
}

TEST(Masing, ResetRuleFollowsEq710AndStaysBounded) {
  // Eq. 7.10 after a reversal at -u_max moving up: -Q(-u, u_max) = -Q_l(u_max) +
  // 2 Q_l((u_max + u)/2) on [-u_max, u_max] (Eq. 4.12-4.13), then the virgin curve.
  const auto bb = mindlin_backbone();
  const double s = mindlin().slip_displacement();
  Hysteresis reset(bb, MemoryRule::reset_at_reversal);
  const double u_max = 0.4 * s;
  for (double x : segment(0.0, 0.9 * s, 40)) reset.update(x);
  for (double x : segment(0.9 * s, -u_max, 40)) reset.update(x);
  for (double x : segment(-u_max, u_max, 40)) {
    EXPECT_NEAR(reset.update(x), -bb->force(u_max) + 2.0 * bb->force(0.5 * (u_max + x)),
                1e-12 * mindlin().Q_max());
  }
  for (double x : segment(u_max, 3.0 * s, 40)) {
    EXPECT_NEAR(reset.update(x), bb->force(x), 1e-12 * mindlin().Q_max());
  }
  // Random histories far beyond the slip displacement: |Q| <= Q_max (a branch that kept
  // going past -u_max would reach Q_l(u_max) - 2 Q_max), odd, and the force-driven
  // inverse retraces the displacements.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uni(-3.0 * s, 3.0 * s);
  std::vector<double> xs;
  double x = 0.0;
  for (int i = 0; i < 60; ++i) {
    const double target = uni(rng);
    const auto seg = segment(x, target, 25);
    xs.insert(xs.end(), seg.begin(), seg.end());
    x = target;
  }
  Hysteresis h(bb, MemoryRule::reset_at_reversal);
  const auto Q = h.forces(xs);
  std::vector<double> neg(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) neg[i] = -xs[i];
  const auto Qn = h.forces(neg);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    ASSERT_LE(std::abs(Q[i]), bb->limit() * (1 + 1e-12)) << i;
    ASSERT_EQ(Qn[i], -Q[i]);
  }
  // Force control cannot pass Q_max: retrace a history that stays below it.
  std::vector<double> small;
  for (double v : xs) small.push_back(0.2 * v);
  const auto Qs = h.forces(small);
  const auto back = h.displacements(Qs);
  for (std::size_t i = 0; i < small.size(); ++i) {
    // B.15 inverted near gross slip loses digits as (1 - Q/mu P)^{-1/3}; 1e-9 s is ample
    // here (|Q| < 0.9 mu P).
    ASSERT_NEAR(back[i], small[i], 1e-9 * s) << i;
  }
}

// Random histories on random backbones: |Q| <= limit, continuity, oddness, and
// non-negative dissipation over a closed cycle.
class MasingProperties : public ::testing::TestWithParam<int> {};

TEST_P(MasingProperties, HoldOnRandomHistories) {
  std::mt19937_64 rng(1234 + GetParam());
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::shared_ptr<const Backbone> bb;
  if (GetParam() % 2 == 0) {
    bb = std::make_shared<MindlinBackbone>(contact::MindlinContact(
        0.1 + uni(rng), 1.0 + 100.0 * uni(rng), 1e10, 1e-5 * (1 + uni(rng))));
  } else {
    bb = std::make_shared<JenkinsBackbone>(1e6 * (1 + uni(rng)), 1.0 + uni(rng));
  }
  const double scale = 3.0 * bb->limit() / bb->initial_stiffness();
  std::vector<double> xs;
  double x = 0.0;
  for (int i = 0; i < 40; ++i) {
    const double target = scale * (2.0 * uni(rng) - 1.0);
    const auto seg = segment(x, target, 50);
    xs.insert(xs.end(), seg.begin(), seg.end());
    x = target;
  }
  // Close with three identical cycles between two points, wide enough to slip.
  const double a = 0.6 * scale, b = -0.5 * scale;
  for (int k = 0; k < 3; ++k) {
    for (double v : segment(xs.back(), a, 2000)) xs.push_back(v);
    for (double v : segment(a, b, 2000)) xs.push_back(v);
  }
  Hysteresis h(bb);
  const auto Q = h.forces(xs);
  std::vector<double> neg(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) neg[i] = -xs[i];
  const auto Qn = h.forces(neg);
  const double k0 = bb->initial_stiffness();
  for (std::size_t i = 0; i < xs.size(); ++i) {
    ASSERT_LE(std::abs(Q[i]), bb->limit() * (1 + 1e-12));
    ASSERT_EQ(Qn[i], -Q[i]);  // odd response
    if (i > 0) {              // Lipschitz with the initial stiffness: no jumps
      ASSERT_LE(std::abs(Q[i] - Q[i - 1]), k0 * std::abs(xs[i] - xs[i - 1]) * (1 + 1e-9) + 1e-12);
    }
  }
  // The last two cycles (b -> a -> b) are closed: the work done on the contact over each
  // is >= 0, and they are equal.
  const std::size_t n = xs.size();
  auto cycle_work = [&](std::size_t begin, std::size_t end) {
    return asperity::testing::trapezoid_work(xs, Q, begin, end);
  };
  const double last = cycle_work(n - 4001, n - 1);
  const double previous = cycle_work(n - 8001, n - 4001);
  EXPECT_GT(last, 0.0);
  EXPECT_NEAR(last, previous, 1e-9 * bb->limit() * scale);
}

INSTANTIATE_TEST_SUITE_P(Random, MasingProperties, ::testing::Range(0, 8));

}  // namespace
}  // namespace asperity::hysteresis
