#include "asperity/dynamics/integrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "asperity/core/error.hpp"
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
      if (i == s - 1) ynew = ytmp_;  // FSAL: the last stage is at the new point
    }
    double err = 0.0;
    for (std::size_t m = 0; m < n_; ++m) {
      double e = 0.0;
      for (int j = 0; j < s; ++j) e += tab_.E[j] * K_[j][m];
      e *= h;
      if (!std::isfinite(ynew[m]) || !std::isfinite(e)) finite = false;
      const double wt = std::max({std::abs(y[m]), std::abs(ynew[m]), threshold[m]});
      err = std::max(err, std::abs(e) / wt);
    }
    if (!finite) return std::numeric_limits<double>::infinity();
    return err;
  }

  [[nodiscard]] std::span<const double> fnew() const { return K_[tab_.stages - 1]; }

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
    throw NumericalError(
        fmt::format("{} integration: {} at t = {:.10g} (step {:.3g}, rtol {:.3g}, atol {:.3g}); "
                    "tried {} steps ({} rejected). Loosen the tolerances, or check the parameters "
                    "for a stiff or unbounded response",
                    to_string(options.method), why, t, h, rtol, options.atol.front(), stats.steps,
                    stats.rejected_steps));
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
  int dir = 0;  // direction of the event state (sign of velocity), 0 before motion
  if (events) dir = sign_of(y[ev]);

  auto emit = [&](double tp, double tn, bool is_event) {
    if (!observer) return;
    StepView view{tp, tn, y, is_event,
                  [&stepper](double s, std::span<double> out) { stepper.dense(s, out); }};
    observer(view);
  };

  while (t < t1) {
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
    for (;;) {
      const double tend = to_stop ? stop : t + h;
      const double tend_eval = to_stop && stop != t1
                                   ? std::nextafter(stop, -std::numeric_limits<double>::infinity())
                                   : tend;
      err = stepper.attempt(t, y, f0, h, tend_eval, threshold, ynew);
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

    // Event search on the continuous extension.
    bool event_found = false;
    double t_event = tnew;
    if (events && dir != 0) {
      constexpr int kSamples = 4;
      double sa = t;
      double ga = dir * y[ev];
      for (int j = 1; j <= kSamples; ++j) {
        const double sb = j == kSamples ? tnew : t + (tnew - t) * j / kSamples;
        const double gb = j == kSamples ? dir * ynew[ev] : dir * stepper.dense_component(sb, ev);
        if (gb < 0.0) {
          event_found = true;
          if (ga <= 0.0) {
            t_event = sa;  // already at (or just past) zero at the start of the bracket
          } else {
            t_event =
                core::find_root([&](double s) { return dir * stepper.dense_component(s, ev); }, sa,
                                sb, "event location", 52);
          }
          break;
        }
        sa = sb;
        ga = gb;
      }
    }

    if (!event_found) {
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
      if (events && dir == 0) dir = sign_of(y[ev]);
      zero_length_events = 0;
      emit(tprev, t, false);
    } else {
      // Redo the step to end on the event, then Newton-correct its length until the
      // event state is zero to round-off.
      double he = t_event - t;
      const double hmin_e = hmin_at(t);
      if (he > hmin_e) {
        for (int it = 0; it < 6; ++it) {
          stepper.attempt(t, y, f0, he, t + he, threshold, yev);
          const double g = yev[ev];
          const double dg = stepper.fnew()[ev];
          if (g == 0.0 || !(dg != 0.0)) break;
          const double dh = -g / dg;
          const double he_new = std::clamp(he + dh, 0.5 * he, std::min(h, 1.5 * he));
          if (std::abs(he_new - he) <=
              4.0 * std::numeric_limits<double>::epsilon() * (std::abs(t) + he)) {
            break;
          }
          he = he_new;
        }
        y.swap(yev);
        ++stats.steps;
      } else {
        he = 0.0;  // the event is at the start of the step
      }
      const double tprev = t;
      t = t + he;
      ++stats.events;
      if (he > 0.0) emit(tprev, t, true);  // before the commit: the step used the old memory
      problem.on_event(t, y);
      dir = -dir;
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
