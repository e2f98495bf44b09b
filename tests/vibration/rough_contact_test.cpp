// The 3-D rough-contact element (vibration/rough_contact.hpp) and the rough flat's elastic
// unloading from its plastic set (RoughFlat::normal_load_after_set_star).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>

#include "../support.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/dynamics/epb.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "asperity/vibration/elements.hpp"
#include "asperity/vibration/rough_contact.hpp"
#include "element_test_support.hpp"

namespace asperity::vibration {
namespace {

using testing::rel;

using test_support::table_7_2;

constexpr double kPressure = 20e6;  // [Pa], a bolted joint's mean pressure
constexpr double kArea = 4e-6;      // [m^2], one interface patch of 2 x 2 mm

std::shared_ptr<const RoughContactSurface> shared_surface() {
  static const auto s =
      std::make_shared<const RoughContactSurface>(table_7_2(), kPressure / 4.0, kPressure * 4.0);
  return s;
}

const RoughContactElement& shared_element() {
  static const RoughContactElement e(shared_surface(), kArea, kPressure, "test element");
  return e;
}

// A period of N samples: harmonics 1..3 with random phases (inner loops at the larger
// third-harmonic content), scaled to `amplitude`.
Eigen::VectorXd signal(std::size_t N, double amplitude, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ph(0.0, 2.0 * std::numbers::pi);
  std::uniform_real_distribution<double> a(0.2, 1.0);
  const double p1 = ph(rng), p2 = ph(rng), p3 = ph(rng), a2 = a(rng), a3 = a(rng);
  Eigen::VectorXd u(static_cast<Eigen::Index>(N));
  for (std::size_t i = 0; i < N; ++i) {
    const double t = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(N);
    u(static_cast<Eigen::Index>(i)) =
        amplitude * (std::cos(t + p1) + a2 * std::cos(2 * t + p2) + a3 * std::sin(3 * t + p3));
  }
  return u;
}

using test_support::dense_tangent;

// At d* = d_set* the unloading sum is the loading sum (Eq. 4.4): both are quadratures to
// 1e-13, so they agree to ~1e-12.
TEST(RoughFlatUnloading, EqualsLoadingAtTheSet) {
  const RoughContactSurface& s = *shared_surface();
  for (double P : {1e-3, 6e-3, 3e-2}) {
    const double d = s.flat().separation_star(P);
    EXPECT_LT(rel(s.flat().normal_load_after_set_star(d, d), s.flat().normal_load_star(d)), 1e-11)
        << "P* = " << P;
  }
}

// The elastic recovery delta_u = 3 P/(4 E* a) takes each law as Hertz's at small
// interference up to its own scales, P/P_c = c_P w^{3/2}, a/a_c = c_a w^{1/2}: a pure power
// law there (c constant from w = 1e-8 to 1e-4 to 1e-12), c = 1 for CEB and KE (Hertz's
// scales at omega_c).
TEST(RoughFlatUnloading, AsperityLawsAreHertzianAtSmallInterference) {
  for (auto m : {contact::ModelName::ceb, contact::ModelName::ke, contact::ModelName::bke}) {
    const contact::AsperityLaws laws(m, 0.3);
    const double cP = laws.load_star(1e-8) / 1e-12, ca = laws.radius_star(1e-8) / 1e-4;
    EXPECT_LT(rel(laws.load_star(1e-4) / 1e-6, cP), 1e-12) << contact::to_string(m);
    EXPECT_LT(rel(laws.radius_star(1e-4) / 1e-2, ca), 1e-12) << contact::to_string(m);
    if (m != contact::ModelName::bke) {
      EXPECT_LT(rel(cP, 1.0), 1e-12) << contact::to_string(m);
      EXPECT_LT(rel(ca, 1.0), 1e-12) << contact::to_string(m);
    }
  }
}

// Unloading is stiffer than loading (plastic set: the load falls faster as d grows, so at
// any d > d_set it lies below the loading curve) and reloading past the set lies above it;
// both monotone in d. An elastic flat (psi = 0.05: omega_c* = 400 sigma, no asperity
// yields) unloads along its loading curve, to the quadratures' 1e-12.
TEST(RoughFlatUnloading, PlasticSetAndElasticLimit) {
  const RoughContactSurface& s = *shared_surface();
  const double d0 = s.flat().separation_star(6e-3);
  double prev = s.flat().normal_load_after_set_star(d0 - 0.3, d0);
  EXPECT_GT(prev, s.flat().normal_load_star(d0 - 0.3));
  for (double dd : {-0.2, -0.1, 0.05, 0.1, 0.3, 0.6, 1.0}) {
    const double P = s.flat().normal_load_after_set_star(d0 + dd, d0);
    EXPECT_LT(P, prev) << dd;
    if (dd > 0.0) {
      EXPECT_LT(P, s.flat().normal_load_star(d0 + dd)) << dd;
    } else {
      EXPECT_GT(P, s.flat().normal_load_star(d0 + dd)) << dd;
    }
    prev = P;
  }
  surface::RoughFlatParameters rp;
  rp.model = contact::ModelName::bke;
  rp.beta = 0.04;
  rp.psi = 0.05;
  rp.G_over_E = 0.2059;
  const surface::RoughFlat elastic(rp);
  for (double dd : {0.1, 0.5, 1.5}) {
    EXPECT_LT(
        rel(elastic.normal_load_after_set_star(1.0 + dd, 1.0), elastic.normal_load_star(1.0 + dd)),
        1e-11)
        << dd;
  }
}

// Constant normal load, motion along t1: exactly today's rough flat element (the same
// tabulated backbone, the same Masing memory), to 1e-10 of the slip force.
TEST(RoughContactElement, OneDirectionAtConstantLoadIsTodaysRoughFlat) {
  const RoughContactElement& e = shared_element();
  dynamics::EpbContact c = dynamics::table_7_2_rough();
  c.A0 = kArea;
  c.P = kPressure * kArea;
  const MasingElement today(dynamics::epb_backbone(c), "rough_flat", {});
  EXPECT_LT(rel(e.slip_force(), today.slip_force()), 1e-10);
  std::mt19937_64 rng(3);
  const std::size_t N = 128;
  const double delta_slip = today.slip_force() / today.initial_stiffness()(0, 0);
  for (double amplitude : {0.02, 0.3, 1.0, 4.0}) {
    const Eigen::VectorXd x = signal(N, amplitude * delta_slip, rng);
    Eigen::MatrixXd u = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(N), 3);
    u.col(0) = x;
    PeriodicResponse r3, r1;
    e.periodic_response(u, Eigen::MatrixXd(), false, r3);
    today.periodic_response(x, Eigen::MatrixXd(), false, r1);
    EXPECT_LT((r3.f.col(0) - r1.f.col(0)).cwiseAbs().maxCoeff(), 1e-10 * today.slip_force())
        << amplitude;
    EXPECT_EQ(r3.f.col(1).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(r3.f.col(2).cwiseAbs().maxCoeff(), 0.0);  // the prestress is the reference
  }
}

// Masing's identities at constant load (Eq. 4.11-4.13): over a harmonic cycle of amplitude
// A the upper branch is -Q_l(A) + 2 Q_l((x + A)/2) and the lower branch its mirror
// image; the loop passes through (+-A, +-Q_l(A)). Round-off only: 1e-12 of Q_l(A).
TEST(RoughContactElement, MasingIdentities) {
  const RoughContactElement& e = shared_element();
  const double sig = table_7_2().sigma;
  const double scale = 20e6 * kArea / kPressure * shared_surface()->pressure_scale();
  const std::size_t N = 200;
  const double A = 0.5 * e.slip_force() / e.initial_stiffness()(0, 0);
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(N), 3);
  for (std::size_t i = 0; i < N; ++i) {
    u(static_cast<Eigen::Index>(i), 0) =
        A * std::cos(2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(N));
  }
  PeriodicResponse r;
  e.periodic_response(u, Eigen::MatrixXd(), false, r);
  const auto& T = e.prestress_table();
  const double QA = scale * T.force(A / sig);
  for (std::size_t i = 0; i < N; ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    const double x = u(ii, 0);
    const bool unloading = i > 0 && i <= N / 2;  // x falls from +A to -A
    const double expected = unloading ? QA - 2.0 * scale * T.force((A - x) / (2.0 * sig))
                                      : -QA + 2.0 * scale * T.force((x + A) / (2.0 * sig));
    EXPECT_LT(std::abs(r.f(ii, 0) - expected), 1e-12 * QA) << i;
  }
}

// Loss of contact: opened past the last asperity, the element carries no traction (the
// structure receives minus the prestress force, the tractions' change).
TEST(RoughContactElement, LossOfContactGivesZeroTraction) {
  const RoughContactElement& e = shared_element();
  const double sig = table_7_2().sigma;
  const double F0 = kPressure * kArea;
  Eigen::MatrixXd u(4, 3);
  u << 1e-6, -2e-6, -30 * sig, 2e-6, 1e-6, -25 * sig, 0.0, 0.0, 0.0, -1e-6, 0.5e-6, -0.2 * sig;
  PeriodicResponse r;
  e.periodic_response(u, Eigen::MatrixXd(), true, r);
  for (int i : {0, 1}) {
    EXPECT_EQ(r.f(i, 0), 0.0);
    EXPECT_EQ(r.f(i, 1), 0.0);
    EXPECT_LT(rel(r.f(i, 2), -F0), 1e-12);
  }
  EXPECT_EQ(r.f(2, 2), 0.0);
  EXPECT_LT(r.f(3, 2), 0.0);  // opened by 0.2 sigma: partly unloaded
  EXPECT_GT(r.f(3, 2), -F0);
}

// The element at its prestress reproduces the rough flat's own numbers at that load
// (Eq. 4.7 static friction, the tangential stiffness dQ_l/ddelta at 0, Eq. 4.4's load).
TEST(RoughContactElement, PrestressPointIsTheRoughFlats) {
  const RoughContactElement& e = shared_element();
  const RoughContactSurface& s = *shared_surface();
  const double p0 = kPressure / s.pressure_scale();
  const double d0 = s.flat().separation_star(p0);
  const double F = s.pressure_scale() * kArea;
  EXPECT_LT(rel(e.d0_star(), d0), 1e-14);
  // Table 1e-9 (its verified bound) against the adaptive sums (1e-13).
  EXPECT_LT(rel(e.slip_force(), F * s.flat().static_friction_star(d0)), 1e-9);
  EXPECT_LT(rel(e.initial_stiffness()(0, 0), F / s.sigma() * s.flat().stiffness_star(d0)), 1e-9);
  EXPECT_EQ(e.initial_stiffness()(0, 0), e.initial_stiffness()(1, 1));
  // Normal stiffness: -dP*/dd* of the unloading law at the set, by one-sided second-order
  // differences of the sum on the unloading side (smooth there; the third derivative is
  // singular on the other): h = 1e-3 sigma, truncation ~h^2/3 of the third derivative ~1e-7
  // relative; the element's value is a fourth-order difference (error ~1e-10).
  const double h = 1e-3;
  const auto P = [&](double d) { return s.flat().normal_load_after_set_star(d, d0); };
  const double dP = (3.0 * P(d0) - 4.0 * P(d0 + h) + P(d0 + 2.0 * h)) / (2.0 * h);
  EXPECT_LT(rel(e.initial_stiffness()(2, 2), F / s.sigma() * dP), 1e-6);
}

// Between tables the tangential curve at a pressure p is the rough flat's at the load p A
// to the interpolation's accuracy (cubic in ln p, 2^(1/8) apart: ~1e-6 of Q_max).
TEST(RoughContactElement, TangentialCurveAtOtherPressures) {
  const RoughContactElement& e = shared_element();
  const RoughContactSurface& s = *shared_surface();
  for (double f : {0.3, 0.77, 1.3, 2.9}) {
    const double p = f * kPressure / s.pressure_scale();
    const auto exact = s.flat().backbone(s.flat().separation_star(p));
    const double lim = exact->limit();
    EXPECT_LT(rel(e.limit_star(p).Q, lim), 1e-6) << f;
    for (double x : {0.01, 0.1, 0.5, 2.0}) {
      const double xs = x * lim / exact->initial_stiffness();
      EXPECT_LT(std::abs(e.tangential_star(xs, p).Q - exact->force(xs)), 2e-6 * lim)
          << f << " " << x;
    }
  }
}

// The gross-slip fraction (interface maps, nonlinear modes' start check): none in microslip
// (Q_l < Q_max at x* << the slip distance) nor out of contact; at a sliding amplitude, the
// samples whose traction is Q_max(p) (Eq. 4.7) of the sample's own pressure, counted directly.
TEST(RoughContactElement, GrossSlipFraction) {
  const RoughContactElement& e = shared_element();
  const double sig = table_7_2().sigma;
  const int N = 128;
  auto path = [&](double tangential, double normal) {
    Eigen::MatrixXd u(N, 3);
    for (int i = 0; i < N; ++i) {
      const double t = 2.0 * std::numbers::pi * i / N;
      u.row(i) << tangential * std::cos(t), 0.0, normal * std::sin(t);
    }
    PeriodicResponse r;
    e.periodic_response(u, Eigen::MatrixXd(), false, r);
    return r;
  };
  EXPECT_EQ(e.gross_slip_fraction(path(1e-3 * sig, 0.0)), 0.0);
  EXPECT_EQ(e.gross_slip_fraction(path(0.0, 0.0)), 0.0);
  const PeriodicResponse sliding = path(200.0 * sig, 0.2 * sig);
  const double scale = shared_surface()->pressure_scale();
  int at_limit = 0;
  for (int i = 0; i < N; ++i) {
    const double p_star = (kPressure + sliding.f(i, 2) / kArea) / scale;
    const double q_star = std::hypot(sliding.f(i, 0), sliding.f(i, 1)) / (scale * kArea);
    EXPECT_LE(q_star, (1.0 + 1e-9) * e.limit_star(p_star).Q) << i;  // never past the limit
    if (q_star >= (1.0 - 1e-9) * e.limit_star(p_star).Q) ++at_limit;
  }
  EXPECT_GT(at_limit, N / 2);  // 200 sigma: sliding over most of the period
  EXPECT_EQ(e.gross_slip_fraction(sliding), at_limit / static_cast<double>(N));
}

// General paths (both tangential directions, normal load varying, with gross slip and inner
// loops): the AFT tangent (local + history) against central differences, as
// VibrationElements.PeriodicTangentMatchesFiniteDifferences; the dissipated energy
// Int f . du over the period (trapezoidal on the samples) is never negative; the steady
// response repeats (a third pass changes nothing: the period's second pass is periodic).
TEST(RoughContactElement, TangentDissipationAndPeriodicity) {
  const RoughContactElement& e = shared_element();
  const double sig = table_7_2().sigma;
  const double delta_slip = e.slip_force() / e.initial_stiffness()(0, 0);
  std::mt19937_64 rng(5);
  const std::size_t N = 48;
  for (double amplitude : {0.1, 0.6, 3.0}) {
    for (double normal : {0.0, 0.02, 0.1}) {
      Eigen::MatrixXd u(static_cast<Eigen::Index>(N), 3);
      u.col(0) = signal(N, amplitude * delta_slip, rng);
      u.col(1) = signal(N, 0.6 * amplitude * delta_slip, rng);
      u.col(2) = signal(N, normal * sig, rng);
      PeriodicResponse r;
      e.periodic_response(u, Eigen::MatrixXd(), true, r);
      const Eigen::MatrixXd D = dense_tangent(r, static_cast<Eigen::Index>(N), 3);
      const double h = 1e-7 * amplitude * delta_slip;
      Eigen::MatrixXd Dfd(D.rows(), D.cols());
      for (Eigen::Index c = 0; c < D.cols(); ++c) {
        Eigen::MatrixXd up = u, um = u;
        up(c % static_cast<Eigen::Index>(N), c / static_cast<Eigen::Index>(N)) += h;
        um(c % static_cast<Eigen::Index>(N), c / static_cast<Eigen::Index>(N)) -= h;
        PeriodicResponse rp, rm;
        e.periodic_response(up, Eigen::MatrixXd(), false, rp);
        e.periodic_response(um, Eigen::MatrixXd(), false, rm);
        const Eigen::MatrixXd df = (rp.f - rm.f) / (2.0 * h);
        Dfd.col(c) = Eigen::Map<const Eigen::VectorXd>(df.data(), df.size());
      }
      const double scale = D.cwiseAbs().maxCoeff();
      EXPECT_LT((D - Dfd).cwiseAbs().maxCoeff(), 1e-5 * scale)
          << "amplitude " << amplitude << " normal " << normal;
      double W = 0.0, Wn = 0.0, Wmax = 0.0;
      for (std::size_t i = 0; i < N; ++i) {
        const auto a = static_cast<Eigen::Index>(i), b = static_cast<Eigen::Index>((i + 1) % N);
        for (Eigen::Index d = 0; d < 2; ++d) {
          W += 0.5 * (r.f(a, d) + r.f(b, d)) * (u(b, d) - u(a, d));
          Wmax += 0.5 * std::abs((r.f(a, d) + r.f(b, d)) * (u(b, d) - u(a, d)));
        }
        Wn += 0.5 * (r.f(a, 2) + r.f(b, 2)) * (u(b, 2) - u(a, 2));
      }
      // At constant normal load the tangential work is the Masing loops' area, never
      // negative; with the load varying the tangential stiffness varies with it, and the
      // decoupled law (the normal force does not depend on the tangential displacement) is
      // not conservative in stick: docs/rough_contact.md, "Limits". Wn: the normal law is
      // elastic during vibration, its work over a period vanishes up to the trapezoidal
      // rule's error.
      if (normal == 0.0) {
        EXPECT_GE(W, -1e-12 * Wmax) << "amplitude " << amplitude;
      }
      (void)Wn;
      // Periodicity: the response to three periods, last period, equals the one-period answer.
      Eigen::MatrixXd u3(3 * static_cast<Eigen::Index>(N), 3);
      u3 << u, u, u;
      PeriodicResponse r3;
      e.periodic_response(u3, Eigen::MatrixXd(), false, r3);
      EXPECT_LT((r3.f.bottomRows(static_cast<Eigen::Index>(N)) - r.f).cwiseAbs().maxCoeff(),
                1e-9 * e.slip_force())
          << "amplitude " << amplitude << " normal " << normal;
    }
  }
}

// Masing's loop memory under a varying normal load: a harmonic tangential cycle with the
// pressure varying in phase (by ~4 %), the peak of the motion half-way between two samples,
// so that moving one of them by +-h moves the reversal and where the loop closes. The force
// must stay a continuous function of the samples: piecewise smooth, with a kink where the
// reversal changes sample, so the central difference is bounded by the largest one-sided
// slope, |f(u + h) - f(u - h)| <= 2 h max|D|, with D the tangent (bound taken twice). Closing
// a loop with the reversal force kept at its own pressure jumped the force there by
// 2 [Q_l(.; p(t)) - Q_l(.; p_r)] (6 % of it on the two_blocks EPMC, docs/vibration.md):
// ~1e5 times the bound here.
TEST(RoughContactElement, LoopMemoryIsContinuousUnderVaryingLoad) {
  const RoughContactElement& e = shared_element();
  const double sig = table_7_2().sigma;
  const double delta_slip = e.slip_force() / e.initial_stiffness()(0, 0);
  const std::size_t N = 32;
  for (double amplitude : {1e-3, 0.1, 0.5}) {
    Eigen::MatrixXd u = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(N), 3);
    for (std::size_t i = 0; i < N; ++i) {
      const double t = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(N);
      // The peak half-way between samples 0 and 1 (and the trough between N/2 and N/2 + 1),
      // the pressure highest at the peak and lowest at the trough.
      const double phase = std::numbers::pi / static_cast<double>(N);
      u(static_cast<Eigen::Index>(i), 0) = amplitude * delta_slip * std::cos(t - phase);
      u(static_cast<Eigen::Index>(i), 2) = 0.02 * sig * std::cos(t - phase);
    }
    PeriodicResponse r;
    e.periodic_response(u, Eigen::MatrixXd(), true, r);
    const Eigen::MatrixXd D = dense_tangent(r, static_cast<Eigen::Index>(N), 3);
    const double h = 1e-7 * amplitude * delta_slip;
    const double scale = D.cwiseAbs().maxCoeff();
    for (const Eigen::Index i : {Eigen::Index{0}, static_cast<Eigen::Index>(N / 2)}) {
      Eigen::MatrixXd up = u, um = u;
      up(i, 0) += h;
      um(i, 0) -= h;
      PeriodicResponse rp, rm;
      e.periodic_response(up, Eigen::MatrixXd(), false, rp);
      e.periodic_response(um, Eigen::MatrixXd(), false, rm);
      EXPECT_LT((rp.f - rm.f).cwiseAbs().maxCoeff(), 4.0 * h * scale)
          << "amplitude " << amplitude << " sample " << i;
    }
  }
}

