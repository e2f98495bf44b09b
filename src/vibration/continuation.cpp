#include "asperity/vibration/continuation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <Eigen/LU>
#include <boost/math/tools/minima.hpp>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::vibration {

void NewtonOptions::validate() const {
  if (max_iterations < 1 || max_iterations > 1000) {
    throw InvalidInput(
        fmt::format("newton.max_iterations = {}: must be in [1, 1000]", max_iterations));
  }
  core::require_in_half_open("newton.step_tolerance", step_tolerance, 1e-15, 1.0);
  core::require_in_half_open("newton.residual_tolerance", residual_tolerance, 1e-15, 1.0);
}

void ContinuationOptions::validate() const {
  core::require_positive("continuation.step", step);
  core::require_positive("continuation.min_step", min_step);
  core::require_positive("continuation.max_step", max_step);
  if (!(min_step <= step && step <= max_step)) {
    throw InvalidInput(fmt::format(
        "continuation steps: need min_step <= step <= max_step, got {} <= {} <= {}",
        core::format_value(min_step), core::format_value(step), core::format_value(max_step)));
  }
  if (max_points < 2 || max_points > 1000000) {
    throw InvalidInput(
        fmt::format("continuation.max_points = {}: must be in [2, 1e6]", max_points));
  }
  if (chord_unknowns < 1) {
    throw InvalidInput(
        "continuation.chord_unknowns = 0: must be >= 1 (a large number for "
        "full Newton always)");
  }
  if (target_iterations < 1 || target_iterations > newton.max_iterations) {
    throw InvalidInput(fmt::format(
        "continuation.target_iterations = {}: must be in [1, newton.max_iterations = {}]",
        target_iterations, newton.max_iterations));
  }
  core::require_in_half_open("continuation.max_angle", max_angle, 1e-3, 1.5);
  newton.validate();
}

