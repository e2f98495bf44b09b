// Benchmarks of the vibration layer (issue 10), with ratios against references measured
// in the same run:
//  - the AFT residual + analytic Jacobian of one Jenkins element, H = 3 (harmonics 0..3),
//    N_t = 1024 (target < 20 us; tmdsimpy needs about 1 ms), against the element's own
//    two passes over the samples (the irreducible time-domain work);
//  - the whole EPMC continuation of the Jenkins SDOF of the issue (m = k = 1, c = 0.01,
//    k_t = 0.25, F_s = 0.2, log10 a from -2 to 5; target < 50 ms);
//  - a forced response curve of the rough-flat SDOF of Table 7.2 (section 7.2's
//    non-dimensional base-excited system, eps = 0.032, the rough contact with A0 = 1 cm^2,
//    A = 18 um, P = 5 k A as in bench/dynamics_bench.cpp) against reaching the same steady
//    states by time integration (200 periods per frequency: the transient decays as
//    exp(-eps/2 * 2 pi * 200) < 1e-8 of its start), target >= 100 times faster;
//  - one 3-D rough-contact element's AFT residual + Jacobian (issue 20: < 50 us at H = 3,
//    N_t = 128) against a Jenkins element on the same basis;
//  - chord against full Newton on the EPMC of a 200-DOF chain (1403 unknowns);
//  - the 3-D dry friction element on a circular slip path (a dense tangent: every sample
//    depends on every earlier one), AFT residual + Jacobian at H = 3, N_t = 256, against
//    the 2-D element on a straight path on the same basis.
// g++ 12 reports writes into Eigen's dynamic matrices as potential null dereferences
// (a known false positive of -Wnull-dereference at -O3).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "../ratio_reporter.hpp"
#include "asperity/dynamics/epb.hpp"
#include "asperity/dynamics/system.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/vibration/analysis.hpp"
#include "asperity/vibration/contact_elements.hpp"
#include "asperity/vibration/rough_contact.hpp"

