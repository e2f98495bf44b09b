#include "asperity/dynamics/integrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "asperity/core/error.hpp"
#include "asperity/core/interrupt.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::dynamics {

const char* to_string(Method m) {
  switch (m) {
    case Method::bogacki_shampine_32:
      return "bs23";
    case Method::dormand_prince_54:
      return "dp54";
  }
  return "?";
}

Method parse_method(const std::string& name) {
  if (name == "bs23" || name == "ode23" || name == "bogacki_shampine_32") {
    return Method::bogacki_shampine_32;
  }
  if (name == "dp54" || name == "ode45" || name == "dopri5" || name == "dormand_prince_54") {
    return Method::dormand_prince_54;
  }
  throw InvalidInput(
      fmt::format("integrator method \"{}\" is not known: use \"bs23\" (MATLAB ode23) or \"dp54\" "
                  "(Dormand-Prince 5(4))",
                  name));
}

void IntegratorOptions::validate(std::size_t n_states) const {
  core::require_in_closed("rtol", rtol, 1e-13, 0.1);
  if (atol.size() != 1 && atol.size() != n_states) {
    throw InvalidInput(fmt::format("atol has {} entries: give one value or one per state ({})",
                                   atol.size(), n_states));
  }
  for (double a : atol) {
    if (!(std::isfinite(a) && a > 0.0 && a <= 1e3)) {
      throw InvalidInput(
          fmt::format("atol = {} is not allowed: it must lie in (0, 1000]", core::format_value(a)));
    }
  }
  core::require_non_negative("max_step", max_step);
  core::require_non_negative("initial_step", initial_step);
  core::require_non_negative("min_step", min_step);
  if (max_steps == 0) throw InvalidInput("max_steps must be > 0");
}

namespace {

constexpr int kMaxStages = 7;

struct Tableau {
  int stages;  // including the FSAL stage
  std::array<double, kMaxStages> c;
  std::array<std::array<double, kMaxStages>, kMaxStages> a;  // a[i][j], j < i
  std::array<double, kMaxStages> E;                          // b - b_hat
  int bi_cols;
  std::array<std::array<double, 4>, kMaxStages> BI;  // continuous extension
  double pow;                                        // 1/(order of the error estimate + 1)
  double first_fail_min;                             // ode23: 0.5, ode45: 0.1
};

// Bogacki & Shampine (1989); E and BI (ntrp23) as in MATLAB ode23.
const Tableau kBS23{4,
                    {0.0, 0.5, 0.75, 1.0},
                    {{{}, {0.5}, {0.0, 0.75}, {2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0}}},
                    {-5.0 / 72.0, 1.0 / 12.0, 1.0 / 9.0, -1.0 / 8.0},
                    3,
                    {{{1.0, -4.0 / 3.0, 5.0 / 9.0},
                      {0.0, 1.0, -2.0 / 3.0},
                      {0.0, 4.0 / 3.0, -8.0 / 9.0},
                      {0.0, -1.0, 1.0}}},
                    1.0 / 3.0,
                    0.5};

// Dormand & Prince (1980); E and BI (ntrp45) as in MATLAB ode45.
const Tableau kDP54{
    7,
    {0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0},
    {{{},
      {0.2},
      {3.0 / 40.0, 9.0 / 40.0},
      {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0},
      {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0},
      {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0},
      {35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0}}},
    {71.0 / 57600.0, 0.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0, 22.0 / 525.0,
     -1.0 / 40.0},
    4,
    {{{1.0, -183.0 / 64.0, 37.0 / 12.0, -145.0 / 128.0},
      {0.0, 0.0, 0.0, 0.0},
      {0.0, 1500.0 / 371.0, -1000.0 / 159.0, 1000.0 / 371.0},
      {0.0, -125.0 / 32.0, 125.0 / 12.0, -375.0 / 64.0},
      {0.0, 9477.0 / 3392.0, -729.0 / 106.0, 25515.0 / 6784.0},
      {0.0, -11.0 / 7.0, 11.0 / 3.0, -55.0 / 28.0},
      {0.0, 1.5, -4.0, 2.5}}},
    0.2,
    0.1};

// One Runge-Kutta step and everything needed for its continuous extension.
class Stepper {
 public:
  Stepper(const Tableau& tab, OdeProblem& problem, std::size_t n, IntegratorStats& stats)
      : tab_(tab), problem_(problem), n_(n), stats_(stats), ytmp_(n), e_(n) {
    for (auto& k : K_) k.assign(n, 0.0);
  }