// Bad input names the item.
TEST(RoughContactElement, RefusesBadInput) {
  EXPECT_NE(testing::invalid_input_message([] {
              RoughContactElement(shared_surface(), 0.0, kPressure, "element 3");
            }).find("element 3: area = 0"),
            std::string::npos);
  EXPECT_NE(testing::invalid_input_message([] {
              RoughContactElement(shared_surface(), kArea, kPressure * 10.0, "element 4");
            }).find("element 4: prestress pressure"),
            std::string::npos);
  RoughInterfaceParameters p = table_7_2();
  p.H = 2.0 * p.E_star;
  EXPECT_NE(testing::invalid_input_message([&] {
              RoughContactSurface(p, 1e6, 1e7);
            }).find("rough_contact.H"),
            std::string::npos);
}

TEST(RoughContactSurface, TablesReachTheLargestLoadTheFlatRepresents) {
  // A range ending just under the flat's largest load (an interface whose most pressed
  // element is near it; the BRB's p_max / 8 .. 0.999 p_flat): the nodes, 2^(1/8) apart from
  // p_low up, would pass p_flat; they end at p_high instead and still cover [p_low, p_high]
  // (the first node below p_low). An element at p_high is accepted and evaluates.
  const RoughInterfaceParameters p = table_7_2();
  const auto probe = std::make_shared<const RoughContactSurface>(p, 1e6, 2e6);
  const double p_flat = probe->flat().max_load_star() * probe->pressure_scale();
  const double p_high = 0.999 * p_flat, p_low = p_high / 64.0 * 1.05;
  const auto s = std::make_shared<const RoughContactSurface>(p, p_low, p_high);
  const double scale = s->pressure_scale();
  EXPECT_LE(s->table_pressure_star(0) * scale, p_low);
  EXPECT_LE(rel(s->table_pressure_star(s->tables() - 1) * scale, p_high), 1e-12);
  EXPECT_LE(s->table_pressure_star(s->tables() - 1), s->flat().max_load_star());
  const RoughContactElement e(s, kArea, p_high, "element at the top");
  EXPECT_LE(rel(e.pressure(0.0).p, p_high / scale), 1e-12);
  EXPECT_GT(e.limit_star(p_high / scale).Q, 0.0);
  EXPECT_THROW((void)e.limit_star(1.01 * p_high / scale), NumericalError);
}

}  // namespace
}  // namespace asperity::vibration

