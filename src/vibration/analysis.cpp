#include "asperity/vibration/analysis.hpp"

// g++ 12 at -O3 reports the non-empty vectors of the quasi-static integration as
// potential null dereferences (a known false positive of -Wnull-dereference).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/LU>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "common.hpp"

namespace asperity::vibration {

namespace {

// Smallest prominence of a reported peak, relative to its amplitude (that of a fold:
// detail::kFoldProminence, common.hpp). On the hardening-contact case of issue 23 the
// Z's of sample-located contact reach 2.0e-2 in amplitude and stay below 1e-2 of the range
// in frequency; its resonance peaks have prominences 0.24 to 0.97 and its folds 0.06 to
// 0.2 of the range.
constexpr double kPeakProminence = 5e-2;

// The stuck structure's mode `mode` (1-based), mass-normalized.
struct StuckMode {
  Eigen::VectorXd phi;
  double omega = 0.0;
};

StuckMode stuck_mode(const HarmonicBalance& hb, int mode) {
  const LinearModes lm = linear_modes(hb.stuck_stiffness(), hb.structure().M);
  if (mode < 1 || mode > lm.omega.size()) {
    throw InvalidInput(
        fmt::format("mode = {}: the structure has modes 1 .. {}", mode, lm.omega.size()));
  }
  StuckMode s{lm.shapes.col(mode - 1), lm.omega(mode - 1)};
  // A negative eigenvalue beyond rounding (1e-9 of the largest): K with the joints stuck is
  // indefinite, the structure unstable at rest; not a rigid-body mode (omega^2 = 0).
  const double lambda = lm.eigenvalues(mode - 1);
  if (lambda < -1e-9 * lm.eigenvalues.cwiseAbs().maxCoeff()) {
    throw InvalidInput(fmt::format(
        "mode {} of the structure with its joints stuck has a negative eigenvalue omega^2 = "
        "{:.6g} (rad/s)^2: the stiffness (structure.stiffness plus the elements' initial "
        "stiffnesses) is not positive semi-definite, so the structure is unstable at rest; check "
        "for a negative stiffness",
        mode, lambda));
  }
  if (!(s.omega > 0.0)) {
    throw InvalidInput(fmt::format(
        "mode {} of the structure with its joints stuck has zero frequency (a rigid-body mode): "
        "ground the structure or choose another mode",
        mode));
  }
  return s;
}

}  // namespace

void NonlinearModeOptions::validate() const {
  if (mode < 1)
    throw InvalidInput(fmt::format("nonlinear_mode.mode = {}: modes count from 1", mode));
  core::require_in_closed("nonlinear_mode.log10_amplitude.from", log10_amplitude_from, -30.0, 30.0);
  core::require_in_closed("nonlinear_mode.log10_amplitude.to", log10_amplitude_to, -30.0, 30.0);
  if (log10_amplitude_from == log10_amplitude_to) {
    throw InvalidInput("nonlinear_mode.log10_amplitude: from and to are equal");
  }
  continuation.validate();
}

namespace {

// A nonlinear mode's range must start where the joints stick (or microslip): along the stuck
// mode at the start amplitude, no element with a slip limit may reach it. A start in gross
// slip misses the linear end of the backbone, and its Newton start, the linear mode, is far
// from the solution.
void require_start_in_stick(const HarmonicBalance& hb, const StuckMode& sm,
                            const NonlinearModeOptions& opt) {
  const HarmonicBasis& basis = hb.basis();
  const auto nc = static_cast<Eigen::Index>(basis.coefficients());
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(nc, hb.dofs());  // coefficients x DOFs
  const double a = std::pow(10.0, opt.log10_amplitude_from);
  X.row(basis.index_of(1, 0)) = a * sm.phi.transpose();
  PeriodicResponse resp;
  for (std::size_t e = 0; e < hb.elements().size(); ++e) {
    const PlacedElement& pe = hb.elements()[e];
    const Eigen::MatrixXd Xe = X * pe.T.transpose();
    const Eigen::MatrixXd u = basis.synthesis() * Xe;
    Eigen::MatrixXd v;
    if (pe.element->velocity_dependent())
      v = sm.omega * (basis.synthesis() * (basis.derivative() * Xe));
    pe.element->periodic_response(u, v, false, resp);
    const double slipping = pe.element->gross_slip_fraction(resp);
    if (!(slipping > 0.0)) continue;  // NaN: no stuck state to leave
    // The amplitude at which the stuck joint's force would reach the slip force.
    const Eigen::VectorXd f0 = pe.element->initial_stiffness() * (pe.T * sm.phi);
    const double tangential =
        pe.element->directions() == 3 ? std::hypot(f0(0), f0(1)) : std::abs(f0(0));
    std::string hint;
    if (tangential > 0.0 && std::isfinite(pe.element->slip_force())) {
      hint = fmt::format(
          "; its stuck force reaches the slip force near log10 amplitude {:.2f}: start a decade or "
          "more below",
          std::log10(pe.element->slip_force() / tangential));
    }
    throw InvalidInput(fmt::format(
        "nonlinear_mode: log10_amplitude starts at {} in gross slip: along the stuck mode {} at "
        "amplitude {}, {} ({}) slides at its slip limit over {:.3g} % of the period{}",
        core::format_value(opt.log10_amplitude_from), opt.mode, core::format_value(a), pe.name,
        pe.element->type(), 100.0 * slipping, hint));
  }
}

}  // namespace

NonlinearModeResult nonlinear_mode(const HarmonicBalance& hb, const NonlinearModeOptions& opt,
                                   const std::vector<Eigen::Index>& outputs,
                                   const ProgressFunction& progress) {
  opt.validate();
  detail::require_outputs(hb, outputs);
  const HarmonicBasis& basis = hb.basis();
  const Eigen::Index n = hb.dofs();
  const Eigen::Index nu = hb.unknowns();
  const auto nc = static_cast<Eigen::Index>(basis.coefficients());
  const long i1c = basis.index_of(1, 0), i1s = basis.index_of(1, 1);
  const Eigen::MatrixXd& M = hb.structure().M;
  const Eigen::MatrixXd& C = hb.structure().C;
  const StuckMode sm = stuck_mode(hb, opt.mode);
  const Eigen::VectorXd Mphi = M * sm.phi;

  // Kronecker (M (x) D): the derivative of A with respect to xi is -omega (M (x) D).
  Eigen::MatrixXd MD = Eigen::MatrixXd::Zero(nu, nu);
  for (Eigen::Index q = 0; q < n; ++q) {
    for (Eigen::Index p = 0; p < n; ++p) {
      if (M(p, q) != 0.0) MD.block(p * nc, q * nc, nc, nc) = M(p, q) * basis.derivative();
    }
  }
  const double res_scale = sm.omega * sm.omega * Mphi.cwiseAbs().maxCoeff();
  auto first = [&](const Eigen::VectorXd& Psi, long idx) {
    Eigen::VectorXd v(n);
    for (Eigen::Index d = 0; d < n; ++d) v(d) = Psi(d * nc + idx);
    return v;
  };

  // y = [Psi, omega, xi, log10 a]; R = [A_xi(omega) Psi + F(a Psi)/a; norm; phase].
  const SystemFunction f = [&](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    const Eigen::VectorXd Psi = y.head(nu);
    const double omega = y(nu), xi = y(nu + 1), la = y(nu + 2);
    const double a = std::pow(10.0, la);
    const Eigen::MatrixXd Ceff = C - xi * M;
    Eigen::VectorXd F, dF_dw;
    Eigen::MatrixXd dF;
    const Eigen::VectorXd U = a * Psi;
    hb.nonlinear_force(U, omega, F, J ? &dF : nullptr, J ? &dF_dw : nullptr);
    const Eigen::MatrixXd A = hb.dynamic_stiffness(omega, Ceff);
    R.resize(nu + 2);
    R.head(nu) = A * Psi + F / a;
    const Eigen::VectorXd p1c = first(Psi, i1c), p1s = first(Psi, i1s);
    R(nu) = res_scale * (p1c.dot(M * p1c) + p1s.dot(M * p1s) - 1.0);  // mass normalization
    R(nu + 1) = res_scale * p1s.dot(Mphi);                            // phase
    if (!J) return;
    J->setZero(nu + 2, nu + 3);
    J->topLeftCorner(nu, nu) = A + dF;
    J->block(0, nu, nu, 1) = hb.dynamic_stiffness_derivative(omega, Ceff) * Psi + dF_dw / a;
    J->block(0, nu + 1, nu, 1) = -omega * (MD * Psi);
    J->block(0, nu + 2, nu, 1) = std::numbers::ln10 * (dF * Psi - F / a);
    const Eigen::VectorXd Mp1c = M * p1c, Mp1s = M * p1s;
    for (Eigen::Index d = 0; d < n; ++d) {
      (*J)(nu, d * nc + i1c) = res_scale * 2.0 * Mp1c(d);
      (*J)(nu, d * nc + i1s) = res_scale * 2.0 * Mp1s(d);
      (*J)(nu + 1, d * nc + i1s) = res_scale * Mphi(d);
    }
  };

  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(nu + 3);
  for (Eigen::Index d = 0; d < n; ++d) y0(d * nc + i1c) = sm.phi(d);
  y0(nu) = sm.omega;
  y0(nu + 1) = sm.phi.dot(C * sm.phi);
  y0(nu + 2) = opt.log10_amplitude_from;

  require_start_in_stick(hb, sm, opt);

  ContinuationProblem pb;
  pb.f = f;
  pb.parameter = nu + 2;
  pb.scale = Eigen::VectorXd::Constant(nu + 3, sm.phi.cwiseAbs().maxCoeff());
  pb.scale(nu) = sm.omega;
  pb.scale(nu + 1) = 0.1 * sm.omega;
  pb.scale(nu + 2) = 1.0;
  pb.residual_scale = res_scale;
  pb.parameter_end = opt.log10_amplitude_to;

  NonlinearModeResult out;
  out.linear_omega = sm.omega;
  out.linear_damping_ratio = sm.phi.dot(C * sm.phi) / (2.0 * sm.omega);
  out.continuation = continue_curve(pb, y0, opt.continuation, progress);
  const auto np = static_cast<Eigen::Index>(out.continuation.points.size());
  out.log10_amplitude.resize(np);
  out.amplitude.resize(np);
  out.omega.resize(np);
  out.frequency_hz.resize(np);
  out.xi.resize(np);
  out.damping_ratio.resize(np);
  out.output_amplitude.resize(np, static_cast<Eigen::Index>(outputs.size()));
  for (Eigen::Index k = 0; k < np; ++k) {
    const Eigen::VectorXd& y = out.continuation.points[static_cast<std::size_t>(k)];
    const double a = std::pow(10.0, y(nu + 2));
    out.log10_amplitude(k) = y(nu + 2);
    out.amplitude(k) = a;
    out.omega(k) = y(nu);
    out.frequency_hz(k) = y(nu) / (2.0 * std::numbers::pi);
    out.xi(k) = y(nu + 1);
    out.damping_ratio(k) = y(nu + 1) / (2.0 * y(nu));
    const Eigen::VectorXd U = a * y.head(nu);
    for (std::size_t o = 0; o < outputs.size(); ++o) {
      out.output_amplitude(k, static_cast<Eigen::Index>(o)) =
          hb.harmonic_amplitude(U, outputs[o], 1);
    }
    out.harmonics.push_back(U);
  }
  if (!out.continuation.complete) {
    out.warnings.push_back("nonlinear mode: " + out.continuation.stop_reason);
  }
  for (Eigen::Index k = 0; k < np; ++k) {
    if (out.damping_ratio(k) < 0.0 && out.damping_ratio(k) < -1e-6) {
      out.warnings.push_back(fmt::format(
          "nonlinear mode: negative damping ratio {} at amplitude {} (energy enters the mode)",
          core::format_value(out.damping_ratio(k)), core::format_value(out.amplitude(k))));
      break;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------

void FrequencyResponseOptions::validate(Eigen::Index unknowns) const {
  if (force.size() != unknowns) {
    throw InvalidInput(fmt::format("frequency_response: the force has {} coefficients, {} expected",
                                   force.size(), unknowns));
  }
  if (!force.allFinite())
    throw InvalidInput("frequency_response: the force holds a NaN or infinity");
  if (force.cwiseAbs().maxCoeff() == 0.0) {
    throw InvalidInput("frequency_response: the force is zero: give force_cos or force_sin");
  }
  if (force_scales.empty()) throw InvalidInput("frequency_response.force_scales is empty");
  for (std::size_t k = 0; k < force_scales.size(); ++k) {
    core::require_positive(fmt::format("frequency_response.force_scales[{}]", k + 1),
                           force_scales[k]);
  }
  core::require_positive("frequency_response.omega.from", omega_from);
  core::require_positive("frequency_response.omega.to", omega_to);
  if (omega_from == omega_to) throw InvalidInput("frequency_response.omega: from and to are equal");
  continuation.validate();
  hill.validate();
}

std::vector<FrequencyResponseCurve> frequency_response(const HarmonicBalance& hb,
                                                       const FrequencyResponseOptions& opt,
                                                       const std::vector<Eigen::Index>& outputs,
                                                       const ProgressFunction& progress) {
  opt.validate(hb.unknowns());
  detail::require_outputs(hb, outputs);
  const Eigen::Index nu = hb.unknowns();
  const Eigen::MatrixXd Ks = hb.stuck_stiffness();
  const auto& harmonics = hb.basis().harmonics();
  std::vector<FrequencyResponseCurve> curves;
  for (std::size_t level = 0; level < opt.force_scales.size(); ++level) {
    const double s = opt.force_scales[level];
    const Eigen::VectorXd F1 = opt.force_per_omega.size() ? Eigen::VectorXd(s * opt.force_per_omega)
                                                          : Eigen::VectorXd::Zero(nu);
    const Eigen::VectorXd F2 = opt.force_per_omega2.size()
                                   ? Eigen::VectorXd(s * opt.force_per_omega2)
                                   : Eigen::VectorXd::Zero(nu);
    const auto excitation = [&](double w) -> Eigen::VectorXd {
      return s * opt.force + w * F1 + w * w * F2;
    };
    // The stuck linear response: the start, and the scale of the unknowns.
    Structure stuck = hb.structure();
    stuck.K = Ks;
    const HarmonicBalance lin(stuck, {},
                              HarmonicBalanceOptions{harmonics, hb.basis().time_points()});
    double u_scale = 0.0;
    for (int k = 0; k <= 64; ++k) {
      const double w = opt.omega_from + (opt.omega_to - opt.omega_from) * k / 64.0;
      const Eigen::VectorXd U =
          lin.dynamic_stiffness(w, stuck.C).partialPivLu().solve(excitation(w));
      if (U.allFinite()) u_scale = std::max(u_scale, U.cwiseAbs().maxCoeff());
    }
    if (!(u_scale > 0.0) || !std::isfinite(u_scale)) u_scale = 1.0;
    Eigen::VectorXd y0(nu + 1);
    y0.head(nu) = lin.dynamic_stiffness(opt.omega_from, stuck.C)
                      .partialPivLu()
                      .solve(excitation(opt.omega_from));
    if (!y0.head(nu).allFinite()) y0.head(nu).setZero();
    y0(nu) = opt.omega_from;

    ContinuationProblem pb;
    pb.f = [&](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
      Eigen::MatrixXd dR;
      Eigen::VectorXd dRw;
      const double w = y(nu);
      hb.residual(y.head(nu), w, excitation(w), R, J ? &dR : nullptr, J ? &dRw : nullptr);
      if (J) {
        J->resize(nu, nu + 1);
        J->leftCols(nu) = dR;
        J->col(nu) = dRw - F1 - 2.0 * w * F2;
      }
    };
    pb.parameter = nu;
    pb.scale = Eigen::VectorXd::Constant(nu + 1, u_scale);
    pb.scale(nu) = std::abs(opt.omega_to - opt.omega_from);
    pb.residual_scale = std::max(excitation(opt.omega_from).cwiseAbs().maxCoeff(),
                                 excitation(opt.omega_to).cwiseAbs().maxCoeff());
    pb.parameter_end = opt.omega_to;

    FrequencyResponseCurve c;
    c.force_scale = s;
    const ProgressFunction sub = progress ? ProgressFunction([&](double x) {
      progress((static_cast<double>(level) + x) / static_cast<double>(opt.force_scales.size()));
    })
                                          : ProgressFunction{};
    c.continuation = continue_curve(pb, y0, opt.continuation, sub);
    const auto np = static_cast<Eigen::Index>(c.continuation.points.size());
    const auto no = static_cast<Eigen::Index>(outputs.size());
    c.omega.resize(np);
    c.output_amplitude.resize(np, no);
    c.max_displacement.resize(np, no);
    c.harmonic_amplitude.assign(outputs.size(),
                                Eigen::MatrixXd(np, static_cast<Eigen::Index>(harmonics.size())));
    for (Eigen::Index k = 0; k < np; ++k) {
      const Eigen::VectorXd& y = c.continuation.points[static_cast<std::size_t>(k)];
      const Eigen::VectorXd U = y.head(nu);
      c.omega(k) = y(nu);
      for (Eigen::Index o = 0; o < no; ++o) {
        const Eigen::Index dof = outputs[static_cast<std::size_t>(o)];
        c.output_amplitude(k, o) = hb.harmonic_amplitude(U, dof, 1);
        c.max_displacement(k, o) = hb.max_displacement(U, dof);
        for (std::size_t h = 0; h < harmonics.size(); ++h) {
          c.harmonic_amplitude[static_cast<std::size_t>(o)](k, static_cast<Eigen::Index>(h)) =
              hb.harmonic_amplitude(U, dof, harmonics[h]);
        }
      }
      c.harmonics.push_back(U);
      if (opt.stability)
        c.stability.push_back(hill_stability(hb, U, y(nu), hb.structure().C, opt.hill));
    }
    // Peaks of each output and folds, refined between the computed points. Contact and
    // slip located at samples fold the curve into Z's one sample wide (issue 23): those
    // are left out by their prominence, below kPeakProminence of the amplitude for a
    // peak and detail::kFoldProminence of the frequency range for a fold.
    const auto& pts = c.continuation.points;
    const auto first_harmonic = [&](const Eigen::VectorXd& y, Eigen::Index dof) {
      return hb.harmonic_amplitude(y.head(nu), dof, 1);
    };
    const double fold_prominence =
        detail::kFoldProminence * std::abs(opt.omega_to - opt.omega_from);
    std::vector<std::pair<std::size_t, double>> fold_at;  // point, +1 max / -1 min of omega
    for (const double sense_w : {1.0, -1.0}) {
      std::vector<double> w(pts.size());
      for (std::size_t k = 0; k < pts.size(); ++k) w[k] = sense_w * pts[k](nu);
      for (const std::size_t k : prominent_maxima(w, [&](double) { return fold_prominence; })) {
        fold_at.emplace_back(k, sense_w);
      }
    }
    std::sort(fold_at.begin(), fold_at.end());
    for (const auto& [k, fold_sense] : fold_at) {
      const double sense_w = fold_sense;
      const Eigen::VectorXd y =
          refine_curve_maximum(pb, pts, k, opt.continuation.newton,
                               [&](const Eigen::VectorXd& yy) { return sense_w * yy(nu); });
      ResponseFold f;
      f.omega = y(nu);
      f.output_amplitude.resize(no);
      for (Eigen::Index o = 0; o < no; ++o) {
        f.output_amplitude(o) = first_harmonic(y, outputs[static_cast<std::size_t>(o)]);
      }
      f.harmonics = y.head(nu);
      c.folds.push_back(std::move(f));
    }
    for (Eigen::Index o = 0; o < no; ++o) {
      const Eigen::Index dof = outputs[static_cast<std::size_t>(o)];
      std::vector<double> a(pts.size());
      for (std::size_t k = 0; k < pts.size(); ++k)
        a[k] = c.output_amplitude(static_cast<Eigen::Index>(k), o);
      for (const std::size_t k :
           prominent_maxima(a, [](double v) { return kPeakProminence * v; })) {
        const Eigen::VectorXd y = refine_curve_maximum(
            pb, pts, k, opt.continuation.newton,
            [&](const Eigen::VectorXd& yy) { return first_harmonic(yy, dof); });
        c.peaks.push_back({static_cast<std::size_t>(o), y(nu), first_harmonic(y, dof), y.head(nu)});
      }
    }
    if (!c.continuation.complete) {
      c.warnings.push_back(fmt::format("frequency response at force scale {}: {}",
                                       core::format_value(s), c.continuation.stop_reason));
    }
    curves.push_back(std::move(c));
  }
  return curves;
}

// ---------------------------------------------------------------------------------------

void QuasiStaticModeOptions::validate() const {
  if (mode < 1)
    throw InvalidInput(fmt::format("quasi_static_mode.mode = {}: modes count from 1", mode));
  core::require_positive("quasi_static_mode.amplitude.from", amplitude_from);
  core::require_positive("quasi_static_mode.amplitude.to", amplitude_to);
  if (!(amplitude_to > amplitude_from)) {
    throw InvalidInput(fmt::format("quasi_static_mode.amplitude: to = {} must be above from = {}",
                                   core::format_value(amplitude_to),
                                   core::format_value(amplitude_from)));
  }
  if (points < 2 || points > 100000) {
    throw InvalidInput(
        fmt::format("quasi_static_mode.points = {}: must be in [2, 100000]", points));
  }
  newton.validate();
}

QuasiStaticModeResult quasi_static_mode(const HarmonicBalance& hb,
                                        const QuasiStaticModeOptions& opt) {
  opt.validate();
  for (const PlacedElement& pe : hb.elements()) {
    if (!pe.element->masing_from_virgin_curve()) {
      throw InvalidInput(fmt::format(
          "quasi_static_mode: element \"{}\" ({}) does not follow Masing's rules on its virgin "
          "curve, which the quasi-static estimate assumes (its energy per cycle comes from the "
          "static push): use [nonlinear_mode] (EPMC), which takes the element's own loops",
          pe.name, pe.element->type()));
    }
  }
  const Eigen::Index n = hb.dofs();
  const Eigen::MatrixXd& M = hb.structure().M;
  const Eigen::MatrixXd& K = hb.structure().K;
  const StuckMode sm = stuck_mode(hb, opt.mode);
  const Eigen::VectorXd Mphi = M * sm.phi;
  const double res_scale = sm.omega * sm.omega * Mphi.cwiseAbs().maxCoeff();

  // Static push: K x + sum T^T f(T x) - lambda M phi = 0, phi^T M x = q.
  double q = 0.0;
  const SystemFunction f = [&](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    const Eigen::VectorXd x = y.head(n);
    const double lambda = y(n);
    R.resize(n + 1);
    R.head(n) = K * x - lambda * Mphi;
    if (J) {
      J->setZero(n + 1, n + 1);
      J->topLeftCorner(n, n) = K;
      J->block(0, n, n, 1) = -Mphi;
      J->block(n, 0, 1, n) = res_scale * Mphi.transpose() / sm.phi.cwiseAbs().maxCoeff();
    }
    for (const PlacedElement& pe : hb.elements()) {
      Eigen::VectorXd fe;
      Eigen::MatrixXd Ke;
      pe.element->static_response(pe.T * x, fe, Ke);
      R.head(n) += pe.T.transpose() * fe;
      if (J) J->topLeftCorner(n, n) += pe.T.transpose() * Ke * pe.T;
    }
    R(n) = res_scale * (Mphi.dot(x) - q) / sm.phi.cwiseAbs().maxCoeff();
  };

  // A 4-times finer internal grid, log-spaced, for the energy integral.
  const std::size_t refine = 4;
  const std::size_t nf = (opt.points - 1) * refine + 1;
  const double l0 = std::log(opt.amplitude_from), l1 = std::log(opt.amplitude_to);
  std::vector<double> qs(nf), lam(nf), g(nf);
  QuasiStaticModeResult out;
  out.linear_omega = sm.omega;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n + 1);
  for (std::size_t k = 0; k < nf; ++k) {
    q = std::exp(l0 + (l1 - l0) * static_cast<double>(k) / static_cast<double>(nf - 1));
    // Start from the previous solution scaled to the new amplitude.
    if (k == 0) {
      y.head(n) = q * sm.phi;
      y(n) = sm.omega * sm.omega * q;
    } else {
      y *= q / qs[k - 1];
    }
    Eigen::VectorXd scale = Eigen::VectorXd::Constant(n + 1, q * sm.phi.cwiseAbs().maxCoeff());
    scale(n) = sm.omega * sm.omega * q;
    const NewtonResult r = solve_newton(f, y, scale, res_scale * q, opt.newton);
    out.newton_iterations += static_cast<std::size_t>(r.iterations);
    if (!r.converged) {
      throw NumericalError(fmt::format(
          "quasi-static mode: the static push did not converge at modal amplitude {} (residual "
          "{}): the joint may have slipped completely (no static equilibrium beyond its slip "
          "force); lower amplitude.to",
          core::format_value(q), core::format_value(r.residual_norm)));
    }
    y = r.y;
    // Tangent d lambda / d q from the bordered Jacobian: J [dx; dl] = [0; d R_q / d q]^-.
    Eigen::VectorXd R;
    Eigen::MatrixXd J;
    f(y, R, &J);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
    rhs(n) = res_scale / sm.phi.cwiseAbs().maxCoeff();
    const Eigen::VectorXd dy = J.partialPivLu().solve(rhs);
    const double k_tan = dy(n);
    qs[k] = q;
    lam[k] = y(n);
    // Masing: D = 4 int_0^q (lambda - q' lambda') dq', integrand q' (k_sec - k_tan).
    g[k] = q * (y(n) / q - k_tan);
  }
  // Cumulative integral of v(q) dq = v q d(ln q) on the fine grid: trapezoids, each pair
  // of intervals replaced by Simpson's rule at the even points (the output points).
  const double hstep = (l1 - l0) / static_cast<double>(nf - 1);
  auto cumulative = [&](const std::vector<double>& v, double start) {
    std::vector<double> I(nf);
    I[0] = start;
    for (std::size_t k = 1; k < nf; ++k) {
      if (k % 2 == 0) {
        I[k] = I[k - 2] +
               hstep / 3.0 * (v[k - 2] * qs[k - 2] + 4.0 * v[k - 1] * qs[k - 1] + v[k] * qs[k]);
      } else {
        I[k] = I[k - 1] + 0.5 * hstep * (v[k - 1] * qs[k - 1] + v[k] * qs[k]);
      }
    }
    return I;
  };
  // Masing's energy per cycle on the modal backbone, two equal forms:
  //  D = 4 int_0^a (lambda - q lambda') dq: no cancellation at small amplitude (the
  //      integrand q (k_sec - k_tan) vanishes with the nonlinearity), but a jump of k_tan
  //      (a Jenkins slider's slip onset) costs O(h) there;
  //  D = 8 int_0^a lambda dq - 4 a lambda(a): O(h^2) across kinks, but a difference of
  //      terms 1/(D / 4 a lambda) times larger than D.
  // The first below D = 1 % of 4 a lambda, the second above (at most two digits lost);
  // the piece below the first point from g ~ q^2 (int_0^q0 g = g(q0) q0 / 3).
  const std::vector<double> Dg = [&] {
    std::vector<double> I = cumulative(g, std::max(0.0, g[0]) * qs[0] / 3.0);
    for (double& x : I) x *= 4.0;
    return I;
  }();
  const std::vector<double> Il = cumulative(lam, (Dg[0] + 4.0 * qs[0] * lam[0]) / 8.0);
  std::vector<double> D(nf);
  for (std::size_t k = 0; k < nf; ++k) {
    const double work = 4.0 * qs[k] * lam[k];
    const double D2 = 8.0 * Il[k] - work;
    D[k] = D2 > 0.01 * work ? D2 : Dg[k];
  }
  // Viscous part at the current frequency: phi^T C phi dissipates pi omega a^2 c_m per
  // cycle, so zeta_c = c_m / (2 omega).
  const double c_modal = sm.phi.dot(hb.structure().C * sm.phi);
  const auto np = static_cast<Eigen::Index>(opt.points);
  out.amplitude.resize(np);
  out.omega.resize(np);
  out.frequency_hz.resize(np);
  out.damping_ratio.resize(np);
  out.modal_force.resize(np);
  out.dissipation.resize(np);
  for (Eigen::Index k = 0; k < np; ++k) {
    const std::size_t j = static_cast<std::size_t>(k) * refine;
    const double w2 = lam[j] / qs[j];
    out.amplitude(k) = qs[j];
    out.modal_force(k) = lam[j];
    out.omega(k) = std::sqrt(std::max(w2, 0.0));
    out.frequency_hz(k) = out.omega(k) / (2.0 * std::numbers::pi);
    out.dissipation(k) = std::max(0.0, D[j]);
    out.damping_ratio(k) =
        w2 > 0.0 ? out.dissipation(k) / (2.0 * std::numbers::pi * qs[j] * qs[j] * w2) +
                       c_modal / (2.0 * out.omega(k))
                 : 0.0;
  }
  if (hb.elements().empty()) out.warnings.push_back("quasi-static mode: no joint elements");
  for (const PlacedElement& pe : hb.elements()) {
    if (pe.element->velocity_dependent()) {
      out.warnings.push_back(fmt::format(
          "quasi-static mode: {} ({}) depends on velocity, so a static push sees no force from "
          "it: its damping is missing from this estimate (use the nonlinear mode)",
          pe.name, pe.element->type()));
    }
  }
  return out;
}

}  // namespace asperity::vibration