namespace {

// Smallest turn of the tangent [rad] across a piece boundary taken for a kink of the curve.
constexpr double kKinkAngle = 1e-3;

// Points of the curve behind the current one against which a kink step is checked for
// having gone back along the curve.
constexpr std::size_t kRecentPoints = 64;
// A kink is looked for once the step has fallen below this fraction of the initial step,
// so that the probe across the boundary meets the next piece only.
constexpr double kKinkStep = 1e-3;
// Largest angle [rad] between a new tangent and the reverse of an old chord, beyond the
// turn of the tangent over that chord, for the new point to be going back along it.
constexpr double kRetraceAngle = 0.02;

double scaled_max(const Eigen::VectorXd& dy, const Eigen::VectorXd& scale) {
  return (dy.array() / scale.array()).abs().maxCoeff();
}

// g(y) where a NumericalError (an element pushed outside what it represents, at a trial
// point of Newton's) is a failed evaluation: R is set non-finite and the message kept, so
// that the step is shortened rather than the analysis ended.
void evaluate(const SystemFunction& g, const Eigen::VectorXd& y, Eigen::VectorXd& R,
              Eigen::MatrixXd* J, std::string& failure) {
  try {
    g(y, R, J);
  } catch (const NumericalError& e) {
    failure = e.what();
    R = Eigen::VectorXd::Constant(std::max<Eigen::Index>(1, y.size()),
                                  std::numeric_limits<double>::quiet_NaN());
    if (J) J->resize(0, 0);
  }
}

// The result at the last iterate: y and max |R| (infinite when R is not finite).
NewtonResult finished(NewtonResult res, const Eigen::VectorXd& y, const Eigen::VectorXd& R) {
  res.y = y;
  res.residual_norm =
      R.allFinite() ? R.cwiseAbs().maxCoeff() : std::numeric_limits<double>::infinity();
  return res;
}

// Newton with backtracking on |R|^2 for a square system g(y) = 0.
NewtonResult newton_square(const SystemFunction& g, Eigen::VectorXd y, const Eigen::VectorXd& scale,
                           double residual_scale, const NewtonOptions& opt) {
  NewtonResult res;
  Eigen::VectorXd R;
  Eigen::MatrixXd J;
  evaluate(g, y, R, &J, res.failure);
  if (!R.allFinite()) {
    res.y = y;
    res.residual_norm = std::numeric_limits<double>::infinity();
    return res;
  }
  double r0 = R.squaredNorm();
  for (int it = 1; it <= opt.max_iterations; ++it) {
    res.iterations = it;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(J);
    ++res.factorizations;
    Eigen::VectorXd dy = lu.solve(-R);
    if (!dy.allFinite()) break;
    // Line search: halve the step while |R|^2 does not decrease (Armijo, c = 1e-4).
    double t = 1.0;
    Eigen::VectorXd y_new, R_new;
    Eigen::MatrixXd J_new;
    bool accepted = false;
    // The full step with its Jacobian (the usual case); shorter ones residual only, the
    // Jacobian once one is accepted.
    Eigen::VectorXd R_full;
    Eigen::MatrixXd J_full;
    for (int ls = 0; ls < 7; ++ls) {
      y_new = y + t * dy;
      if (ls == 0) {
        evaluate(g, y_new, R_full, &J_full, res.failure);
        R_new = R_full;
      } else {
        evaluate(g, y_new, R_new, nullptr, res.failure);
      }
      if (R_new.allFinite() && R_new.squaredNorm() <= (1.0 - 2e-4 * t) * r0) {
        accepted = true;
        if (ls == 0) {
          J_new = std::move(J_full);
        } else {
          evaluate(g, y_new, R_new, &J_new, res.failure);
          if (!R_new.allFinite()) accepted = false;
        }
        break;
      }
      t *= 0.5;
    }
    if (!accepted) {
      // Take the full step anyway if it stays finite: piecewise-smooth residuals (stick-slip
      // kinks) can need a step that first increases |R|.
      if (!R_full.allFinite()) break;
      y_new = y + dy;
      R_new = std::move(R_full);
      J_new = std::move(J_full);
      t = 1.0;
    }
    const double step = t * scaled_max(dy, scale);
    y = y_new;
    R = R_new;
    J = J_new;
    r0 = R.squaredNorm();
    const double rn = R.cwiseAbs().maxCoeff();
    if (step < opt.step_tolerance && rn <= opt.residual_tolerance * residual_scale) {
      res.converged = true;
      break;
    }
    if (rn == 0.0) {
      res.converged = true;
      break;
    }
  }
  return finished(std::move(res), y, R);
}

// Reduction of max |R| from the guess that a failed chord corrector's Newton steps must have
// achieved for full Newton to go on from its last iterate (continue_curve's corrector).
constexpr double kFallbackProgress = 0.1;
// Reduction of |R| a chord step must achieve for the factorisation to be kept.
constexpr double kChordContraction = 0.5;
// Chord iterations stop when the estimated error is below this fraction of the step
// tolerance: full Newton's last step leaves an error quadratically smaller than the
// tolerance, and the curves should not depend on which corrector ran (a few more chord
// steps, each a residual evaluation, cost little where chord Newton is used).
constexpr double kChordStepTolerance = 1e-2;
// A scaled step this small is rounding (unknowns of the order of their scale).
constexpr double kRoundoffStep = 1e-13;

// Fresh Jacobians a chord corrector may factorise before it gives up.
int chord_max_factorizations(const NewtonOptions& opt) {
  return std::max(2, opt.max_iterations / 4);
}

// Solves J dy = rhs with a factorisation made earlier (chord iterations).
using ChordSolve = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

// Chord Newton (Newton's method with the Jacobian kept while it contracts; Kelley, "Solving
// Nonlinear Equations with Newton's Method", SIAM 2003, sec. 1.10 and 2.3): steps with the
// factorisation `solve` (given, or made at the start) while each reduces |R| by
// kChordContraction or reaches the residual tolerance; otherwise the Jacobian is evaluated
// and factorised at the current iterate and the step retried, with a backtracking line
// search as in newton_square when even that step does not contract. At most
// max(2, opt.max_iterations / 4) factorisations and 4 opt.max_iterations steps.
NewtonResult newton_chord(const SystemFunction& g, Eigen::VectorXd y, const Eigen::VectorXd& scale,
                          double residual_scale, const NewtonOptions& opt, ChordSolve solve) {
  NewtonResult res;
  Eigen::VectorXd R;
  Eigen::MatrixXd J;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  auto failed = [&]() { return finished(res, y, R); };
  // J (and R) at y, factorised.
  auto refactor = [&]() {
    evaluate(g, y, R, &J, res.failure);
    if (!R.allFinite() || J.size() == 0 || !J.allFinite()) return false;
    lu.compute(J);
    ++res.factorizations;
    solve = [&lu](const Eigen::VectorXd& b) { return Eigen::VectorXd(lu.solve(b)); };
    return true;
  };
  bool fresh = false;  // the factorisation is of J at the current iterate
  if (solve) {
    evaluate(g, y, R, nullptr, res.failure);
    if (!R.allFinite()) return failed();
  } else {
    if (!refactor()) return failed();
    fresh = true;
  }
  const double tol = opt.residual_tolerance * residual_scale;
  // A corrector that needs many fresh Jacobians is not a chord iteration any more: it
  // gives up early (continue_curve decides whether full Newton goes on).
  const int max_factorizations = chord_max_factorizations(opt);
  double previous_step = 0.0;  // of the last chord step (0: none since the last Newton step)
  for (int it = 1; it <= 4 * opt.max_iterations; ++it) {
    res.iterations = it;
    const bool newton_step = fresh;
    const Eigen::VectorXd dy = solve(-R);
    Eigen::VectorXd y_new = y + dy, R_new;
    if (dy.allFinite()) evaluate(g, y_new, R_new, nullptr, res.failure);
    const bool contracts =
        dy.allFinite() && R_new.allFinite() &&
        (R_new.norm() <= kChordContraction * R.norm() || R_new.cwiseAbs().maxCoeff() <= tol);
    double t = 1.0;
    if (!contracts) {
      if (!fresh) {
        if (res.factorizations >= max_factorizations || !refactor()) break;
        fresh = true;
        continue;
      }
      if (!dy.allFinite()) break;
      // A fresh Jacobian's step that does not contract: line search on |R|^2 (Armijo),
      // else the full step if it stays finite (stick-slip kinks can need a step that first
      // increases |R|), as newton_square.
      const double r0 = R.squaredNorm();
      if (!(R_new.allFinite() && R_new.squaredNorm() <= (1.0 - 2e-4) * r0)) {
        const Eigen::VectorXd y_full = y_new, R_full = R_new;
        bool accepted = false;
        for (int ls = 1; ls < 7 && !accepted; ++ls) {
          t *= 0.5;
          y_new = y + t * dy;
          evaluate(g, y_new, R_new, nullptr, res.failure);
          accepted = R_new.allFinite() && R_new.squaredNorm() <= (1.0 - 2e-4 * t) * r0;
        }
        if (!accepted) {
          if (!R_full.allFinite()) break;
          y_new = y_full;
          R_new = R_full;
          t = 1.0;
        }
      }
    }
    const double step = t * scaled_max(dy, scale);
    y = y_new;
    R = R_new;
    fresh = false;
    // The error left after a step: a Newton step's next is quadratically smaller (the step
    // itself bounds it, as in newton_square); chord steps converge linearly at the ratio
    // rho of successive steps, leaving about rho / (1 - rho) of the last step (Kelley 2003,
    // sec. 1.10), unknown after the first one.
    double error = step;
    if (!newton_step) {
      const double rho = previous_step > 0.0 ? step / previous_step : 1.0;
      // Steps below kRoundoffStep (scaled) are rounding noise, which does not contract.
      error = rho < 1.0              ? step * std::max(1.0, rho / (1.0 - rho))
              : step < kRoundoffStep ? step
                                     : std::numeric_limits<double>::infinity();
      previous_step = step;
    } else {
      previous_step = 0.0;
    }
    const double rn = R.cwiseAbs().maxCoeff();
    if ((error < kChordStepTolerance * opt.step_tolerance && rn <= tol) || rn == 0.0) {
      res.converged = true;
      break;
    }
  }
  return finished(std::move(res), y, R);
}

}  // namespace

