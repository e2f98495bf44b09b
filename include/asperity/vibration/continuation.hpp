#pragma once
// Newton's method with a line search, and pseudo-arclength continuation with step-size
// control that follows turning points (Keller 1977; Allgower & Georg, "Introduction to
// Numerical Continuation Methods", 2003, ch. 2 and 6), including folds at kinks of a
// piecewise-smooth residual (AFT with contact and slip located at samples): where no
// point on the corrector's plane continues the curve, the next piece's tangent, taken
// from the Jacobian across the boundary and oriented by the sign of det [J S; t^T]
// (ch. 2.1, and the piecewise-linear methods of ch. 12), gives the predictor.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace asperity::vibration {

/// Newton settings. Convergence: the scaled step max|dy_i / scale_i| < step_tolerance
/// and |R| <= residual_tolerance * residual_scale.
struct NewtonOptions {
  int max_iterations = 20;           ///< >= 1
  double step_tolerance = 1e-9;      ///< (0, 1)
  double residual_tolerance = 1e-9;  ///< (0, 1)
  void validate() const;
};

/// R(y) (m equations) and, when J is non-null, dR/dy (m x unknowns).
using SystemFunction =
    std::function<void(const Eigen::VectorXd& y, Eigen::VectorXd& R, Eigen::MatrixXd* J)>;

struct NewtonResult {
  Eigen::VectorXd y;
  bool converged = false;
  int iterations = 0;
  double residual_norm = 0.0;
  /// Jacobians factorised (chord Newton, ContinuationOptions::chord_unknowns; in full
  /// Newton one per iteration).
  int factorizations = 0;
  /// The last NumericalError met at a trial point (an element outside what it represents):
  /// such a point counts as a failed evaluation, the step is shortened. Empty if none.
  std::string failure;
};

/// Square system (m = unknowns): Newton with a backtracking line search on |R|^2
/// (Armijo, halving down to 1/64). `scale` is the typical magnitude of each unknown.
[[nodiscard]] NewtonResult solve_newton(const SystemFunction& f, Eigen::VectorXd y0,
                                        const Eigen::VectorXd& scale, double residual_scale,
                                        const NewtonOptions& options);

struct ContinuationOptions {
  double step = 0.05;      ///< initial arclength step in scaled unknowns; > 0
  double min_step = 1e-6;  ///< below this the continuation has stalled; > 0
  double max_step = 0.5;   ///< >= step
  std::size_t max_points = 2000;
  int target_iterations = 4;  ///< Newton iterations per point the step size aims at
  double max_angle = 0.35;    ///< [rad] largest turn of the tangent between points
  /// Systems with at least this many unknowns are corrected by chord Newton: the
  /// factorisation made for the tangent at the last point (its border row updated by
  /// Sherman-Morrison) serves the next corrector's iterations while each reduces |R| by
  /// half; a fresh Jacobian is factorised at the iterate only when one does not. Where one
  /// dense LU costs hundreds of residual evaluations (a reduced finite-element model:
  /// 649 DOFs x 7 coefficients), this takes one factorisation per point instead of one
  /// per iteration. Step control then counts factorisations plus a quarter of the chord
  /// iterations against target_iterations. >= 1.
  std::size_t chord_unknowns = 1500;
  NewtonOptions newton;
  void validate() const;
};

/// A one-parameter family R(y) = 0 with unknowns = m + 1. The continuation runs from y0
/// (a solution, or a guess that Newton corrects at fixed parameter) in the direction of
/// increasing (or decreasing) y[parameter] until it passes `parameter_end`.
struct ContinuationProblem {
  SystemFunction f;
  Eigen::Index parameter = 0;   ///< index of the continuation parameter in y
  Eigen::VectorXd scale;        ///< typical magnitude of each unknown (> 0)
  double residual_scale = 1.0;  ///< typical magnitude of R (> 0)
  double parameter_end = 0.0;
};

/// Why a continuation stopped.
enum class StopCause {
  end,          ///< the parameter end was reached
  max_points,   ///< max_points converged points
  stalled,      ///< no converged point on steps down to min_step
  turned_back,  ///< the curve went back past the start of the range
};

struct ContinuationResult {
  std::vector<Eigen::VectorXd> points;  ///< converged solutions in order along the curve
  std::size_t newton_iterations = 0;
  /// Jacobians factorised by the correctors (the cost that dominates on large systems).
  std::size_t factorizations = 0;
  std::size_t rejected_steps = 0;
  std::size_t turning_points = 0;  ///< sign changes of d parameter / d s
  /// Points reached along the tangent of the next piece of a piecewise-smooth residual
  /// (a fold or sharp turn at a kink of the curve).
  std::size_t kinks = 0;
  bool complete = false;  ///< the parameter end was reached
  StopCause cause = StopCause::end;
  std::string stop_reason;  ///< why it stopped (for messages and summaries)
};

/// Progress callback: fraction of the parameter range covered, in [0, 1].
using ProgressFunction = std::function<void(double)>;

/// Pseudo-arclength continuation. Never throws for a stall: it returns what it has with
/// complete = false and the reason; throws NumericalError if y0 cannot be corrected.
[[nodiscard]] ContinuationResult continue_curve(const ContinuationProblem& problem,
                                                const Eigen::VectorXd& y0,
                                                const ContinuationOptions& options,
                                                const ProgressFunction& progress = {});

/// The maximum of value(y) along the curve between points[k-1] and points[k+1] (0 < k <
/// points.size() - 1, points[k] the largest of the three): the curve is parametrised by
/// sigma on the chord from points[k-1] to points[k+1] (in scaled unknowns), each point
/// corrected by Newton on R(y) = 0 and the chord's plane, and Brent's method finds the
/// maximum to sqrt(machine epsilon) of the chord (the value's error quadratic in that,
/// where the curve is smooth). Returns points[k]
/// where the chord does not parametrise the curve or Newton fails.
[[nodiscard]] Eigen::VectorXd refine_curve_maximum(
    const ContinuationProblem& problem, const std::vector<Eigen::VectorXd>& points, std::size_t k,
    const NewtonOptions& newton, const std::function<double(const Eigen::VectorXd&)>& value);

/// Interior local maxima of v whose topographic prominence (how far v falls on both sides
/// before rising above the maximum again or reaching an end) is at least
/// min_prominence(v_k), in order.
[[nodiscard]] std::vector<std::size_t> prominent_maxima(
    const std::vector<double>& v, const std::function<double(double)>& min_prominence);

}  // namespace asperity::vibration