namespace asperity::surface {
namespace {

// A flat described by its summit heights' standard deviation (a measured summit
// distribution) is the same physical flat as one described by the surface heights' rms
// sigma_s with sigma_a = sqrt(1 - 3.717e-4/beta^2) sigma_s (Eq. 4.2): at the same separation
// in metres, the same load and static friction (Eq. 4.4, 4.7) to the quadratures' 1e-12.
TEST(RoughFlatSummitHeights, SameFlatAsFromTheSurfaceRms) {
  const contact::Material steel{.E = 200e9, .nu = 0.3, .G = 0.0, .H = 5.8e9};
  const double sigma = 2.7e-6, R = 30.1e-6, eta = 2.9e8;
  const auto by_surface =
      RoughFlat::from_dimensional(steel, steel, sigma, eta, R, 1.0, contact::ModelName::bke);
  const double sigma_a = by_surface.sigma_a_over_sigma() * sigma;
  const auto by_summits =
      RoughFlat::from_summit_heights(steel, steel, sigma_a, eta, R, 1.0, contact::ModelName::bke);
  EXPECT_EQ(by_summits.sigma_a_over_sigma(), 1.0);
  EXPECT_LT(testing::rel(by_summits.parameters().psi, by_surface.parameters().psi), 1e-14);
  for (double d : {0.5e-6, 2e-6, 5e-6}) {
    EXPECT_LT(testing::rel(by_summits.normal_load_star(d / sigma_a),
                           by_surface.normal_load_star(d / sigma)),
              1e-12)
        << d;
    EXPECT_LT(testing::rel(by_summits.static_friction_star(d / sigma_a),
                           by_surface.static_friction_star(d / sigma)),
              1e-12)
        << d;
  }
}

// from_combined with summit_sigma (the form a reduced model's rough_surface record and
// RoughInterfaceParameters::summit_sigma use) is from_summit_heights's flat: the same
// parameters to the last bit (the same formulas on the combined values).
TEST(RoughFlatSummitHeights, FromCombinedEqualsFromSummitHeights) {
  const contact::Material steel{.E = 200e9, .nu = 0.3, .G = 0.0, .H = 5.8e9};
  const double sigma_a = 3.17e-6, R = 30.1e-6, eta = 2.9e8;
  const auto a =
      RoughFlat::from_summit_heights(steel, steel, sigma_a, eta, R, 1.0, contact::ModelName::bke);
  const auto& pair = a.scales()->pair;
  const auto b = RoughFlat::from_combined(pair.E_star, pair.G_star, pair.H, pair.nu, sigma_a, R,
                                          eta, contact::ModelName::bke, {}, true);
  EXPECT_TRUE(b.parameters().summit_sigma);
  EXPECT_EQ(b.parameters().beta, a.parameters().beta);
  EXPECT_EQ(b.parameters().psi, a.parameters().psi);
  EXPECT_EQ(b.parameters().G_over_E, a.parameters().G_over_E);
  EXPECT_EQ(b.normal_load_star(1.5), a.normal_load_star(1.5));
}

}  // namespace
}  // namespace asperity::surface