NewtonResult solve_newton(const SystemFunction& f, Eigen::VectorXd y0, const Eigen::VectorXd& scale,
                          double residual_scale, const NewtonOptions& options) {
  options.validate();
  if (scale.size() != y0.size() || !(scale.array() > 0.0).all()) {
    throw InvalidInput("newton: scale must be positive, one entry per unknown");
  }
  return newton_square(f, std::move(y0), scale, residual_scale, options);
}

namespace {

// Unit tangent of R(y) = 0 in scaled unknowns z = y / scale: [J S; t_ref^T] t = [0; 1].
// With `orientation`, the sign of det [J S; t^T] (S = diag(scale)) for the returned t:
// the orientation of the curve, which a continuation keeps across turning points
// (Allgower & Georg 2003, sec. 2.1). det [J S; v^T] is linear in v and vanishes on the
// rows of J S, so it is det [J S; t_ref^T] times t.v / t.t_ref, and t.t_ref > 0.
// With `factorisation`, the LU of [J S; t_ref^T] is kept there (chord Newton's next
// corrector).
Eigen::VectorXd tangent_of(
    const Eigen::MatrixXd& J, const Eigen::VectorXd& scale, const Eigen::VectorXd& t_ref,
    double* orientation = nullptr,
    std::shared_ptr<const Eigen::PartialPivLU<Eigen::MatrixXd>>* factorisation = nullptr) {
  const Eigen::Index m = J.rows(), n = J.cols();
  Eigen::MatrixXd A(n, n);
  A.topRows(m) = J * scale.asDiagonal();
  A.row(m) = t_ref.transpose();
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  b(m) = 1.0;
  const auto lu_ptr = std::make_shared<const Eigen::PartialPivLU<Eigen::MatrixXd>>(A);
  const Eigen::PartialPivLU<Eigen::MatrixXd>& lu = *lu_ptr;
  if (factorisation) *factorisation = lu_ptr;
  Eigen::VectorXd t = lu.solve(b);
  if (!t.allFinite() || t.norm() == 0.0) return {};
  if (orientation) {
    double sign = static_cast<double>(lu.permutationP().determinant());
    for (Eigen::Index i = 0; i < n; ++i) {
      if (lu.matrixLU()(i, i) < 0.0) sign = -sign;
    }
    *orientation = sign;
  }
  return t / t.norm();
}

}  // namespace