namespace {

using namespace asperity;
using namespace asperity::vibration;

HarmonicBalance jenkins_sdof(std::vector<int> harmonics, std::size_t N) {
  Structure s{Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd::Constant(1, 1, 1.0),
              Eigen::MatrixXd::Constant(1, 1, 0.01)};
  return HarmonicBalance(
      s, {{make_jenkins_element(0.25, 0.2), Eigen::MatrixXd::Ones(1, 1), "jenkins"}},
      HarmonicBalanceOptions{std::move(harmonics), N});
}

Eigen::VectorXd jenkins_state(const HarmonicBalance& hb) {
  // A state in gross slip: amplitude 2 on the first harmonic, some of the others.
  Eigen::VectorXd U = Eigen::VectorXd::Zero(hb.unknowns());
  U(hb.index(0, 1)) = 2.0;
  U(hb.index(0, 2)) = 0.3;
  U(hb.index(0, 5)) = 0.1;
  return U;
}

void aft_jenkins(benchmark::State& state, std::size_t time_points) {
  const auto hb = jenkins_sdof({0, 1, 2, 3}, time_points);
  const Eigen::VectorXd U = jenkins_state(hb);
  const Eigen::VectorXd F = Eigen::VectorXd::Zero(hb.unknowns());
  Eigen::VectorXd R, dRw;
  Eigen::MatrixXd J;
  for (auto _ : state) {
    hb.residual(U, 1.1, F, R, &J, &dRw);
    benchmark::DoNotOptimize(J.data());
  }
}
void BM_AftJenkinsResidualJacobian(benchmark::State& state) {
  aft_jenkins(state, 1024);
}
BENCHMARK(BM_AftJenkinsResidualJacobian)->Unit(benchmark::kMicrosecond);

void BM_JenkinsElementTwoPasses(benchmark::State& state) {
  const auto hb = jenkins_sdof({0, 1, 2, 3}, 1024);
  const Eigen::MatrixXd u = hb.basis().synthesis() * jenkins_state(hb);
  PeriodicResponse r;
  for (auto _ : state) {
    hb.elements()[0].element->periodic_response(u, Eigen::MatrixXd(), false, r);
    benchmark::DoNotOptimize(r.f.data());
  }
}
BENCHMARK(BM_JenkinsElementTwoPasses)->Unit(benchmark::kMicrosecond);

std::size_t g_epmc_points = 0;
void BM_EpmcJenkinsSdof(benchmark::State& state) {
  const auto hb = jenkins_sdof({0, 1, 2, 3}, 1024);
  NonlinearModeOptions opt;
  opt.log10_amplitude_from = -2.0;
  opt.log10_amplitude_to = 5.0;
  for (auto _ : state) {
    const auto r = nonlinear_mode(hb, opt, {0});
    g_epmc_points = r.amplitude.size();
    benchmark::DoNotOptimize(r.omega.data());
  }
  state.counters["points"] = static_cast<double>(g_epmc_points);
}
BENCHMARK(BM_EpmcJenkinsSdof)->Unit(benchmark::kMillisecond);

// Table 7.2's rough contact in the non-dimensional variables of section 7.2.
constexpr double kK = 1e5, kA = 18e-6, kEps = 0.032;
std::shared_ptr<const hysteresis::Backbone> rough_flat_nondimensional() {
  static const auto bb = [] {
    auto c = dynamics::table_7_2_rough();
    c.A0 = 1e-4;
    c.P = 5.0 * kK * kA;
    return std::shared_ptr<const hysteresis::Backbone>(std::make_shared<hysteresis::ScaledBackbone>(
        dynamics::epb_backbone(c), 1.0 / kA, 1.0 / (kK * kA)));
  }();
  return bb;
}

std::size_t g_frf_points = 0;
double g_omega_from = 0.6, g_omega_to = 1.4;
void BM_FrfRoughFlatSdof(benchmark::State& state) {
  Structure s{Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::MatrixXd::Constant(1, 1, 1.0),
              Eigen::MatrixXd::Constant(1, 1, kEps)};
  const HarmonicBalance hb(
      s,
      {{make_rough_flat_element(rough_flat_nondimensional(), {}), Eigen::MatrixXd::Ones(1, 1), ""}},
      HarmonicBalanceOptions{{0, 1, 2, 3}, 256});
  FrequencyResponseOptions opt;
  // Base motion y = sin(Omega tau): force y + eps y' = sin + eps Omega cos (Eq. 7.1).
  opt.force = Eigen::VectorXd::Zero(hb.unknowns());
  opt.force(hb.index(0, 2)) = 1.0;
  opt.force_per_omega = Eigen::VectorXd::Zero(hb.unknowns());
  opt.force_per_omega(hb.index(0, 1)) = kEps;
  opt.omega_from = g_omega_from;
  opt.omega_to = g_omega_to;
  for (auto _ : state) {
    const auto c = frequency_response(hb, opt, {0});
    g_frf_points = c[0].omega.size();
    benchmark::DoNotOptimize(c[0].omega.data());
  }
  state.counters["points"] = static_cast<double>(g_frf_points);
}
BENCHMARK(BM_FrfRoughFlatSdof)->Unit(benchmark::kMillisecond);

void BM_TimeIntegrationRoughFlatSdof200Periods(benchmark::State& state) {
  const auto model = dynamics::make_physics_based(
      [] {
        auto c = dynamics::table_7_2_rough();
        c.A0 = 1e-4;
        c.P = 5.0 * kK * kA;
        return dynamics::epb_backbone(c);
      }(),
      kK, kA);
  const double Omega = 0.5 * (g_omega_from + g_omega_to);
  const double f = Omega / (2.0 * std::numbers::pi);
  dynamics::SimulationOptions o;
  o.duration = 200.0 / f;
  o.output_interval = 0.1;
  for (auto _ : state) {
    const auto tr = dynamics::simulate(
        {.epsilon = kEps}, dynamics::HarmonicExcitation{.frequency = f, .amplitude = 1.0}, *model,
        o);
    benchmark::DoNotOptimize(tr.u.back());
  }
}
BENCHMARK(BM_TimeIntegrationRoughFlatSdof200Periods)->Unit(benchmark::kMillisecond);

// One 3-D rough-contact element (Table 7.2's surfaces, BKE, 20 MPa on 4 mm^2: an interface
// patch of a bolted joint) in microslip with the normal load varying: AFT residual +
// Jacobian with H = 3, N_t = 128 (issue 20's target < 50 us), against a Jenkins element on
// the same basis (the cheapest hysteretic element: what harmonic balance alone costs).
HarmonicBalance rough_contact_block() {
  const dynamics::EpbContact c = dynamics::table_7_2_rough();
  const RoughInterfaceParameters p{.E_star = c.E_star,
                                   .G_star = c.G_star,
                                   .H = c.H,
                                   .nu = c.nu,
                                   .sigma = c.sigma,
                                   .R = c.R,
                                   .eta = c.eta,
                                   .model = contact::ModelName::bke,
                                   .friction = {}};
  constexpr double kPressure = 20e6, kArea = 4e-6;
  const auto surface = std::make_shared<const RoughContactSurface>(p, kPressure / 8, kPressure * 8);
  Structure s{Eigen::Matrix3d::Identity(), Eigen::Vector3d(1e8, 2e8, 0.0).asDiagonal(),
              Eigen::Matrix3d::Zero()};
  return HarmonicBalance(
      s,
      {{std::make_shared<RoughContactElement>(surface, kArea, kPressure, "patch"),
        Eigen::MatrixXd(Eigen::Matrix3d::Identity()), "patch"}},
      HarmonicBalanceOptions{{0, 1, 2, 3}, 128});
}

void BM_AftRoughContactResidualJacobian(benchmark::State& state) {
  const auto hb = rough_contact_block();
  const double slip = hb.elements()[0].element->slip_force() / 1e8;  // x where Q ~ Q_max
  Eigen::VectorXd U = Eigen::VectorXd::Zero(hb.unknowns());
  U(hb.index(0, 1)) = 0.3 * slip;   // t1: microslip
  U(hb.index(1, 2)) = 0.1 * slip;   // t2: a 2-D path
  U(hb.index(2, 1)) = 0.05 * slip;  // the normal closure oscillates
  U(hb.index(0, 3)) = 0.02 * slip;
  const Eigen::VectorXd F = Eigen::VectorXd::Zero(hb.unknowns());
  Eigen::VectorXd R, dRw;
  Eigen::MatrixXd J;
  for (auto _ : state) {
    hb.residual(U, 2000.0, F, R, &J, &dRw);
    benchmark::DoNotOptimize(J.data());
  }
}
BENCHMARK(BM_AftRoughContactResidualJacobian)->Unit(benchmark::kMicrosecond);

void BM_AftJenkinsResidualJacobianNt128(benchmark::State& state) {
  aft_jenkins(state, 128);
}
BENCHMARK(BM_AftJenkinsResidualJacobianNt128)->Unit(benchmark::kMicrosecond);

// A 3-DOF point mass on a 3-D dry friction contact (k_t = k_n = 1, mu = 0.5, N0 = 1) moved
// on a circle of radius 10 mu N0 / k_t (slipping throughout, the slip direction turning
// with every sample), and the 2-D element moved along t1 with the same amplitude.
HarmonicBalance dry_friction_block(bool three_d) {
  const Eigen::Index n = three_d ? 3 : 2;
  Structure s{Eigen::MatrixXd::Identity(n, n), Eigen::MatrixXd::Identity(n, n),
              Eigen::MatrixXd::Zero(n, n)};
  std::shared_ptr<const Element> e =
      three_d
          ? make_elastic_dry_friction_3d_element({.k_t = 1.0, .k_n = 1.0, .mu = 0.5, .N0 = 1.0})
          : make_elastic_dry_friction_2d_element({.k_t = 1.0, .k_n = 1.0, .mu = 0.5, .N0 = 1.0});
  return HarmonicBalance(s, {{e, Eigen::MatrixXd::Identity(n, n), "contact"}},
                         HarmonicBalanceOptions{{0, 1, 2, 3}, 256});
}

void aft_dry_friction(benchmark::State& state, bool three_d) {
  const auto hb = dry_friction_block(three_d);
  Eigen::VectorXd U = Eigen::VectorXd::Zero(hb.unknowns());
  U(hb.index(0, static_cast<std::size_t>(hb.basis().index_of(1, 0)))) = 5.0;
  if (three_d) U(hb.index(1, static_cast<std::size_t>(hb.basis().index_of(1, 1)))) = 5.0;
  const Eigen::VectorXd F = Eigen::VectorXd::Zero(hb.unknowns());
  Eigen::VectorXd R, dRw;
  Eigen::MatrixXd J;
  for (auto _ : state) {
    hb.residual(U, 1.0, F, R, &J, &dRw);
    benchmark::DoNotOptimize(J.data());
  }
}
void BM_AftDryFriction3dCircleNt256(benchmark::State& state) {
  aft_dry_friction(state, true);
}
void BM_AftDryFriction2dLineNt256(benchmark::State& state) {
  aft_dry_friction(state, false);
}
BENCHMARK(BM_AftDryFriction3dCircleNt256)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AftDryFriction2dLineNt256)->Unit(benchmark::kMicrosecond);