  // Attempts a step of size h from (t, y) with f0 = f(t, y); stages at t + h are
  // evaluated at t_end_eval (just left of a breakpoint when the step ends on one).
  // Fills ynew, fnew (the FSAL stage) and returns the error norm relative to rtol
  // weights (accept if <= rtol), +inf if the state became non-finite.
  double attempt(double t, std::span<const double> y, std::span<const double> f0, double h,
                 double t_end_eval, std::span<const double> threshold, std::vector<double>& ynew) {
    t_ = t;
    h_ = h;
    y0_.assign(y.begin(), y.end());
    std::copy(f0.begin(), f0.end(), K_[0].begin());
    const int s = tab_.stages;
    bool finite = true;
    for (int i = 1; i < s; ++i) {
      for (std::size_t m = 0; m < n_; ++m) {
        double acc = 0.0;
        for (int j = 0; j < i; ++j) acc += tab_.a[i][j] * K_[j][m];
        ytmp_[m] = y[m] + h * acc;
      }
      const double ti = tab_.c[i] == 1.0 ? t_end_eval : t + tab_.c[i] * h;
      problem_.rhs(ti, ytmp_, K_[i]);
      ++stats_.rhs_evaluations;
      if (i == s - 2) ystage_ = ytmp_;  // for the stiffness test
      if (i == s - 1) ynew = ytmp_;     // FSAL: the last stage is at the new point
    }
    double err = 0.0;
    for (std::size_t m = 0; m < n_; ++m) {
      if (!std::isfinite(ynew[m])) finite = false;
    }
    if (!finite) return std::numeric_limits<double>::infinity();
    problem_.error_scales(t, y, t_end_eval, ynew, e_);
    for (std::size_t m = 0; m < n_; ++m) {
      double e = 0.0;
      for (int j = 0; j < s; ++j) e += tab_.E[j] * K_[j][m];
      e *= h;
      if (!std::isfinite(e)) finite = false;
      const double wt = std::max(e_[m], threshold[m]);
      err = std::max(err, std::abs(e) / wt);
    }
    if (!finite) return std::numeric_limits<double>::infinity();
    return err;
  }

  [[nodiscard]] std::span<const double> fnew() const { return K_[tab_.stages - 1]; }

  // h |lambda| estimated from the last two stages when both are at c = 1 (DOPRI5's
  // stiffness test), after an attempt that ended at ynew; 0 for other tableaus.
  [[nodiscard]] double stability_estimate(std::span<const double> ynew) const {
    const int s = tab_.stages;
    if (tab_.c[s - 2] != 1.0) return 0.0;
    double num = 0.0, den = 0.0;
    for (std::size_t m = 0; m < n_; ++m) {
      const double dk = K_[s - 1][m] - K_[s - 2][m];
      const double dy = ynew[m] - ystage_[m];
      num += dk * dk;
      den += dy * dy;
    }
    return den > 0.0 ? h_ * std::sqrt(num / den) : 0.0;
  }

  // Continuous extension at time s in [t, t + h] of the last attempt.
  void dense(double s, std::span<double> out) const {
    const double theta = (s - t_) / h_;
    std::array<double, 4> pw{};
    double p = theta;
    for (int j = 0; j < tab_.bi_cols; ++j) {
      pw[j] = p;
      p *= theta;
    }
    for (std::size_t m = 0; m < n_; ++m) {
      double acc = 0.0;
      for (int i = 0; i < tab_.stages; ++i) {
        double w = 0.0;
        for (int j = 0; j < tab_.bi_cols; ++j) w += tab_.BI[i][j] * pw[j];
        acc += w * K_[i][m];
      }
      out[m] = y0_[m] + h_ * acc;
    }
  }

  double dense_component(double s, std::size_t m) const {
    const double theta = (s - t_) / h_;
    double acc = 0.0;
    for (int i = 0; i < tab_.stages; ++i) {
      double w = 0.0;
      double p = theta;
      for (int j = 0; j < tab_.bi_cols; ++j) {
        w += tab_.BI[i][j] * p;
        p *= theta;
      }
      acc += w * K_[i][m];
    }
    return y0_[m] + h_ * acc;
  }

 private:
  const Tableau& tab_;
  OdeProblem& problem_;
  std::size_t n_;
  IntegratorStats& stats_;
  std::array<std::vector<double>, kMaxStages> K_;
  std::vector<double> ytmp_;
  std::vector<double> e_;
  std::vector<double> y0_;
  std::vector<double> ystage_;
  double t_ = 0.0;
  double h_ = 1.0;
};

int sign_of(double v) {
  return (v > 0.0) - (v < 0.0);
}

}  // namespace