ContinuationResult continue_curve(const ContinuationProblem& pb, const Eigen::VectorXd& y0,
                                  const ContinuationOptions& opt,
                                  const ProgressFunction& progress) {
  opt.validate();
  const Eigen::Index n = y0.size();
  const Eigen::Index p = pb.parameter;
  if (pb.scale.size() != n || !(pb.scale.array() > 0.0).all() || !pb.scale.allFinite()) {
    throw InvalidInput("continuation: scale must be positive and finite, one entry per unknown");
  }
  if (p < 0 || p >= n) throw InvalidInput("continuation: parameter index out of range");
  const double lambda0 = y0(p);
  const double lambda_end = pb.parameter_end;
  const double range = lambda_end - lambda0;
  if (!(std::abs(range) > 0.0)) {
    throw InvalidInput("continuation: the parameter's start and end are equal");
  }
  const double sense = range > 0.0 ? 1.0 : -1.0;
  ContinuationResult out;
  std::string last_failure;  // the last element error at a trial point

  // Correct the start at fixed parameter.
  auto fixed_parameter = [&](double lambda) {
    return [&, lambda](const Eigen::VectorXd& x, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
      Eigen::VectorXd y(n);
      y << x.head(p), lambda, x.tail(n - p - 1);
      Eigen::VectorXd r;
      Eigen::MatrixXd Jy;
      pb.f(y, r, J ? &Jy : nullptr);
      R = r;
      if (J) {
        J->resize(n - 1, n - 1);
        J->leftCols(p) = Jy.leftCols(p);
        J->rightCols(n - p - 1) = Jy.rightCols(n - p - 1);
      }
    };
  };
  auto without = [&](const Eigen::VectorXd& v) {
    Eigen::VectorXd x(n - 1);
    x << v.head(p), v.tail(n - p - 1);
    return x;
  };
  auto with = [&](const Eigen::VectorXd& x, double lambda) {
    Eigen::VectorXd y(n);
    y << x.head(p), lambda, x.tail(n - p - 1);
    return y;
  };
  const bool chord = static_cast<std::size_t>(n) >= opt.chord_unknowns;
  auto correct = [&](const SystemFunction& g, const Eigen::VectorXd& guess,
                     const Eigen::VectorXd& scale, const ChordSolve& initial = {}) {
    NewtonResult r = chord ? newton_chord(g, guess, scale, pb.residual_scale, opt.newton, initial)
                           : newton_square(g, guess, scale, pb.residual_scale, opt.newton);
    if (chord && !r.converged) {
      // Where chord iterations fail (a kink between the last point and the predictor, a
      // strongly curved branch), full Newton may still converge. Chord Newton's steps on
      // fresh Jacobians from the guess are full Newton's own iterates (the same line search),
      // so full Newton goes on from the chord's last iterate, for as many more Jacobians as
      // the chord corrector had (a Newton iteration that has converged that far finishes in a
      // few; on the BRB's mode 2 none of 15 more ever did), and only while those steps were
      // converging (|R| down by kFallbackProgress from the guess). Otherwise (Newton cycling where
      // the residual is not smooth: on the BRB's mode 2 at log10 a = -4.31, where one element's
      // response jumps, |R| 5.8e3 -> 1.4e3 -> 5.9e3 -> ...) the step is halved at once: restarting
      // full Newton there repeated the chord's iterates and cycled for 20 dense factorisations per
      // halving.
      const int chord_factorizations = r.factorizations;
      const int left = std::min(opt.newton.max_iterations - chord_factorizations,
                                chord_max_factorizations(opt.newton));
      std::string failure = r.failure;
      bool go_on = chord_factorizations == 0;
      if (!go_on && left > 0 && std::isfinite(r.residual_norm)) {
        Eigen::VectorXd R_guess;
        std::string ignored;
        evaluate(g, guess, R_guess, nullptr, ignored);
        go_on = R_guess.allFinite() &&
                r.residual_norm <= kFallbackProgress * R_guess.cwiseAbs().maxCoeff();
      }
      if (go_on) {
        out.newton_iterations += static_cast<std::size_t>(r.iterations);
        if (chord_factorizations == 0) {
          r = newton_square(g, guess, scale, pb.residual_scale, opt.newton);
        } else {
          NewtonOptions rest = opt.newton;
          rest.max_iterations = left;
          r = newton_square(g, r.y, scale, pb.residual_scale, rest);
        }
        r.factorizations += chord_factorizations;
        if (r.failure.empty()) r.failure = failure;
      }
    }
    out.newton_iterations += static_cast<std::size_t>(r.iterations);
    out.factorizations += static_cast<std::size_t>(r.factorizations);
    if (!r.failure.empty()) last_failure = r.failure;
    return r;
  };
  {
    const auto start = correct(fixed_parameter(lambda0), without(y0), without(pb.scale));
    if (!start.converged) {
      throw NumericalError(fmt::format(
          "the continuation cannot start: Newton did not converge at the start (parameter {}, "
          "residual {} after {} iterations); start from a smaller amplitude or force, or nearer "
          "a solution{}",
          core::format_value(lambda0), core::format_value(start.residual_norm), start.iterations,
          start.failure.empty() ? "" : fmt::format(" (at a trial point: {})", start.failure)));
    }
    out.points.push_back(with(start.y, lambda0));
  }

  Eigen::VectorXd R;
  Eigen::MatrixXd J;
  pb.f(out.points.back(), R, &J);
  Eigen::VectorXd e_p = Eigen::VectorXd::Zero(n);
  e_p(p) = 1.0;
  double sigma = 1.0;  // orientation of the tangent t
  // Chord Newton: the factorisation of [J S; base_ref^T] at the last point.
  std::shared_ptr<const Eigen::PartialPivLU<Eigen::MatrixXd>> base_lu;
  Eigen::VectorXd base_ref = e_p;
  Eigen::VectorXd t = tangent_of(J, pb.scale, e_p, &sigma, chord ? &base_lu : nullptr);
  if (t.size() == 0) {
    throw NumericalError(
        "the continuation cannot start: the tangent at the start is undefined (a "
        "singular Jacobian)");
  }
  if (t(p) * sense < 0.0) {
    t = -t;
    sigma = -sigma;
  }
  std::vector<Eigen::VectorXd> tangents{t};  // at each point
  std::vector<Eigen::VectorXd> scaled{(out.points.back().array() / pb.scale.array()).matrix()};
  double h = opt.step;
  double h_regular = h;     // the step after the last point reached at the first try
  bool smooth_step = true;  // no step rejected since the last point
  double last_dir = t(p) > 0.0 ? 1.0 : -1.0;

  while (true) {
    const Eigen::VectorXd& y = out.points.back();
    if (progress) progress(std::clamp((y(p) - lambda0) / range, 0.0, 1.0));
    if (out.points.size() >= opt.max_points) {
      out.cause = StopCause::max_points;
      out.stop_reason = fmt::format("reached max_points = {} at parameter {}", opt.max_points,
                                    core::format_value(y(p)));
      break;
    }
    if (h < opt.min_step) {
      out.cause = StopCause::stalled;
      out.stop_reason = fmt::format(
          "stalled at parameter {}: the step size fell below min_step = {} (Newton did not "
          "converge on smaller steps){}",
          core::format_value(y(p)), core::format_value(opt.min_step),
          last_failure.empty()
              ? ""
              : fmt::format("; the last element error at a trial point: {}", last_failure));
      break;
    }
    const Eigen::VectorXd z = (y.array() / pb.scale.array()).matrix();
    const Eigen::VectorXd z_ahead = z + h * t;
    const double lambda_pred = z_ahead(p) * pb.scale(p);
    // Past the end: land the last point on it at fixed parameter.
    if ((lambda_pred - lambda_end) * sense >= 0.0 && t(p) * sense > 0.0) {
      const double frac = (lambda_end - y(p)) / (lambda_pred - y(p));
      const Eigen::VectorXd guess = (z + frac * h * t).cwiseProduct(pb.scale);
      const auto end = correct(fixed_parameter(lambda_end), without(guess), without(pb.scale));
      if (end.converged) {
        out.points.push_back(with(end.y, lambda_end));
        out.complete = true;
        out.stop_reason = "reached the end of the parameter range";
        if (progress) progress(1.0);
        break;
      }
      ++out.rejected_steps;
      smooth_step = false;
      h *= 0.5;
      continue;
    }
    // Corrector: R(y) = 0 and d^T (z - z_pred) = 0 with z_pred = z + h d.
    auto corrector = [&](const Eigen::VectorXd& d, Eigen::VectorXd& zp) {
      zp = z + h * d;
      const Eigen::VectorXd zp_fixed = zp;
      // The bordered Jacobian D [J S; d^T] S^-1 (D = diag(1, .., 1, residual_scale)) with
      // J at the last point: its factorisation there has the border row base_ref, so
      // B = A + e_n (d - base_ref)^T is solved by Sherman-Morrison.
      ChordSolve initial;
      if (chord && base_lu) {
        Eigen::VectorXd e_n = Eigen::VectorXd::Zero(n);
        e_n(n - 1) = 1.0;
        const Eigen::VectorXd Au = base_lu->solve(e_n);
        const Eigen::VectorXd v = d - base_ref;
        const double denom = 1.0 + v.dot(Au);
        if (Au.allFinite() && std::abs(denom) > 1e-8) {
          initial = [lu = base_lu, Au, v, denom, rs = pb.residual_scale, sc = pb.scale,
                     n](const Eigen::VectorXd& b) {
            Eigen::VectorXd c = b;
            c(n - 1) /= rs;
            Eigen::VectorXd w = lu->solve(c);
            w -= Au * (v.dot(w) / denom);
            return Eigen::VectorXd(w.cwiseProduct(sc));
          };
        }
      }
      auto bordered = [&, d, zp_fixed](const Eigen::VectorXd& yy, Eigen::VectorXd& Rb,
                                       Eigen::MatrixXd* Jb) {
        Eigen::VectorXd r;
        Eigen::MatrixXd Jy;
        pb.f(yy, r, Jb ? &Jy : nullptr);
        Rb.resize(n);
        Rb.head(n - 1) = r;
        const Eigen::VectorXd zz = (yy.array() / pb.scale.array()).matrix();
        // The arclength equation in residual units, so that the line search weighs it fairly.
        Rb(n - 1) = pb.residual_scale * d.dot(zz - zp_fixed);
        if (Jb) {
          Jb->resize(n, n);
          Jb->topRows(n - 1) = Jy;
          Jb->row(n - 1) = pb.residual_scale * (d.array() / pb.scale.array()).matrix().transpose();
        }
      };
      return correct(bordered, zp.cwiseProduct(pb.scale), pb.scale, initial);
    };
    // True when a point y moving along `dir` goes back along the curve already traced:
    // it lies on the polyline of the last points (within a tenth of the step plus the
    // sag of a chord, about its length times the turn of the tangent over it / 4) and
    // moves against it.
    auto retraces = [&](const Eigen::VectorXd& yy, const Eigen::VectorXd& dir, double step) {
      const Eigen::VectorXd zz = (yy.array() / pb.scale.array()).matrix();
      const std::size_t np = scaled.size();
      for (std::size_t k = np - 1; k >= 1 && k + kRecentPoints >= np; --k) {
        const Eigen::VectorXd& a = scaled[k - 1];
        if (dir.dot(scaled[k] - a) >= 0.0) continue;  // moving along this chord
        const Eigen::VectorXd ab = scaled[k] - a;
        const double l2 = ab.squaredNorm();
        if (!(l2 > 0.0)) continue;
        const double turn = std::acos(std::clamp(tangents[k - 1].dot(tangents[k]), -1.0, 1.0));
        // Against the chord to within the turn over it (another piece of the curve, a
        // fold's far strand, turns by a finite angle).
        const double against = std::acos(std::clamp(-dir.dot(ab) / std::sqrt(l2), -1.0, 1.0));
        if (against > turn + kRetraceAngle) continue;
        const double s = std::clamp((zz - a).dot(ab) / l2, 0.0, 1.0);
        if ((a + s * ab - zz).norm() < 0.1 * step + 0.25 * std::sqrt(l2) * turn) return true;
      }
      return false;
    };
    Eigen::VectorXd z_used;
    Eigen::VectorXd d_used = t;
    NewtonResult corr = corrector(t, z_used);
    bool kink = false;
    if (!corr.converged && h <= kKinkStep * opt.step) {
      // A fold at a kink: the curve meets the boundary of a piece of the piecewise-smooth
      // residual (contact or slip changing at a sample) and leaves it on the next piece,
      // possibly backwards, so that no point on the plane normal to t continues it. The
      // next piece's tangent comes from the Jacobian just across the boundary, oriented
      // so that det [J S; t^T] keeps its sign (Allgower & Georg 2003, sec. 2.1 and 12.1).
      Eigen::VectorXd Rk;
      Eigen::MatrixXd Jk;
      evaluate(pb.f, (z + h * t).cwiseProduct(pb.scale), Rk, &Jk, last_failure);
      double sigma_k = 1.0;
      Eigen::VectorXd d = Jk.size() != 0 && Jk.allFinite() ? tangent_of(Jk, pb.scale, t, &sigma_k)
                                                           : Eigen::VectorXd{};
      if (d.size() != 0 && std::abs(d.dot(t)) < std::cos(kKinkAngle)) {
        if (sigma_k != sigma) d = -d;
        // The orientation's sign is that of the piece across the boundary; should the
        // probe have crossed more than one boundary, the other sense is tried too.
        for (const double sense_d : {1.0, -1.0}) {
          Eigen::VectorXd zk;
          NewtonResult ck = corrector(sense_d * d, zk);
          if (!ck.converged) continue;
          Eigen::VectorXd Rc;
          Eigen::MatrixXd Jc;
          pb.f(ck.y, Rc, &Jc);
          Eigen::VectorXd tc = tangent_of(Jc, pb.scale, sense_d * d);
          if (tc.size() == 0) continue;
          if (tc.dot(sense_d * d) < 0.0) tc = -tc;
          if (!retraces(ck.y, tc, h)) {
            corr = std::move(ck);
            z_used = zk;
            d_used = sense_d * d;
            kink = true;
            ++out.kinks;
            break;
          }
        }
      }
    }
    if (!corr.converged) {
      ++out.rejected_steps;
      smooth_step = false;
      h *= 0.5;
      continue;
    }
    // A corrector that wandered far from the predictor has jumped to another branch of
    // the curve (seen at lightly damped resonances with large steps): a shorter step.
    const double wander = ((corr.y.array() / pb.scale.array()).matrix() - z_used).norm();
    if (wander > std::max(2.0 * h, 10.0 * opt.min_step) && h > opt.min_step * 2.0) {
      ++out.rejected_steps;
      smooth_step = false;
      h *= 0.5;
      continue;
    }
    pb.f(corr.y, R, &J);
    double sigma_new = 1.0;
    std::shared_ptr<const Eigen::PartialPivLU<Eigen::MatrixXd>> new_lu;
    Eigen::VectorXd t_new = tangent_of(J, pb.scale, d_used, &sigma_new, chord ? &new_lu : nullptr);
    if (t_new.size() == 0) {
      ++out.rejected_steps;
      smooth_step = false;
      h *= 0.5;
      continue;
    }
    const double angle = std::acos(std::clamp(t_new.dot(t), -1.0, 1.0));
    // A kink of the solution curve (stick-slip onset, separation) turns the tangent by a
    // finite angle however short the step: past a few halvings the point is accepted.
    if (!kink && angle > opt.max_angle && h > std::max(16.0 * opt.min_step, opt.step / 64.0)) {
      ++out.rejected_steps;
      smooth_step = false;
      h *= 0.5;
      continue;
    }
    out.points.push_back(corr.y);
    last_failure.clear();
    if (chord) {
      base_lu = std::move(new_lu);
      base_ref = d_used;
    }
    const double dir = t_new(p) > 0.0 ? 1.0 : -1.0;
    if (dir != last_dir) ++out.turning_points;
    last_dir = dir;
    t = t_new;
    tangents.push_back(t);
    scaled.emplace_back((corr.y.array() / pb.scale.array()).matrix());
    sigma = sigma_new;
    // Step control: aim at target_iterations per point and a bounded turn.
    const int effort = chord ? corr.factorizations + (corr.iterations + 3) / 4 : corr.iterations;
    const double ratio =
        static_cast<double>(opt.target_iterations) / static_cast<double>(std::max(1, effort));
    double factor = std::clamp(ratio, 0.5, 2.0);
    if (angle > 0.5 * opt.max_angle) factor = std::min(factor, 1.0);
    // Past a kink the next piece is smooth again: back to the step of the last regular
    // point rather than growing from the short step that found the boundary.
    h = std::clamp(kink ? std::max(h, 0.5 * h_regular) : h * factor, opt.min_step * 0.5,
                   opt.max_step);
    if (!kink && smooth_step) h_regular = h;
    smooth_step = true;
    // Leaving the range backwards (the curve turned round and went past the start).
    if ((corr.y(p) - lambda0) * sense < -std::abs(range)) {
      out.cause = StopCause::turned_back;
      out.stop_reason = "the curve turned back past the start of the parameter range";
      break;
    }
  }
  return out;
}

