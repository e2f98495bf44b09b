#include "asperity/vibration/response_control.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/LU>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/vibration/structure.hpp"
#include "common.hpp"

namespace asperity::vibration {

namespace {

void require_force(const HarmonicBalance& hb, const Eigen::VectorXd& force, const char* what) {
  if (force.size() != hb.unknowns()) {
    throw InvalidInput(fmt::format("{}: the force has {} coefficients, {} expected", what,
                                   force.size(), hb.unknowns()));
  }
  if (!force.allFinite())
    throw InvalidInput(fmt::format("{}: the force holds a NaN or infinity", what));
  if (force.cwiseAbs().maxCoeff() == 0.0) {
    throw InvalidInput(fmt::format("{}: the force is zero: give force_cos or force_sin", what));
  }
}

void require_dof(const HarmonicBalance& hb, Eigen::Index dof, const char* what) {
  if (dof < 0 || dof >= hb.dofs()) {
    throw InvalidInput(
        fmt::format("{}.dof = {}: DOFs are numbered 0 .. {}", what, dof, hb.dofs() - 1));
  }
}

// The structure with its joints stuck, without elements: the linear response that starts
// a continuation.
HarmonicBalance stuck_linear(const HarmonicBalance& hb) {
  Structure stuck = hb.structure();
  stuck.K = hb.stuck_stiffness();
  return HarmonicBalance(stuck, {},
                         HarmonicBalanceOptions{hb.basis().harmonics(), hb.basis().time_points()});
}

// The stuck structure's angular frequency of mode `mode` (1-based), refused when the mode
// does not exist or is a rigid-body one.
double stuck_mode_frequency(const HarmonicBalance& hb, int mode, const char* what) {
  const LinearModes lm = linear_modes(hb.stuck_stiffness(), hb.structure().M);
  if (mode < 1 || mode > lm.omega.size()) {
    throw InvalidInput(
        fmt::format("{}.mode = {}: the structure has modes 1 .. {}", what, mode, lm.omega.size()));
  }
  const double w = lm.omega(mode - 1);
  if (!(w > 0.0)) {
    throw InvalidInput(fmt::format(
        "{}.mode = {}: a rigid-body mode of the stuck structure (zero frequency)", what, mode));
  }
  return w;
}

// Indices in U of the cosine and sine coefficients of harmonic 1 of `dof`.
std::pair<Eigen::Index, Eigen::Index> first_harmonic(const HarmonicBalance& hb, Eigen::Index dof) {
  return {hb.index(dof, static_cast<std::size_t>(hb.basis().index_of(1, 0))),
          hb.index(dof, static_cast<std::size_t>(hb.basis().index_of(1, 1)))};
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Amplitude control

void AmplitudeControlOptions::validate(const HarmonicBalance& hb) const {
  require_force(hb, force, "amplitude_control");
  require_dof(hb, dof, "amplitude_control");
  core::require_positive("amplitude_control.amplitude", amplitude);
  core::require_positive("amplitude_control.omega.from", omega_from);
  core::require_positive("amplitude_control.omega.to", omega_to);
  if (omega_from == omega_to) throw InvalidInput("amplitude_control.omega: from and to are equal");
  continuation.validate();
}

AmplitudeControlResult amplitude_controlled_response(const HarmonicBalance& hb,
                                                     const AmplitudeControlOptions& opt,
                                                     const std::vector<Eigen::Index>& outputs,
                                                     const ProgressFunction& progress) {
  opt.validate(hb);
  detail::require_outputs(hb, outputs);
  const Eigen::Index nu = hb.unknowns();
  const auto [ic, is] = first_harmonic(hb, opt.dof);
  const double A = opt.amplitude;
  const HarmonicBalance lin = stuck_linear(hb);
  const Eigen::MatrixXd C =
      hb.structure().C.size() ? hb.structure().C : Eigen::MatrixXd::Zero(hb.dofs(), hb.dofs());
  // The linear force scale A / |X_d(omega)| over the range: the start and the scales.
  const auto linear = [&](double w) -> Eigen::VectorXd {
    return lin.dynamic_stiffness(w, C).partialPivLu().solve(opt.force);
  };
  double lambda_scale = 0.0;
  for (int k = 0; k <= 64; ++k) {
    const double w = opt.omega_from + (opt.omega_to - opt.omega_from) * k / 64.0;
    const Eigen::VectorXd U = linear(w);
    const double r = std::hypot(U(ic), U(is));
    if (U.allFinite() && r > 0.0) lambda_scale = std::max(lambda_scale, A / r);
  }
  const Eigen::VectorXd U1 = linear(opt.omega_from);
  const double r1 = std::hypot(U1(ic), U1(is));
  if (!U1.allFinite() || !(r1 > 0.0)) {
    throw InvalidInput(fmt::format(
        "amplitude_control: the force does not move DOF {} at omega = {} rad/s (its linear "
        "first harmonic is zero): force that DOF's mode or choose another",
        opt.dof, opt.omega_from));
  }
  if (!(lambda_scale > 0.0) || !std::isfinite(lambda_scale)) lambda_scale = A / r1;
  const double lambda0 = A / r1;
  Eigen::VectorXd y0(nu + 2);
  y0.head(nu) = lambda0 * U1;
  y0(nu) = lambda0;
  y0(nu + 1) = opt.omega_from;

  // The amplitude constraint in force units: kappa (c^2 + s^2 - A^2) / (2 A).
  const double residual_scale = lambda_scale * opt.force.cwiseAbs().maxCoeff();
  const double kappa = residual_scale / A;
  ContinuationProblem pb;
  pb.f = [&](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    const double lambda = y(nu), w = y(nu + 1);
    Eigen::VectorXd Rh;
    Eigen::MatrixXd dR;
    Eigen::VectorXd dRw;
    hb.residual(y.head(nu), w, lambda * opt.force, Rh, J ? &dR : nullptr, J ? &dRw : nullptr);
    const double c = y(ic), s = y(is);
    R.resize(nu + 1);
    R.head(nu) = Rh;
    R(nu) = kappa * (c * c + s * s - A * A) / (2.0 * A);
    if (J) {
      J->setZero(nu + 1, nu + 2);
      J->topLeftCorner(nu, nu) = dR;
      J->block(0, nu, nu, 1) = -opt.force;
      J->block(0, nu + 1, nu, 1) = dRw;
      (*J)(nu, ic) = kappa * c / A;
      (*J)(nu, is) = kappa * s / A;
    }
  };
  pb.parameter = nu + 1;
  pb.scale = Eigen::VectorXd::Constant(nu + 2, std::max(A, y0.head(nu).cwiseAbs().maxCoeff()));
  pb.scale(nu) = lambda_scale;
  pb.scale(nu + 1) = std::abs(opt.omega_to - opt.omega_from);
  pb.residual_scale = residual_scale;
  pb.parameter_end = opt.omega_to;

  AmplitudeControlResult r;
  r.continuation = continue_curve(pb, y0, opt.continuation, progress);
  const auto np = static_cast<Eigen::Index>(r.continuation.points.size());
  const auto no = static_cast<Eigen::Index>(outputs.size());
  r.omega.resize(np);
  r.force_scale.resize(np);
  r.output_amplitude.resize(np, no);
  for (Eigen::Index k = 0; k < np; ++k) {
    const Eigen::VectorXd& y = r.continuation.points[static_cast<std::size_t>(k)];
    r.omega(k) = y(nu + 1);
    r.force_scale(k) = y(nu);
    for (Eigen::Index o = 0; o < no; ++o) {
      r.output_amplitude(k, o) =
          hb.harmonic_amplitude(y.head(nu), outputs[static_cast<std::size_t>(o)], 1);
    }
    r.harmonics.push_back(y.head(nu));
  }
  if (!r.continuation.complete) {
    r.warnings.push_back(fmt::format("amplitude-controlled response at {} m: {}",
                                     core::format_value(A), r.continuation.stop_reason));
  }
  return r;
}

// ---------------------------------------------------------------------------------------
// Phase resonance

void PhaseResonanceOptions::validate(const HarmonicBalance& hb) const {
  require_force(hb, force, "phase_resonance");
  require_dof(hb, dof, "phase_resonance");
  core::require_finite("phase_resonance.log10_amplitude.from", log10_amplitude_from);
  core::require_finite("phase_resonance.log10_amplitude.to", log10_amplitude_to);
  if (log10_amplitude_from == log10_amplitude_to) {
    throw InvalidInput("phase_resonance.log10_amplitude: from and to are equal");
  }
  const auto [ic, is] = first_harmonic(hb, dof);
  if (std::hypot(force(ic), force(is)) == 0.0) {
    throw InvalidInput(fmt::format(
        "phase_resonance: the force has no first harmonic at DOF {}, the phase reference of a "
        "90 degree lag: drive the controlled DOF (a driving point)",
        dof));
  }
  continuation.validate();
}

PhaseResonanceResult phase_resonance(const HarmonicBalance& hb, const PhaseResonanceOptions& opt,
                                     const std::vector<Eigen::Index>& outputs,
                                     const ProgressFunction& progress) {
  opt.validate(hb);
  detail::require_outputs(hb, outputs);
  const Eigen::Index nu = hb.unknowns();
  const auto [ic, is] = first_harmonic(hb, opt.dof);
  // Phase of the force at the DOF, and the in-phase and lagging directions in (cos, sin).
  const double fm = std::hypot(opt.force(ic), opt.force(is));
  const Eigen::Vector2d eF(opt.force(ic) / fm, opt.force(is) / fm);
  const Eigen::Vector2d eLag(-eF(1), eF(0));
  const double w0 = stuck_mode_frequency(hb, opt.mode, "phase_resonance");
  const HarmonicBalance lin = stuck_linear(hb);
  const Eigen::MatrixXd C =
      hb.structure().C.size() ? hb.structure().C : Eigen::MatrixXd::Zero(hb.dofs(), hb.dofs());
  const Eigen::VectorXd U1 = lin.dynamic_stiffness(w0, C).partialPivLu().solve(opt.force);
  const double q = U1(ic) * eLag(0) + U1(is) * eLag(1);
  if (!U1.allFinite() || q == 0.0) {
    throw InvalidInput(fmt::format(
        "phase_resonance: the stuck structure's linear response at DOF {} has no part lagging "
        "the force by 90 degrees at mode {} ({} rad/s): choose the mode or DOF",
        opt.dof, opt.mode, w0));
  }
  // Unknowns y = [Psi, omega, mu, log10 a] with U = a Psi and lambda = a mu.
  const Eigen::Index iw = nu, imu = nu + 1, ip = nu + 2;
  Eigen::VectorXd y0(nu + 3);
  y0.head(nu) = U1 / q;
  y0(iw) = w0;
  y0(imu) = 1.0 / q;
  y0(ip) = opt.log10_amplitude_from;
  // mu = lambda / a grows with the amplitude where the damping does (cubic damping,
  // friction): its scale is at least the force per unit amplitude that balances the
  // stiffness, max|K| / max|F|, so that the step control does not shrink with it.
  const double f_max = opt.force.cwiseAbs().maxCoeff();
  const double mu_scale =
      std::max(std::abs(y0(imu)), hb.stuck_stiffness().cwiseAbs().maxCoeff() / f_max);
  const double residual_scale = mu_scale * f_max;
  ContinuationProblem pb;
  pb.f = [&](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    const double w = y(iw), mu = y(imu), a = std::pow(10.0, y(ip));
    const Eigen::VectorXd Psi = y.head(nu);
    Eigen::VectorXd Rh;
    Eigen::MatrixXd dR;
    Eigen::VectorXd dRw;
    // G = R(a Psi, omega, a mu F) / a.
    hb.residual(a * Psi, w, a * mu * opt.force, Rh, J ? &dR : nullptr, J ? &dRw : nullptr);
    R.resize(nu + 2);
    R.head(nu) = Rh / a;
    R(nu) = residual_scale * (Psi(ic) * eF(0) + Psi(is) * eF(1));
    R(nu + 1) = residual_scale * (Psi(ic) * eLag(0) + Psi(is) * eLag(1) - 1.0);
    if (J) {
      J->setZero(nu + 2, nu + 3);
      J->topLeftCorner(nu, nu) = dR;
      J->block(0, iw, nu, 1) = dRw / a;
      J->block(0, imu, nu, 1) = -opt.force;
      J->block(0, ip, nu, 1) = std::numbers::ln10 * (dR * Psi - mu * opt.force - R.head(nu));
      (*J)(nu, ic) = residual_scale * eF(0);
      (*J)(nu, is) = residual_scale * eF(1);
      (*J)(nu + 1, ic) = residual_scale * eLag(0);
      (*J)(nu + 1, is) = residual_scale * eLag(1);
    }
  };
  pb.parameter = ip;
  pb.scale = Eigen::VectorXd::Constant(nu + 3, std::max(1.0, y0.head(nu).cwiseAbs().maxCoeff()));
  pb.scale(iw) = w0;
  pb.scale(imu) = mu_scale;
  pb.scale(ip) = 1.0;
  pb.residual_scale = residual_scale;
  pb.parameter_end = opt.log10_amplitude_to;

  PhaseResonanceResult r;
  r.continuation = continue_curve(pb, y0, opt.continuation, progress);
  const auto np = static_cast<Eigen::Index>(r.continuation.points.size());
  const auto no = static_cast<Eigen::Index>(outputs.size());
  r.amplitude.resize(np);
  r.omega.resize(np);
  r.force_scale.resize(np);
  r.output_amplitude.resize(np, no);
  for (Eigen::Index k = 0; k < np; ++k) {
    const Eigen::VectorXd& y = r.continuation.points[static_cast<std::size_t>(k)];
    const double a = std::pow(10.0, y(ip));
    const Eigen::VectorXd U = a * y.head(nu);
    r.amplitude(k) = a;
    r.omega(k) = y(iw);
    r.force_scale(k) = a * y(imu);
    for (Eigen::Index o = 0; o < no; ++o) {
      r.output_amplitude(k, o) = hb.harmonic_amplitude(U, outputs[static_cast<std::size_t>(o)], 1);
    }
    r.harmonics.push_back(U);
  }
  if (!r.continuation.complete) {
    r.warnings.push_back(
        fmt::format("phase resonance of DOF {}: {}", opt.dof, r.continuation.stop_reason));
  }
  return r;
}

// ---------------------------------------------------------------------------------------
// Superharmonic resonance (VPRNM)

void SuperharmonicResonanceOptions::validate(const HarmonicBalance& hb) const {
  require_force(hb, force, "superharmonic_resonance");
  const HarmonicBasis& b = hb.basis();
  if (harmonic < 2 || b.index_of(harmonic, 0) < 0) {
    throw InvalidInput(fmt::format(
        "superharmonic_resonance.harmonic = {}: a harmonic >= 2 kept in harmonic_balance is "
        "needed (kept: up to {})",
        harmonic, b.max_harmonic()));
  }
  if (b.index_of(1, 0) < 0) {
    throw InvalidInput(
        "superharmonic_resonance: harmonic 1 is not kept; the excitation and the lower harmonics "
        "that drive harmonic r need it");
  }
  core::require_finite("superharmonic_resonance.log10_force.from", log10_force_from);
  core::require_finite("superharmonic_resonance.log10_force.to", log10_force_to);
  if (log10_force_from == log10_force_to) {
    throw InvalidInput("superharmonic_resonance.log10_force: from and to are equal");
  }
  continuation.validate();
}

namespace {

// The coefficients of harmonic r (X_r) and of the harmonics below it (U_low), all DOFs.
struct HarmonicSplit {
  std::vector<Eigen::Index> low, high;
  Eigen::Index unknowns = 0;
  HarmonicSplit(const HarmonicBalance& hb, int r) : unknowns(hb.unknowns()) {
    const HarmonicBasis& b = hb.basis();
    for (Eigen::Index d = 0; d < hb.dofs(); ++d) {
      for (std::size_t c = 0; c < b.coefficients(); ++c) {
        if (b.harmonic_of(c) < r) low.push_back(hb.index(d, c));
        if (b.harmonic_of(c) == r) high.push_back(hb.index(d, c));
      }
    }
  }
  [[nodiscard]] Eigen::VectorXd take(const Eigen::VectorXd& v) const {
    Eigen::VectorXd x(static_cast<Eigen::Index>(high.size()));
    for (std::size_t i = 0; i < high.size(); ++i) x(static_cast<Eigen::Index>(i)) = v(high[i]);
    return x;
  }
  [[nodiscard]] Eigen::VectorXd lower(const Eigen::VectorXd& U) const {
    Eigen::VectorXd L = Eigen::VectorXd::Zero(unknowns);
    for (const Eigen::Index i : low) L(i) = U(i);
    return L;
  }
};

}  // namespace

void superharmonic_resonance_system(const HarmonicBalance& hb,
                                    const SuperharmonicResonanceOptions& opt,
                                    const Eigen::VectorXd& y, Eigen::VectorXd& R,
                                    Eigen::MatrixXd* J) {
  const Eigen::Index nu = hb.unknowns(), iw = nu, ip = nu + 1;
  const int r = opt.harmonic;
  const HarmonicSplit split(hb, r);
  const auto& low = split.low;
  const auto& high = split.high;
  const auto n_r = static_cast<Eigen::Index>(high.size());
  const double residual_scale = opt.force.cwiseAbs().maxCoeff();
  const double w = y(iw), lambda = std::pow(10.0, y(ip));
  const Eigen::VectorXd Psi = y.head(nu);
  Eigen::VectorXd Rh, dRw, Gl, dGw;
  Eigen::MatrixXd dR, dG;
  hb.residual(lambda * Psi, w, lambda * opt.force, Rh, J ? &dR : nullptr, J ? &dRw : nullptr);
  const Eigen::VectorXd Ul = split.lower(lambda * Psi);
  hb.nonlinear_force(Ul, w, Gl, J ? &dG : nullptr, J ? &dGw : nullptr);
  const Eigen::VectorXd F = -split.take(Gl), X = split.take(Psi);
  const double nF = F.norm(), nX = X.norm();
  if (!(nF > 0.0) || !(nX > 0.0)) {
    throw NumericalError(fmt::format(
        "superharmonic_resonance: harmonic {} of the {} vanished (omega = {} rad/s)", r,
        nF > 0.0 ? "response" : "elements' force from the lower harmonics", core::format_value(w)));
  }
  const double c = F.dot(X) / (nF * nX);
  R.resize(nu + 1);
  R.head(nu) = Rh / lambda;
  R(nu) = residual_scale * c;  // Eq. VPRNM: harmonic r in quadrature with its drive
  if (!J) return;
  J->setZero(nu + 1, nu + 2);
  J->topLeftCorner(nu, nu) = dR;
  J->block(0, iw, nu, 1) = dRw / lambda;
  J->block(0, ip, nu, 1) = std::numbers::ln10 * (dR * Psi - opt.force - R.head(nu));
  const Eigen::VectorXd dc_dF = X / (nF * nX) - c * F / (nF * nF);
  const Eigen::VectorXd dc_dX = F / (nF * nX) - c * X / (nX * nX);
  // F = -S_r G(U_low): dF/dPsi_low = -S_r dG lambda, dF/domega = -S_r dG_w,
  // dF/dlog10 lambda = -S_r dG U_low ln 10.
  Eigen::VectorXd row = Eigen::VectorXd::Zero(nu);
  for (Eigen::Index i = 0; i < n_r; ++i) {
    const Eigen::Index gi = high[static_cast<std::size_t>(i)];
    for (const Eigen::Index j : low) row(j) -= dc_dF(i) * dG(gi, j) * lambda;
    row(gi) += dc_dX(i);
    (*J)(nu, iw) -= residual_scale * dc_dF(i) * dGw(gi);
    (*J)(nu, ip) -= residual_scale * dc_dF(i) * std::numbers::ln10 * dG.row(gi).dot(Ul);
  }
  J->block(nu, 0, 1, nu) = residual_scale * row.transpose();
}

SuperharmonicResonanceResult superharmonic_resonance(const HarmonicBalance& hb,
                                                     const SuperharmonicResonanceOptions& opt,
                                                     const std::vector<Eigen::Index>& outputs,
                                                     const ProgressFunction& progress) {
  opt.validate(hb);
  detail::require_outputs(hb, outputs);
  const Eigen::Index nu = hb.unknowns(), n = hb.dofs();
  const int r = opt.harmonic;
  const HarmonicSplit split(hb, r);

  const double w_mode = stuck_mode_frequency(hb, opt.mode, "superharmonic_resonance");
  // Start: the stuck linear response at omega_mode / r, plus its harmonic r driven by F_r.
  const double w0 = w_mode / r, lambda0 = std::pow(10.0, opt.log10_force_from);
  const HarmonicBalance lin = stuck_linear(hb);
  const Eigen::MatrixXd C =
      hb.structure().C.size() ? hb.structure().C : Eigen::MatrixXd::Zero(n, n);
  const Eigen::PartialPivLU<Eigen::MatrixXd> A0(lin.dynamic_stiffness(w0, C));
  Eigen::VectorXd U0 = A0.solve(lambda0 * opt.force);
  Eigen::VectorXd G;
  hb.nonlinear_force(split.lower(U0), w0, G, nullptr, nullptr);
  Eigen::VectorXd drive = Eigen::VectorXd::Zero(nu);
  for (const Eigen::Index i : split.high) drive(i) = -G(i);
  // Round-off of the AFT leaves ~1e-16 of the force in harmonics it cannot hold.
  if (!(split.take(drive).norm() > 1e-10 * G.norm()) || !drive.allFinite()) {
    throw InvalidInput(fmt::format(
        "superharmonic_resonance: the elements' force has no harmonic {} from the lower "
        "harmonics at the start (omega = {} rad/s, force scale {}): nothing drives this "
        "superharmonic (a symmetric law has no even ones; a linear structure none)",
        r, core::format_value(w0), core::format_value(lambda0)));
  }
  const Eigen::VectorXd Ur = A0.solve(drive);
  for (const Eigen::Index i : split.high) U0(i) = Ur(i);

  const Eigen::Index iw = nu, ip = nu + 1;
  const double residual_scale = opt.force.cwiseAbs().maxCoeff();
  Eigen::VectorXd y0(nu + 2);
  y0.head(nu) = U0 / lambda0;
  y0(iw) = w0;
  y0(ip) = opt.log10_force_from;

  ContinuationProblem pb;
  pb.f = [&](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    superharmonic_resonance_system(hb, opt, y, R, J);
  };
  pb.parameter = ip;
  pb.scale = Eigen::VectorXd::Constant(nu + 2, std::max(1e-300, y0.head(nu).cwiseAbs().maxCoeff()));
  pb.scale(iw) = w0;
  pb.scale(ip) = 1.0;
  pb.residual_scale = residual_scale;
  pb.parameter_end = opt.log10_force_to;

  SuperharmonicResonanceResult res;
  res.harmonic = r;
  res.continuation = continue_curve(pb, y0, opt.continuation, progress);
  const auto np = static_cast<Eigen::Index>(res.continuation.points.size());
  const auto no = static_cast<Eigen::Index>(outputs.size());
  res.force_scale.resize(np);
  res.omega.resize(np);
  res.output_amplitude.resize(np, no);
  res.output_harmonic_amplitude.resize(np, no);
  for (Eigen::Index k = 0; k < np; ++k) {
    const Eigen::VectorXd& y = res.continuation.points[static_cast<std::size_t>(k)];
    const double lambda = std::pow(10.0, y(ip));
    const Eigen::VectorXd U = lambda * y.head(nu);
    res.force_scale(k) = lambda;
    res.omega(k) = y(iw);
    for (Eigen::Index o = 0; o < no; ++o) {
      const Eigen::Index d = outputs[static_cast<std::size_t>(o)];
      res.output_amplitude(k, o) = hb.harmonic_amplitude(U, d, 1);
      res.output_harmonic_amplitude(k, o) = hb.harmonic_amplitude(U, d, r);
    }
    res.harmonics.push_back(U);
  }
  if (!res.continuation.complete) {
    res.warnings.push_back(
        fmt::format("superharmonic resonance {}:1: {}", r, res.continuation.stop_reason));
  }
  return res;
}

}  // namespace asperity::vibration
