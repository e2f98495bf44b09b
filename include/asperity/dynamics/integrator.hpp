#pragma once
// Adaptive explicit Runge-Kutta integration with event location (thesis ch. 7).
//
// Two embedded pairs:
//  - Bogacki-Shampine 3(2) with MATLAB ode23's step control (Shampine & Reichelt,
//    SIAM J. Sci. Comput. 18 (1997) 1-22): error per step
//      err = max_i |h sum_j E_j k_ij| / max(scale_i, atol_i/rtol),
//    scale_i = max(|y_i|, |ynew_i|) as in ode23 unless the problem says otherwise
//    (OdeProblem::error_scales), accepted if err <= rtol; a failed step shrinks h by max(0.5, 0.8
//    (rtol/err)^(1/3)) the first time and by 1/2 after that; a step that succeeds at the first
//    attempt sets the next to h/max(0.2, 1.25 (err/rtol)^(1/3)); the initial step, hmax = (t1 -
//    t0)/10 and hmin = 16 eps(t) as in ode23. This reproduces the thesis's integrations (rtol 1e-6,
//    atol 1e-7) up to the event handling: MATLAB takes the state at an event from the interpolant,
//    this code redoes the step to end there.
//  - Dormand-Prince 5(4) (the default), with the same control and exponent 1/5 and
//    ode45's factor 0.1 on the first failure.
// Both are FSAL and have continuous extensions (ode23's ntrp23, ode45's ntrp45).
// Written here rather than taken from Boost.Odeint so that the step control matches
// MATLAB's exactly and events can restart the step cleanly.
//
// Events: the problem names one state (the velocity) whose sign changes are events.
// Within each accepted step the continuous extension is sampled for a sign change and
// the crossing is located on it by root finding. The step is then redone to end on the
// discrete solution's own zero: a safeguarded Newton iteration on the step length
// (started at the interpolant's root, bisecting inside a bracket when Newton leaves it
// or is slow) until the state is zero to round-off; the step taken is always the last
// one computed, so its state, time and continuous extension belong together. The
// problem then commits its memory (on_event) and integration restarts with a fresh
// right-hand side. Sign changes while the motion is at rest within the tolerance are
// not events (OdeProblem::event_rest_state). Known discontinuities in time (the end of
// an impulse) are breakpoints: steps end on them exactly.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace asperity::dynamics {

enum class Method {
  bogacki_shampine_32,  ///< MATLAB ode23
  dormand_prince_54,    ///< ode45-like, the default
};

[[nodiscard]] const char* to_string(Method m);
/// "bs23"/"ode23" or "dp54"/"ode45"/"dopri5"; throws InvalidInput otherwise.
[[nodiscard]] Method parse_method(const std::string& name);

/// A first-order system y' = f(t, y) whose right-hand side is smooth between events.
class OdeProblem {
 public:
  virtual ~OdeProblem() = default;
  OdeProblem() = default;
  OdeProblem(const OdeProblem&) = default;
  OdeProblem& operator=(const OdeProblem&) = default;

  [[nodiscard]] virtual std::size_t size() const = 0;
  /// dydt = f(t, y). May throw; must be const between events.
  virtual void rhs(double t, std::span<const double> y, std::span<double> dydt) const = 0;
  /// The magnitudes against which the local errors are measured: state i is accepted if
  /// |err_i| <= rtol max(scale_i, atol_i/rtol). ode23/ode45 (the default) use
  /// scale_i = max(|y_i(t)|, |y_i(t_new)|); a problem may measure an accumulated
  /// quantity against a physical scale instead of its own growing value.
  virtual void error_scales(double /*t*/, std::span<const double> y, double /*t_new*/,
                            std::span<const double> y_new, std::span<double> scale) const {
    for (std::size_t i = 0; i < scale.size(); ++i) {
      scale[i] = std::max(std::abs(y[i]), std::abs(y_new[i]));
    }
  }
  /// Index of the state whose zero crossings are events, or size() for none.
  [[nodiscard]] virtual std::size_t event_state() const { return size(); }
  /// The state whose rate is the event state (the displacement for velocity events),
  /// or size() for none. With one, zeros of the event state count as events only once
  /// this state has moved by more than ten times its absolute tolerance since the last
  /// event: below that the integration does not resolve the motion (a mass at rest
  /// dithers at the level of the local error allowed per step), and such "reversals"
  /// would commit memory and restart the step for nothing.
  [[nodiscard]] virtual std::size_t event_rest_state() const { return size(); }
  /// Called at each located event with the state there (which it may not change).
  virtual void on_event(double /*t*/, std::span<const double> /*y*/) {}
  /// Times where the right-hand side is discontinuous; steps end on them.
  [[nodiscard]] virtual std::vector<double> breakpoints() const { return {}; }
};

struct IntegratorOptions {
  Method method = Method::dormand_prince_54;
  double rtol = 1e-6;  ///< relative tolerance, in [1e-13, 0.1]
  /// Absolute tolerance per state; one value applies to all states. Each > 0.
  std::vector<double> atol{1e-7};
  /// Largest step; 0 means MATLAB's default of a tenth of the interval.
  double max_step = 0.0;
  /// Initial step; 0 means ode23/ode45's automatic choice.
  double initial_step = 0.0;
  /// The step-size collapse threshold: the integration fails when the step falls
  /// below max(min_step, 16 eps(t)).
  double min_step = 0.0;
  std::size_t max_steps = 50'000'000;
  void validate(std::size_t n_states) const;
};

/// Counters of one integration.
struct IntegratorStats {
  std::size_t steps = 0;            ///< accepted steps
  std::size_t rejected_steps = 0;   ///< steps that failed the error test
  std::size_t rhs_evaluations = 0;  ///< calls of OdeProblem::rhs
  std::size_t events = 0;           ///< located events
  /// Accepted steps whose size was held by stability rather than accuracy (Dormand-Prince
  /// only): the stiffness test of Hairer's DOPRI5, h |lambda| ~ h ||k7 - k6|| / ||y7 -
  /// y6|| (the two stages at c = 1) above 2.5 (DOPRI5: 3.25; under ode45's control a
  /// stiff problem settles at 2.7-2.9), counted from the 15th such step in a row on
  /// (Hairer & Wanner, Solving ODEs II, sec. IV.2). Many of them mean a stiff problem (e.g. a
  /// Dankowicz contact with F_max/delta >> 1 while it slides), for which an explicit
  /// method is slow though still accurate.
  std::size_t stiff_steps = 0;
};

/// Receives every accepted step: t, y, and a continuous extension valid on
/// [t_prev, t] (dense(s, out) with s in [t_prev, t]). `is_event` marks steps that end
/// on an event.
struct StepView {
  double t_prev;
  double t;
  std::span<const double> y;
  bool is_event;
  std::function<void(double, std::span<double>)> dense;
};

/// Integrates `problem` from (t0, y0) to t1 > t0. Throws NumericalError if the step
/// size collapses, the state becomes non-finite, or max_steps is exceeded (each says
/// where, with what tolerances), InvalidInput for bad options.
IntegratorStats integrate(OdeProblem& problem, std::span<const double> y0, double t0, double t1,
                          const IntegratorOptions& options,
                          const std::function<void(const StepView&)>& observer);

}  // namespace asperity::dynamics