namespace {

// Iterations allowed to Brent's method when refining a maximum along the curve.
constexpr std::uintmax_t kBrentIterations = 100;

// The curve near point k (0 < k < last) as y(sigma): the solution on the plane
// c^T (z - z_{k-1}) = sigma, c the unit chord from z_{k-1} to z_{k+1} in scaled unknowns,
// corrected by Newton from the polyline through the three points.
class LocalCurve {
 public:
  LocalCurve(const ContinuationProblem& pb, const std::vector<Eigen::VectorXd>& points,
             std::size_t k, const NewtonOptions& newton)
      : pb_(pb), newton_(newton) {
    for (int j = 0; j < 3; ++j) {
      z_[j] = (points[k - 1 + static_cast<std::size_t>(j)].array() / pb.scale.array()).matrix();
    }
    length_ = (z_[2] - z_[0]).norm();
    c_ = length_ > 0.0 ? Eigen::VectorXd((z_[2] - z_[0]) / length_) : Eigen::VectorXd();
    sigma_mid_ = length_ > 0.0 ? c_.dot(z_[1] - z_[0]) : 0.0;
  }
  [[nodiscard]] double length() const { return length_; }
  [[nodiscard]] bool monotone() const {
    return length_ > 0.0 && sigma_mid_ > 0.0 && sigma_mid_ < length_;
  }
  // The point at sigma; empty when Newton fails there.
  [[nodiscard]] Eigen::VectorXd at(double sigma) const {
    const Eigen::VectorXd guess =
        sigma <= sigma_mid_ ? Eigen::VectorXd(z_[0] + (z_[1] - z_[0]) * (sigma / sigma_mid_))
                            : Eigen::VectorXd(z_[1] + (z_[2] - z_[1]) * ((sigma - sigma_mid_) /
                                                                         (length_ - sigma_mid_)));
    const Eigen::Index n = guess.size();
    const SystemFunction g = [&](const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J) {
      Eigen::VectorXd r;
      Eigen::MatrixXd Jy;
      pb_.f(y, r, J ? &Jy : nullptr);
      R.resize(n);
      R.head(n - 1) = r;
      R(n - 1) =
          pb_.residual_scale * (c_.dot((y.array() / pb_.scale.array()).matrix() - z_[0]) - sigma);
      if (J) {
        J->resize(n, n);
        J->topRows(n - 1) = Jy;
        J->row(n - 1) = pb_.residual_scale * (c_.array() / pb_.scale.array()).matrix().transpose();
      }
    };
    const NewtonResult r =
        solve_newton(g, guess.cwiseProduct(pb_.scale), pb_.scale, pb_.residual_scale, newton_);
    return r.converged ? r.y : Eigen::VectorXd();
  }

