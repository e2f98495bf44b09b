#include "asperity/vibration/force_response.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>
#include <Eigen/LU>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "common.hpp"

namespace asperity::vibration {

namespace {}  // namespace

void ForceResponseOptions::validate(Eigen::Index unknowns) const {
  const auto check = [&](const Eigen::VectorXd& v, const char* name, bool required) {
    if (!required && v.size() == 0) return;
    if (v.size() != unknowns) {
      throw InvalidInput(fmt::format("force_response: {} has {} coefficients, {} expected", name,
                                     v.size(), unknowns));
    }
    if (!v.allFinite()) {
      throw InvalidInput(fmt::format("force_response: {} holds a NaN or infinity", name));
    }
  };
  check(force, "the force", true);
  check(force_per_omega, "force_per_omega", false);
  check(force_per_omega2, "force_per_omega2", false);
  core::require_positive("force_response.omega", omega);
  core::require_non_negative("force_response.force_scale.from", scale_from);
  core::require_non_negative("force_response.force_scale.to", scale_to);
  if (scale_from == scale_to) {
    throw InvalidInput("force_response.force_scale: from and to are equal");
  }
  Eigen::VectorXd F = force;
  if (force_per_omega.size()) F += omega * force_per_omega;
  if (force_per_omega2.size()) F += omega * omega * force_per_omega2;
  if (F.cwiseAbs().maxCoeff() == 0.0) {
    throw InvalidInput(fmt::format(
        "force_response: the force at omega = {} rad/s is zero: give force_cos or force_sin",
        omega));
  }
  continuation.validate();
}

ForceResponseCurve force_response(const HarmonicBalance& hb, const ForceResponseOptions& opt,
                                  const std::vector<Eigen::Index>& outputs,
                                  const ProgressFunction& progress) {
  opt.validate(hb.unknowns());
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    if (outputs[k] < 0 || outputs[k] >= hb.dofs()) {
      throw InvalidInput(fmt::format("output_dofs[{}] = {}: DOFs are numbered 0 .. {}", k + 1,
                                     outputs[k], hb.dofs() - 1));
    }
  }
  const Eigen::Index nu = hb.unknowns();
  const double w = opt.omega;
  Eigen::VectorXd F = opt.force;
  if (opt.force_per_omega.size()) F += w * opt.force_per_omega;
  if (opt.force_per_omega2.size()) F += w * w * opt.force_per_omega2;
  const auto& harmonics = hb.basis().harmonics();

  // The stuck linear response: the start, and the scale of the unknowns.
  Structure stuck = hb.structure();
  stuck.K = hb.stuck_stiffness();
  const HarmonicBalance lin(stuck, {}, HarmonicBalanceOptions{harmonics, hb.basis().time_points()});
  const Eigen::VectorXd U1 = lin.dynamic_stiffness(w, stuck.C).partialPivLu().solve(F);
  const bool finite = U1.allFinite();
  double u_scale = finite ? std::max(opt.scale_from, opt.scale_to) * U1.cwiseAbs().maxCoeff() : 0.0;
  if (!(u_scale > 0.0) || !std::isfinite(u_scale)) u_scale = 1.0;
  Eigen::VectorXd y0(nu + 1);
  y0.head(nu) = finite ? Eigen::VectorXd(opt.scale_from * U1) : Eigen::VectorXd::Zero(nu);
  y0(nu) = opt.scale_from;

  ContinuationProblem pb;
  pb.f = [&](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    Eigen::MatrixXd dR;
    hb.residual(y.head(nu), w, y(nu) * F, R, J ? &dR : nullptr, nullptr);
    if (J) {
      J->resize(nu, nu + 1);
      J->leftCols(nu) = dR;
      J->col(nu) = -F;
    }
  };
  pb.parameter = nu;
  pb.scale = Eigen::VectorXd::Constant(nu + 1, u_scale);
  const double range = std::abs(opt.scale_to - opt.scale_from);
  pb.scale(nu) = range;
  pb.residual_scale = std::max(opt.scale_from, opt.scale_to) * F.cwiseAbs().maxCoeff();
  pb.parameter_end = opt.scale_to;

  ForceResponseCurve c;
  c.omega = w;
  c.continuation = continue_curve(pb, y0, opt.continuation, progress);
  const auto& pts = c.continuation.points;
  const auto np = static_cast<Eigen::Index>(pts.size());
  const auto no = static_cast<Eigen::Index>(outputs.size());
  c.force_scale.resize(np);
  c.output_amplitude.resize(np, no);
  c.max_displacement.resize(np, no);
  c.harmonic_amplitude.assign(outputs.size(),
                              Eigen::MatrixXd(np, static_cast<Eigen::Index>(harmonics.size())));
  for (Eigen::Index k = 0; k < np; ++k) {
    const Eigen::VectorXd U = pts[static_cast<std::size_t>(k)].head(nu);
    c.force_scale(k) = pts[static_cast<std::size_t>(k)](nu);
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
  }
  // Folds: prominent local extrema of lambda along the curve, refined between the points.
  std::vector<std::pair<std::size_t, double>> fold_at;  // point, +1 max / -1 min of lambda
  for (const double sense : {1.0, -1.0}) {
    std::vector<double> s(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) s[k] = sense * pts[k](nu);
    for (const std::size_t k :
         prominent_maxima(s, [&](double) { return detail::kFoldProminence * range; })) {
      fold_at.emplace_back(k, sense);
    }
  }
  std::sort(fold_at.begin(), fold_at.end());
  for (const auto& [k, sense] : fold_at) {
    const double sg = sense;
    const Eigen::VectorXd y =
        refine_curve_maximum(pb, pts, k, opt.continuation.newton,
                             [&](const Eigen::VectorXd& yy) { return sg * yy(nu); });
    ForceResponseFold f;
    f.force_scale = y(nu);
    f.output_amplitude.resize(no);
    for (Eigen::Index o = 0; o < no; ++o) {
      f.output_amplitude(o) =
          hb.harmonic_amplitude(y.head(nu), outputs[static_cast<std::size_t>(o)], 1);
    }
    f.harmonics = y.head(nu);
    c.folds.push_back(std::move(f));
  }
  if (!c.continuation.complete) {
    c.warnings.push_back(fmt::format("force response at omega {} rad/s: {}", core::format_value(w),
                                     c.continuation.stop_reason));
  }
  return c;
}

}  // namespace asperity::vibration
