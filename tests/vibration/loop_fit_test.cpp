// Jenkins and four-parameter Iwan fits of hysteresis loops: the loop formula against the
// elements' own periodic response, recovery of known parameters from noise-free and noisy
// synthetic loops, the round trip fit -> element -> loop, and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "asperity/core/error.hpp"
#include "asperity/dynamics/friction_model.hpp"
#include "asperity/joint/fretting.hpp"
#include "asperity/vibration/loop_fit.hpp"

namespace asperity::vibration {
namespace {

constexpr double um = 1e-6;

// The steady loop of `element` under u = a cos(2 pi i/N) + x_c: its periodic response
// (virgin start, second pass kept), split at the minimum (i = N/2) into the unloading
// branch (i = 0..N/2) and the reloading branch, plus the force offset Q_c.
MeasuredLoop loop_of(const Element& element, double a, double x_c = 0.0, double Q_c = 0.0,
                     std::size_t N = 400) {
  Eigen::MatrixXd u(static_cast<Eigen::Index>(N), 1);
  for (std::size_t i = 0; i < N; ++i)
    u(static_cast<Eigen::Index>(i), 0) =
        a * std::cos(2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(N));
  PeriodicResponse r;
  element.periodic_response(u, Eigen::MatrixXd(), false, r);
  MeasuredLoop l{.unloading = N / 2 + 1, .source = "synthetic"};
  for (std::size_t i = 0; i < N; ++i) {
    l.delta.push_back(u(static_cast<Eigen::Index>(i), 0) + x_c);
    l.Q.push_back(r.f(static_cast<Eigen::Index>(i), 0) + Q_c);
  }
  return l;
}

const dynamics::SegalmanIwanParameters kIwan{.F_S = 100.0, .K_T = 5e7, .chi = -0.4, .beta = 0.2};

// The Masing loop formula of loop_fit.hpp is the element's periodic response: the Iwan
// element is a MasingElement over the same backbone, so they agree to round-off.
TEST(LoopFit, MasingFormulaIsTheElementsLoop) {
  const auto element = make_iwan4_element(kIwan);
  const dynamics::SegalmanBackbone b(kIwan);
  for (double a : {0.5 * b.phi_max(), 3.0 * b.phi_max()}) {
    const auto loop = loop_of(*element, a);
    const auto q = masing_loop(b, loop);
    for (std::size_t i = 0; i < q.size(); ++i) EXPECT_NEAR(q[i], loop.Q[i], 1e-10 * kIwan.F_S);
  }
}

std::vector<MeasuredLoop> iwan_loops(double noise, std::uint64_t seed) {
  const auto element = make_iwan4_element(kIwan);
  const double phi = dynamics::SegalmanBackbone(kIwan).phi_max();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, noise > 0 ? noise : 1.0);
  std::vector<MeasuredLoop> loops;
  // Micro-slip loops and one into macro-slip, each with its own offsets (as measured).
  for (double f : {0.25, 0.6, 1.0, 2.5}) {
    auto l = loop_of(*element, f * phi, 0.3 * um * f, 2.0 * f);
    if (noise > 0)
      for (auto& q : l.Q) q += g(rng);
    loops.push_back(std::move(l));
  }
  return loops;
}

// Noise-free loops: the fit returns the parameters that made them. Levenberg-Marquardt
// stops when the cost no longer falls by 1e-14 of itself; with a residual at round-off
// the parameters are then within ~1e-7 of the optimum, checked at 1e-5.
TEST(LoopFit, Iwan4RecoversKnownParametersFromExactLoops) {
  const auto fit = fit_loops(iwan_loops(0.0, 1), LoopModel::iwan4);
  EXPECT_NEAR(fit.value("F_S") / kIwan.F_S, 1.0, 1e-5);
  EXPECT_NEAR(fit.value("K_T") / kIwan.K_T, 1.0, 1e-5);
  EXPECT_NEAR(fit.value("chi") / kIwan.chi, 1.0, 1e-5);
  EXPECT_NEAR(fit.value("beta") / kIwan.beta, 1.0, 1e-5);
  EXPECT_LT(fit.relative_residual, 1e-6);
  EXPECT_NEAR(fit.Q_offsets[3], 5.0, 1e-6 * kIwan.F_S);
}

TEST(LoopFit, JenkinsRecoversKnownParametersFromExactLoops) {
  const double k_t = 2e7, F_s = 50.0;  // slip at 2.5 um
  const auto element = make_jenkins_element(k_t, F_s);
  std::vector<MeasuredLoop> loops;
  for (double a : {1.5 * um, 4.0 * um, 8.0 * um}) loops.push_back(loop_of(*element, a));
  const auto fit = fit_loops(loops, LoopModel::jenkins);
  EXPECT_NEAR(fit.value("k_t") / k_t, 1.0, 1e-5);
  EXPECT_NEAR(fit.value("F_s") / F_s, 1.0, 1e-5);
  EXPECT_LT(fit.relative_residual, 1e-6);
}

// Independent Gaussian force noise of sd 0.5 N: the estimates lie within 4 of their
// standard errors of the truth (the errors are independent here, so the Gauss-Newton
// covariance is the right one; 4 sd: a false failure < 1e-4 per parameter), and the rms
// residual estimates the noise (relative sd 1/sqrt(2 n) = 1.8 %; 4 sd = 7 %).
TEST(LoopFit, Iwan4NoisyLoopsWithinTheirStandardErrors) {
  const double noise = 0.5;
  const auto fit = fit_loops(iwan_loops(noise, 42), LoopModel::iwan4);
  const double truth[] = {kIwan.F_S, kIwan.K_T, kIwan.chi, kIwan.beta};
  for (std::size_t j = 0; j < 4; ++j) {
    const auto& p = fit.parameters[j];
    SCOPED_TRACE(p.name);
    ASSERT_TRUE(std::isfinite(p.standard_error));
    EXPECT_GT(p.standard_error, 0.0);
    EXPECT_LT(std::abs(p.value - truth[j]), 4.0 * p.standard_error);
  }
  EXPECT_NEAR(fit.residual_rms / noise, 1.0, 4.0 / std::sqrt(2.0 * 1600));
}

// Round trip: the fitted element, driven along each measured loop's displacements, gives
// back the fitted loop, so its misfit to the measurement is the fit's residual (to the
// round-off of the element's branch arithmetic, 1e-9 of the force).
TEST(LoopFit, RoundTripFitElementLoop) {
  for (LoopModel model : {LoopModel::iwan4, LoopModel::jenkins}) {
    SCOPED_TRACE(std::string(to_string(model)));
    const auto loops = iwan_loops(0.5, 7);
    const auto fit = fit_loops(loops, model);
    const auto element = fit.element();
    double ss = 0.0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < loops.size(); ++k) {
      const auto& l = loops[k];
      Eigen::MatrixXd u(static_cast<Eigen::Index>(l.delta.size()), 1);
      for (std::size_t i = 0; i < l.delta.size(); ++i)
        u(static_cast<Eigen::Index>(i), 0) = l.delta[i] - 0.5 * (l.delta.front() + l.delta[200]);
      PeriodicResponse r;
      element->periodic_response(u, Eigen::MatrixXd(), false, r);
      for (std::size_t i = 0; i < l.delta.size(); ++i) {
        const double q = r.f(static_cast<Eigen::Index>(i), 0) + fit.Q_offsets[k];
        EXPECT_NEAR(q, fit.Q_model[k][i], 1e-9 * kIwan.F_S);
        ss += (l.Q[i] - q) * (l.Q[i] - q);
        ++n;
      }
    }
    EXPECT_NEAR(std::sqrt(ss / static_cast<double>(n)) / fit.residual_rms, 1.0, 1e-9);
  }
}