 private:
  const ContinuationProblem& pb_;
  NewtonOptions newton_;
  Eigen::VectorXd z_[3];
  Eigen::VectorXd c_;
  double length_ = 0.0;
  double sigma_mid_ = 0.0;
};

}  // namespace

Eigen::VectorXd refine_curve_maximum(const ContinuationProblem& pb,
                                     const std::vector<Eigen::VectorXd>& points, std::size_t k,
                                     const NewtonOptions& newton,
                                     const std::function<double(const Eigen::VectorXd&)>& value) {
  const LocalCurve curve(pb, points, k, newton);
  if (!curve.monotone()) return points[k];
  bool failed = false;
  const auto minus_value = [&](double sigma) {
    const Eigen::VectorXd y = curve.at(sigma);
    if (y.size() == 0) {
      failed = true;
      return std::numeric_limits<double>::max();
    }
    return -value(y);
  };
  // Brent's method locates a smooth maximum to sqrt(machine epsilon) of the chord (it
  // caps `bits` at half the mantissa); the value's error is quadratic in that.
  std::uintmax_t iterations = kBrentIterations;
  const auto best = boost::math::tools::brent_find_minima(
      minus_value, 0.0, curve.length(), std::numeric_limits<double>::digits / 2, iterations);
  if (failed || !(-best.second >= value(points[k]))) return points[k];
  return curve.at(best.first);
}

std::vector<std::size_t> prominent_maxima(const std::vector<double>& v,
                                          const std::function<double(double)>& min_prominence) {
  std::vector<std::size_t> out;
  const std::size_t n = v.size();
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (!(v[k] > v[k - 1] && v[k] >= v[k + 1])) continue;
    double left = v[k], right = v[k];
    for (std::size_t j = k; j-- > 0 && v[j] <= v[k];) left = std::min(left, v[j]);
    for (std::size_t j = k + 1; j < n && v[j] <= v[k]; ++j) right = std::min(right, v[j]);
    if (v[k] - std::max(left, right) >= min_prominence(v[k])) out.push_back(k);
  }
  return out;
}

}  // namespace asperity::vibration