IntegratorStats integrate(OdeProblem& problem, std::span<const double> y0, double t0, double t1,
                          const IntegratorOptions& options,
                          const std::function<void(const StepView&)>& observer) {
  const std::size_t n = problem.size();
  options.validate(n);
  if (y0.size() != n) {
    throw InvalidInput(fmt::format("initial state has {} entries, the problem {}", y0.size(), n));
  }
  core::require_finite("start time", t0);
  core::require_finite("end time", t1);
  if (!(t1 > t0)) {
    throw InvalidInput(fmt::format("end time {} must exceed the start time {}",
                                   core::format_value(t1), core::format_value(t0)));
  }
  for (double v : y0) core::require_finite("initial state", v);

  const Tableau& tab = options.method == Method::bogacki_shampine_32 ? kBS23 : kDP54;
  const double rtol = options.rtol;
  std::vector<double> threshold(n);
  for (std::size_t m = 0; m < n; ++m) {
    threshold[m] = (options.atol.size() == 1 ? options.atol[0] : options.atol[m]) / rtol;
  }
  const std::size_t ev = problem.event_state();
  const bool events = ev < n;

  std::vector<double> breaks = problem.breakpoints();
  std::sort(breaks.begin(), breaks.end());
  std::erase_if(breaks, [&](double b) { return !(b > t0 && b < t1); });
  std::size_t next_break = 0;

  IntegratorStats stats;
  Stepper stepper(tab, problem, n, stats);
  std::vector<double> y(y0.begin(), y0.end());
  std::vector<double> f0(n), ynew(n), yev(n);
  problem.rhs(t0, y, f0);
  ++stats.rhs_evaluations;

  const double span = t1 - t0;
  const double hmax = options.max_step > 0.0 ? std::min(options.max_step, span) : 0.1 * span;
  auto hmin_at = [&](double t) {
    return std::max(options.min_step,
                    16.0 * (std::nextafter(std::abs(t), std::numeric_limits<double>::infinity()) -
                            std::abs(t)));
  };
  auto fail = [&](double t, double h, const std::string& why) {
    const std::string stiff =
        stats.stiff_steps > stats.steps / 2 && stats.steps > 0
            ? fmt::format(", {} of them held by stability: the problem is stiff", stats.stiff_steps)
            : std::string();
    throw NumericalError(
        fmt::format("{} integration: {} at t = {:.10g} (step {:.3g}, rtol {:.3g}, atol {:.3g}); "
                    "tried {} steps ({} rejected{}). Loosen the tolerances, or check the "
                    "parameters for a stiff or unbounded response",
                    to_string(options.method), why, t, h, rtol, options.atol.front(), stats.steps,
                    stats.rejected_steps, stiff));
  };

  double t = t0;
  double absh;
  if (options.initial_step > 0.0) {
    absh = std::min(options.initial_step, hmax);
  } else {
    // ode23/ode45's initial step.
    absh = std::min(hmax, span);
    double rh = 0.0;
    for (std::size_t m = 0; m < n; ++m) {
      rh = std::max(rh, std::abs(f0[m]) / std::max(std::abs(y[m]), threshold[m]));
    }
    rh /= 0.8 * std::pow(rtol, tab.pow);
    if (absh * rh > 1.0) absh = 1.0 / rh;
    absh = std::max(absh, hmin_at(t));
  }

  int zero_length_events = 0;
  int stiff_run = 0;  // consecutive steps that failed DOPRI5's stiffness test
  int dir = 0;        // direction of the event state (sign of velocity), 0 before motion
  if (events) dir = sign_of(y[ev]);
  // The rest rule: with a rest state (the displacement, whose rate is the event state),
  // zeros of the event state count as events only once the rest state has moved by
  // more than ten times its absolute tolerance since the last event. Below that the
  // integration does not resolve the motion: a mass that has come to rest dithers at the
  // level of the local error allowed per step (measured: u swinging by 2 atol at the
  // contact's natural frequency for a Jenkins element at rest, |v| ~ atol for a creeping
  // Coulomb contact), and each such "reversal" would commit memory and restart the step.
  const std::size_t rs = problem.event_rest_state();
  const bool rest_rule = events && rs < n;
  const double rest_swing = rest_rule ? 10.0 * threshold[rs] * rtol : 0.0;
  double rest_ref = rest_rule ? y[rs] : 0.0;  // the rest state at the last event
  double swing = 0.0;                         // its largest excursion since then
  // Stepper state of the last attempt, to know whether its continuous extension is the
  // one of the step finally taken.
  double attempted_h = 0.0;

  auto emit = [&](double tp, double tn, bool is_event) {
    if (!observer) return;
    StepView view{tp, tn, y, is_event,
                  [&stepper](double s, std::span<double> out) { stepper.dense(s, out); }};
    observer(view);
  };

  while (t < t1) {
    core::check_interrupt();  // a front end's Ctrl-C (core/interrupt.hpp)
    if (stats.steps >= options.max_steps) {
      fail(t, absh, fmt::format("more than {} steps", options.max_steps));
    }
    const double hmin = hmin_at(t);
    absh = std::min(hmax, std::max(hmin, absh));
    const double stop = next_break < breaks.size() ? breaks[next_break] : t1;
    bool to_stop = false;
    double h = absh;
    if (1.1 * absh >= stop - t) {
      h = stop - t;
      absh = h;
      to_stop = true;
    }
    bool nofailed = true;
    double err = 0.0;
    double tend_eval = t + h;
    for (;;) {
      const double tend = to_stop ? stop : t + h;
      tend_eval = to_stop && stop != t1
                      ? std::nextafter(stop, -std::numeric_limits<double>::infinity())
                      : tend;
      err = stepper.attempt(t, y, f0, h, tend_eval, threshold, ynew);
      attempted_h = h;
      if (err <= rtol) break;
      ++stats.rejected_steps;
      if (absh <= hmin) {
        fail(t, absh,
             std::isfinite(err) ? "the step size collapsed below the smallest allowed"
                                : "the state became non-finite and the step size "
                                  "collapsed");
      }
      if (nofailed && std::isfinite(err)) {
        nofailed = false;
        absh = std::max(hmin,
                        absh * std::max(tab.first_fail_min, 0.8 * std::pow(rtol / err, tab.pow)));
      } else {
        nofailed = false;
        absh = std::max(hmin, 0.5 * absh);
      }
      h = absh;
      to_stop = false;
    }
    const double tnew = to_stop ? stop : t + h;

    // Event search on the continuous extension: the first of kSamples sub-intervals on
    // which dir * v changes sign.
    bool event_found = false;
    double t_event = tnew;
    double sb_event = tnew;  // upper end of the sub-interval holding the crossing
    double v_step = std::abs(y[ev < n ? ev : 0]);
    double swing_step = swing;
    auto track_swing = [&](double s) {  // only until the swing passes the rest threshold
      if (rest_rule && swing_step <= rest_swing) {
        const double x = s == tnew ? ynew[rs] : s == t ? y[rs] : stepper.dense_component(s, rs);
        swing_step = std::max(swing_step, std::abs(x - rest_ref));
      }
    };
    if (events && dir != 0) {
      constexpr int kSamples = 4;
      double sa = t;
      double ga = dir * y[ev];
      for (int j = 1; j <= kSamples; ++j) {
        const double sb = j == kSamples ? tnew : t + (tnew - t) * j / kSamples;
        const double gb = j == kSamples ? dir * ynew[ev] : dir * stepper.dense_component(sb, ev);
        if (gb < 0.0) {
          double te = sa;  // already at (or just past) zero at the start of the bracket
          if (ga > 0.0) {
            te = core::find_root([&](double s) { return dir * stepper.dense_component(s, ev); }, sa,
                                 sb, "event location", 52);
          }
          if (rest_rule) {
            track_swing(te);                      // the excursion up to the zero
            if (swing_step <= rest_swing) break;  // at rest: not a reversal
          }
          event_found = true;
          sb_event = sb;
          t_event = te;
          break;
        }
        v_step = std::max(v_step, std::abs(gb));
        if (rest_rule && j < kSamples) track_swing(sb);
        sa = sb;
        ga = gb;
      }
    }

    // The discrete solution's own zero of v: the step is redone to end where
    // g(he) = dir * v(t + he), the velocity after a step of length he, vanishes. The
    // interpolant's root starts a safeguarded Newton iteration (dg/dhe = dir * v' at
    // the step's end, the FSAL stage) inside a bracket [a, b] with g(a) > 0 >= g(b),
    // bisecting when Newton leaves the bracket or is slow; it stops when |g| is at
    // round-off level (32 eps of the velocity scale of the step) or, failing that, on
    // the b side of a bracket a few ulps wide. The step finally taken is recomputed if
    // it was not the last one attempted, so its state and continuous extension belong
    // together.
    double he = 0.0;
    if (event_found && t_event - t > hmin_at(t)) {
      constexpr double kEps = std::numeric_limits<double>::epsilon();
      const double hfull = tnew - t;
      double g = 0.0, dg = 0.0;
      auto g_at = [&](double hh) {
        const double te = hh == hfull ? tend_eval : t + hh;
        stepper.attempt(t, y, f0, hh, te, threshold, yev);
        attempted_h = hh;
        g = dir * yev[ev];
        dg = dir * stepper.fnew()[ev];
      };
      double a = 0.0, b = std::numeric_limits<double>::quiet_NaN();
      double vscale = std::max(std::abs(y[ev]), v_step);
      auto evaluate = [&](double hh) {  // true when converged at hh
        g_at(hh);
        vscale = std::max(vscale, std::abs(dg) * hfull);
        if (g <= 0.0) {
          b = hh;
        } else {
          a = hh;
        }
        return std::abs(g) <= 32.0 * kEps * vscale;
      };
      double he_try = t_event - t;
      bool done = evaluate(he_try);
      // An upper end of the bracket if the interpolant's root fell short of the zero.
      for (double cand : {sb_event - t, hfull}) {
        if (done || !std::isnan(b) || !(cand > a)) continue;
        he_try = cand;
        done = evaluate(cand);
      }
      if (done) {
        he = he_try;
      } else if (std::isnan(b)) {
        // The interpolant crossed zero but the discrete solution does not reverse on
        // this step (a tangency at tolerance level): no event.
        event_found = false;
      } else {
        he = b;
        for (int it = 0; it < 200; ++it) {
          if (b - a <= 4.0 * kEps * (std::abs(t) + b)) break;
          double c = dg != 0.0 ? he_try - g / dg : a;
          if (!(c > a && c < b) || it >= 8) c = 0.5 * (a + b);
          he_try = c;
          if (evaluate(c)) {
            he = c;
            break;
          }
          he = b;
        }
      }
      if (event_found) {
        if (attempted_h != he) g_at(he);  // the state and extension of the step taken
        y.swap(yev);
        ++stats.steps;
      }
    } else if (event_found) {
      he = 0.0;  // the event is at the start of the step
    }

    if (!event_found) {
      if (attempted_h != tnew - t) {
        stepper.attempt(t, y, f0, tnew - t, tend_eval, threshold, ynew);
        attempted_h = tnew - t;
      }
      // DOPRI5's test with threshold 2.5 rather than Hairer's 3.25: under ode45's step
      // control h |lambda| settles at 2.7-2.9 on a stiff problem (measured, Dankowicz
      // delta = 1e-6 sliding), below the real stability boundary 3.3; a non-stiff step
      // has h |lambda| << 1.
      if (stepper.stability_estimate(ynew) > 2.5) {
        if (++stiff_run >= 15) ++stats.stiff_steps;
      } else {
        stiff_run = 0;
      }
      y.swap(ynew);
      const double tprev = t;
      t = tnew;
      ++stats.steps;
      if (to_stop) {
        if (next_break < breaks.size() && stop == breaks[next_break]) ++next_break;
        problem.rhs(t, y, f0);  // right-hand limit after a breakpoint
        ++stats.rhs_evaluations;
      } else {
        const auto fn = stepper.fnew();
        std::copy(fn.begin(), fn.end(), f0.begin());
      }
      if (events) {
        if (rest_rule) swing = std::max({swing, swing_step, std::abs(y[rs] - rest_ref)});
        const int s = sign_of(y[ev]);
        // Set the direction at the start of motion, and follow the sign of v while the
        // mass is at rest (sign changes below the tolerance are not events).
        if (dir == 0 || (s != 0 && s != dir)) dir = s;
      }
      zero_length_events = 0;
      emit(tprev, t, false);
    } else {
      const double tprev = t;
      t = t + he;
      ++stats.events;
      if (he > 0.0) emit(tprev, t, true);  // before the commit: the step used the old memory
      problem.on_event(t, y);
      dir = -dir;
      if (rest_rule) {
        rest_ref = y[rs];
        swing = 0.0;
      }
      problem.rhs(t, y, f0);  // the memory changed: fresh right-hand side
      ++stats.rhs_evaluations;
      zero_length_events = he > 0.0 ? 0 : zero_length_events + 1;
      if (zero_length_events > 8) fail(t, absh, "velocity reversals repeat without motion");
      continue;  // keep absh: the step size of the rejected long step is still fine
    }

    // Step-size update after a successful step, only if it did not fail first
    // (ode23/ode45: "if there were no failures compute a new h").
    if (nofailed) {
      const double temp = 1.25 * std::pow(err / rtol, tab.pow);
      absh = temp > 0.2 ? absh / temp : 5.0 * absh;
    }
  }
  return stats;
}

}  // namespace asperity::dynamics