// Chord Newton against full Newton (ContinuationOptions::chord_unknowns) on the EPMC of a
// chain of 200 unit masses and springs with a Jenkins joint between every tenth mass and
// ground, H = 3, N_t = 64 (1400 unknowns: the size where one dense LU costs as much as many
// residual evaluations; a reduced finite-element model has 3-10 times more).
HarmonicBalance jenkins_chain() {
  constexpr Eigen::Index n = 200;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    K(i, i) += 1.0;
    if (i + 1 < n) {
      K(i, i) += 1.0;
      K(i + 1, i + 1) += 1.0;
      K(i, i + 1) -= 1.0;
      K(i + 1, i) -= 1.0;
    }
  }
  std::vector<PlacedElement> elements;
  for (Eigen::Index i = 5; i < n; i += 10) {
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(1, n);
    T(0, i) = 1.0;
    elements.push_back({make_jenkins_element(0.5, 0.01), T, ""});
  }
  return HarmonicBalance(Structure{Eigen::MatrixXd::Identity(n, n), K, Eigen::MatrixXd::Zero(n, n)},
                         std::move(elements), HarmonicBalanceOptions{{0, 1, 2, 3}, 64});
}

std::size_t g_chain_points[2] = {0, 0};
void epmc_chain(benchmark::State& state, std::size_t chord_unknowns, std::size_t& points) {
  const auto hb = jenkins_chain();
  NonlinearModeOptions opt;
  opt.log10_amplitude_from = -3.0;
  opt.log10_amplitude_to = -0.5;
  opt.continuation.chord_unknowns = chord_unknowns;
  for (auto _ : state) {
    const auto r = nonlinear_mode(hb, opt, {0});
    points = r.amplitude.size();
    benchmark::DoNotOptimize(r.omega.data());
  }
  state.counters["points"] = static_cast<double>(points);
}
void BM_EpmcJenkinsChainFullNewton(benchmark::State& state) {
  epmc_chain(state, 1000000000, g_chain_points[0]);
}
void BM_EpmcJenkinsChainChordNewton(benchmark::State& state) {
  epmc_chain(state, 1, g_chain_points[1]);
}
BENCHMARK(BM_EpmcJenkinsChainFullNewton)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_EpmcJenkinsChainChordNewton)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  asperity::bench::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  auto get = [&](const char* name) { return reporter.seconds_of(name); };
  const double aft = get("BM_AftJenkinsResidualJacobian");
  const double element = get("BM_JenkinsElementTwoPasses");
  const double epmc = get("BM_EpmcJenkinsSdof");
  const double frf = get("BM_FrfRoughFlatSdof");
  const double integ = get("BM_TimeIntegrationRoughFlatSdof200Periods");
  const double rough = get("BM_AftRoughContactResidualJacobian");
  const double jenkins128 = get("BM_AftJenkinsResidualJacobianNt128");
  const double chain_full = get("BM_EpmcJenkinsChainFullNewton");
  const double dry3 = get("BM_AftDryFriction3dCircleNt256");
  const double dry2 = get("BM_AftDryFriction2dLineNt256");
  const double chain_chord = get("BM_EpmcJenkinsChainChordNewton");
  std::printf("\nRatios (same run):\n");
  if (rough > 0) {
    std::printf(
        "  AFT residual + Jacobian, 3-D rough contact, H = 3, N_t = 128 = %7.2f us "
        "(target < 50)\n",
        rough * 1e6);
  }
  if (rough > 0 && jenkins128 > 0) {
    std::printf("  3-D rough contact / Jenkins on the same basis = %7.2f\n", rough / jenkins128);
  }
  if (dry3 > 0 && dry2 > 0) {
    std::printf(
        "  AFT residual + Jacobian, N_t = 256: 3-D dry friction on a circle %.1f us / 2-D on a "
        "line %.1f us = %7.2f\n",
        dry3 * 1e6, dry2 * 1e6, dry3 / dry2);
  }
  if (chain_full > 0 && chain_chord > 0) {
    std::printf(
        "  EPMC, 200-DOF chain with 20 Jenkins joints (1403 unknowns): full Newton %.2f s "
        "(%zu points) / chord Newton %.2f s (%zu points) = %7.2f\n",
        chain_full, g_chain_points[0], chain_chord, g_chain_points[1], chain_full / chain_chord);
  }
  if (aft > 0) {
    std::printf("  AFT residual + Jacobian, Jenkins, H = 3, N_t = 1024 = %7.2f us (target < 20)\n",
                aft * 1e6);
  }
  if (aft > 0 && element > 0) {
    std::printf("  AFT residual + Jacobian / element's two passes alone = %7.2f\n", aft / element);
  }
  if (epmc > 0) {
    std::printf("  EPMC continuation, Jenkins SDOF, %zu points       = %7.2f ms (target < 50)\n",
                g_epmc_points, epmc * 1e3);
  }
  if (frf > 0 && integ > 0) {
    std::printf(
        "  time integration to the same %zu steady states / forced response curve = %7.1f "
        "(target >= 100)\n",
        g_frf_points, integ * static_cast<double>(g_frf_points) / frf);
  }
  benchmark::Shutdown();
  return 0;
}
