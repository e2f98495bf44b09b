// The tabulated (user table) backbone: through every point, monotone, exact integral and
// inverse, convergence on the Mindlin backbone (B.15), the refusals; and the masing_table
// vibration element against the elements it tabulates.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "asperity/contact/mindlin.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/hysteresis/table_backbone.hpp"
#include "asperity/vibration/elements.hpp"

namespace asperity::hysteresis {
namespace {

// Micro-scale experiment 1 of Table 3.2 with CEB's mu (as masing_test.cpp).
MindlinBackbone mindlin() {
  return MindlinBackbone(contact::MindlinContact(0.528, 35.0, 24.32e9, 83.25e-6));
}

// A random monotone table: through its points, non-decreasing between them (checked on
// 50 points an interval), the exact integral against adaptive quadrature (1e-12), and
// force(displacement(Q)) = Q (bisection to 1e-14 of an interval: 1e-12 of the force).
TEST(TableBackbone, InterpolatesMonotoneWithExactIntegralAndInverse) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> x{0.0}, Q{0.0};
  for (int i = 0; i < 30; ++i) {
    x.push_back(x.back() + 1e-7 * (0.2 + u(rng)));
    Q.push_back(Q.back() + (u(rng) < 0.2 ? 0.0 : 10.0 * u(rng)));  // flat stretches too
  }
  Q[1] = std::max(Q[1], 1.0);
  for (std::size_t i = 2; i < Q.size(); ++i) Q[i] = std::max(Q[i], Q[i - 1]);
  const TableBackbone b(x, Q);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(b.force(x[i]), Q[i], 1e-12 * Q.back());
  double prev = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    for (int k = 0; k <= 50; ++k) {
      const double v = b.force(x[i] + (x[i + 1] - x[i]) * k / 50.0);
      EXPECT_GE(v, prev - 1e-12 * Q.back());
      prev = v;
    }
  }
  for (double xe : {0.3 * x.back(), 0.77 * x.back(), 1.5 * x.back()}) {
    const double ref =
        core::integrate([&](double s) { return b.force(s); }, 0.0, xe, 1e-13, 20, "table integral")
            .value;
    EXPECT_NEAR(b.integral(xe), ref, 1e-12 * Q.back() * xe);
  }
  for (double q : {0.5, 0.3 * Q.back(), 0.9 * Q.back()})
    EXPECT_NEAR(b.force(b.displacement(q)), q, 1e-12 * Q.back());
  EXPECT_EQ(b.force(2.0 * x.back()), Q.back());
  EXPECT_EQ(b.limit(), Q.back());
  EXPECT_THROW((void)b.displacement(Q.back()), InvalidInput);
}

// tabulate() of the Mindlin backbone, read back: the error falls as the table refines
// (halving the spacing more than halves the largest error; the backbone's slope has a
// square-root singularity at the slip displacement, so the order there is 1.5, O(h^3)
// elsewhere) and is below 1e-3 of the slip force at the export's 401 points.
TEST(TableBackbone, ConvergesOnMindlin) {
  const auto m = mindlin();
  auto max_error = [&](std::size_t n) {
    const auto [x, Q] = tabulate(m, n);
    const TableBackbone b(x, Q);
    double e = 0.0;
    for (int k = 0; k <= 5000; ++k) {
      const double v = 1.3 * x[n - 1] * k / 5000.0;
      e = std::max(e, std::abs(b.force(v) - m.force(v)));
    }
    return e / m.limit();
  };
  const double e401 = max_error(401), e801 = max_error(801);
  EXPECT_LT(e401, 1e-3);
  EXPECT_LT(e801, 0.5 * e401);
}

TEST(TableBackbone, Refusals) {
  EXPECT_THROW(TableBackbone({0.0}, {0.0}), InvalidInput);                        // one point
  EXPECT_THROW(TableBackbone({1e-6, 2e-6}, {0.0, 1.0}), InvalidInput);            // not at 0
  EXPECT_THROW(TableBackbone({0.0, 1e-6}, {0.5, 1.0}), InvalidInput);             // Q(0) != 0
  EXPECT_THROW(TableBackbone({0.0, 1e-6, 1e-6}, {0.0, 1.0, 2.0}), InvalidInput);  // x repeats
  EXPECT_THROW(TableBackbone({0.0, 1e-6, 2e-6}, {0.0, 2.0, 1.0}), InvalidInput);  // Q falls
  EXPECT_THROW(TableBackbone({0.0, 1e-6}, {0.0, 0.0}), InvalidInput);             // no stiffness
  EXPECT_THROW(TableBackbone({0.0, NAN}, {0.0, 1.0}), InvalidInput);
  EXPECT_THROW(TableBackbone({0.0, 1e-6}, {0.0}), InvalidInput);
  try {
    (void)TableBackbone({0.0, 1e-6, 2e-6}, {0.0, 2.0, 1.0}, "backbone.csv");
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("backbone.csv"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("point 3"), std::string::npos);
  }
}

Eigen::MatrixXd cosine(double a, std::size_t N = 256) {
  Eigen::MatrixXd u(static_cast<Eigen::Index>(N), 1);
  for (std::size_t i = 0; i < N; ++i)
    u(static_cast<Eigen::Index>(i), 0) =
        a * std::cos(2 * M_PI * static_cast<double>(i) / static_cast<double>(N));
  return u;
}

// A two-point table is a straight line to the slip force, then constant: the Jenkins
// backbone, so the masing_table element's loop is the Jenkins element's (round-off).
TEST(MasingTableElement, TwoPointTableIsJenkins) {
  const double k = 2e7, F = 50.0;
  const auto table = vibration::make_masing_table_element({0.0, F / k}, {0.0, F});
  const auto jenkins = vibration::make_jenkins_element(k, F);
  for (double a : {1e-6, 8e-6}) {
    vibration::PeriodicResponse rt, rj;
    table->periodic_response(cosine(a), Eigen::MatrixXd(), false, rt);
    jenkins->periodic_response(cosine(a), Eigen::MatrixXd(), false, rj);
    EXPECT_LT((rt.f - rj.f).cwiseAbs().maxCoeff(), 1e-12 * F);
  }
}

// The Mindlin backbone through tabulate() as a masing_table element against the Masing
// element on the backbone itself: a Masing branch Q_r -+ 2 B(|x - x_r|/2) moves the
// backbone's error at most three times (B(a) and 2 B), so the loops differ by at most
// 3 max|B_table - B|.
TEST(MasingTableElement, LoopWithinThreeTimesTheTablesError) {
  const auto m = std::make_shared<MindlinBackbone>(mindlin());
  auto [x, Q] = tabulate(*m);
  const TableBackbone b(x, Q);
  double e = 0.0;
  for (int k = 0; k <= 20000; ++k) {
    const double v = 1.3 * x.back() * k / 20000.0;
    e = std::max(e, std::abs(b.force(v) - m->force(v)));
  }
  const auto table = vibration::make_masing_table_element(x, Q);
  const vibration::MasingElement exact(m, "mindlin", {});
  for (double f : {0.2, 0.7, 2.0}) {
    vibration::PeriodicResponse rt, re;
    table->periodic_response(cosine(f * x.back()), Eigen::MatrixXd(), false, rt);
    exact.periodic_response(cosine(f * x.back()), Eigen::MatrixXd(), false, re);
    EXPECT_LE((rt.f - re.f).cwiseAbs().maxCoeff(), 3.0 * e * (1.0 + 1e-9));
  }
}

}  // namespace
}  // namespace asperity::hysteresis