// The case form: the [[element]] table names the type and every parameter with its unit.
TEST(LoopFit, CaseTomlHasEveryParameter) {
  const auto fit = fit_loops(iwan_loops(0.5, 3), LoopModel::iwan4);
  const auto toml = fit.case_toml();
  for (const char* s : {"[[element]]", "type = \"iwan4\"", "F_S = \"", " N\"", "K_T = \"", " N/m\"",
                        "chi = ", "beta = ", "T = [[1.0]]"})
    EXPECT_NE(toml.find(s), std::string::npos) << s << "\n" << toml;
}

TEST(LoopFit, RefusesBadLoops) {
  EXPECT_THROW(fit_loops({}, LoopModel::iwan4), InvalidInput);
  MeasuredLoop l{.delta = {0, 1, 2}, .Q = {0, 1, 2}, .unloading = 2};
  EXPECT_THROW(fit_loops({l}, LoopModel::jenkins), InvalidInput);
  EXPECT_THROW((void)parse_loop_model("iwan"), InvalidInput);
  auto flat = iwan_loops(0.0, 1).front();
  for (auto& q : flat.Q) q = 1.0;
  EXPECT_THROW(fit_loops({flat}, LoopModel::iwan4), InvalidInput);
}

// Synthetic experiments of Segalman's model (the apparatus of Fig. 5.7, Eq. 5.3 at three
// amplitudes, the largest into macro-slip), analysed as measurements; the fit uses their
// averaged loops (analyze_fretting: 200 points a branch, resampled linearly).
const dynamics::SegalmanIwanParameters kTruth{.F_S = 200.0, .K_T = 1e8, .chi = -0.5, .beta = 0.1};

LoopFit fit_synthetic(double noise_delta, double noise_Q) {
  const auto backbone = std::make_shared<dynamics::SegalmanBackbone>(kTruth);
  std::vector<MeasuredLoop> loops;
  for (double a : {3.0 * um, 8.0 * um, 16.0 * um}) {
    joint::SyntheticOptions o;
    o.excitation.amplitude = a;
    o.sample_rate = 2000.0;
    o.noise_delta = noise_delta;
    o.noise_Q = noise_Q;
    const auto an = joint::analyze_fretting(joint::synthetic_experiment(backbone, o), 500.0);
    loops.push_back({.delta = an.loop_delta,
                     .Q = an.loop_Q,
                     .unloading = an.loop_delta.size() / 2,
                     .source = "synthetic"});
  }
  return fit_loops(loops, LoopModel::iwan4);
}

void expect_truth(const LoopFit& fit, double tolerance, double se_multiple) {
  const double truth[] = {kTruth.F_S, kTruth.K_T, kTruth.chi, kTruth.beta};
  for (std::size_t j = 0; j < 4; ++j) {
    const auto& p = fit.parameters[j];
    SCOPED_TRACE(p.name);
    EXPECT_LT(std::abs(p.value - truth[j]),
              std::max(tolerance * std::abs(truth[j]), se_multiple * p.standard_error));
  }
}

// Noise-free sensors: only the linear resampling of the averaged loop (an error of ~h^2/8
// times the curvature; rms residual 8e-5 N against 200 N) separates the loops from the
// model: the parameters come out within 3e-5, checked at 1e-4.
TEST(LoopFit, Iwan4FromNoiseFreeSyntheticExperiments) {
  const auto fit = fit_synthetic(0.0, 0.0);
  expect_truth(fit, 1e-4, 0.0);
  EXPECT_LT(fit.relative_residual, 1e-5);
}

// The load cell's 1 N noise alone (the regressor, the displacement, exact): unbiased
// estimates, within 5 standard errors (the averaged loop's points come from distinct
// samples, so the errors are nearly independent and the covariance applies).
TEST(LoopFit, Iwan4FromSyntheticExperimentsWithForceNoise) {
  const auto fit = fit_synthetic(0.0, 1.0);
  expect_truth(fit, 0.0, 5.0);
  // The averaged loop's noise: 1 N / sqrt(10 cycles) = 0.32 N; 15 % for the resampling.
  EXPECT_LT(fit.residual_rms, 1.15 / std::sqrt(10.0));
}

// With the displacement sensor's 0.1 um too (section 5.2), the averaged loop's displacements
// carry 0.1 um / sqrt(10) = 0.03 um of noise, 3 N at K_T = 1e8 N/m: noise in the regressor
// flattens the fitted slope near the reversals (errors-in-variables attenuation, docs/
// joints.md), so K_T comes out low (7.7 % measured) and chi, beta absorb it, while F_S, the
// macro-slip plateau, is insensitive to it (0.6 % measured). Checked: F_S within 1 %, K_T
// low but within 10 %.
TEST(LoopFit, Iwan4FromSyntheticExperimentsWithBothSensorsNoise) {
  const auto fit = fit_synthetic(0.1 * um, 1.0);
  EXPECT_NEAR(fit.value("F_S") / kTruth.F_S, 1.0, 0.01);
  EXPECT_LT(fit.value("K_T"), kTruth.K_T);
  EXPECT_GT(fit.value("K_T"), 0.9 * kTruth.K_T);
}

}  // namespace
}  // namespace asperity::vibration
