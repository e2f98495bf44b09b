#include "asperity/dynamics/case.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include "asperity/core/error.hpp"
#include "case_parse.hpp"

namespace asperity::dynamics {

const SummaryValue* SummaryValue::find(const std::string& key) const {
  const auto* o = std::get_if<SummaryObject>(&data);
  if (!o) return nullptr;
  for (const auto& [k, v] : *o) {
    if (k == key) return &v;
  }
  return nullptr;
}

namespace {

using detail::time_scale;

}  // namespace

double expected_steps(const DynamicsCase& c) {
  const auto* h = std::get_if<HarmonicExcitation>(&c.excitation);
  return h ? kStepsPerPeriod * h->frequency * c.simulation.duration : 0.0;
}

std::string expected_cost_warning(const DynamicsCase& c) {
  const double steps = expected_steps(c);
  const auto* h = std::get_if<HarmonicExcitation>(&c.excitation);
  if (!h) return {};
  const double periods = h->frequency * c.simulation.duration;
  const auto max_steps = static_cast<double>(c.simulation.integrator.max_steps);
  if (steps > max_steps) {
    throw InvalidInput(fmt::format(
        "{}: dynamics.harmonic.frequency = {:.6g} over duration = {:.6g} is {:.3g} forcing "
        "periods, about {:.3g} integration steps ({:.0f} a period), above the integrator's "
        "max_steps = {:.3g}: lower the frequency or the duration (both in tau = sqrt(k/m) t)",
        c.source, h->frequency, c.simulation.duration, periods, steps, kStepsPerPeriod, max_steps));
  }
  if (steps > 1e7) {
    // About 3e5 steps a second on one core (the measurement of kStepsPerPeriod: 0.06 s).
    return fmt::format(
        "dynamics.harmonic.frequency = {:.6g} over duration = {:.6g} is {:.3g} forcing periods: "
        "expect about {:.3g} integration steps, roughly {:.0f} s or more",
        h->frequency, c.simulation.duration, periods, steps, steps / 3e5);
  }
  return {};
}

CaseResult run_case(const DynamicsCase& c, const RunOptions& options) {
  CaseResult r;
  if (auto w = expected_cost_warning(c); !w.empty()) r.warnings.push_back(std::move(w));
  SimulationOptions sim_run = c.simulation;
  sim_run.sink = options.sink;
  if (const auto* h = std::get_if<HarmonicExcitation>(&c.excitation); h && options.summary_only) {
    // steady_loop() reads the last loop_cycles periods; one more is kept to spare.
    sim_run.record_from =
        std::max(0.0, c.simulation.duration - (c.analysis.loop_cycles + 1.0) / h->frequency);
  }
  const Trajectory& tr = r.trajectory = simulate(c.system, c.excitation, *c.friction, sim_run);
  const SimulationOptions& sim = c.simulation;
  const double rtol = sim.integrator.rtol;
  SummaryObject& j = r.summary;
  const CaseScales& sc = c.scales;
  const bool decays = c.excitation_name == "impulse" || c.excitation_name == "free";

  j.emplace_back("case", c.source);
  j.emplace_back("excitation", c.excitation_name);
  j.emplace_back("excitation_parameters",
                 std::visit(
                     [](const auto& e) -> SummaryObject {
                       using T = std::decay_t<decltype(e)>;
                       if constexpr (std::is_same_v<T, ImpulseExcitation>) {
                         return {{"Omega", e.Omega}, {"amplitude", e.amplitude}};
                       } else if constexpr (std::is_same_v<T, RampExcitation>) {
                         return {{"alpha", e.alpha}};
                       } else if constexpr (std::is_same_v<T, HarmonicExcitation>) {
                         return {{"frequency", e.frequency}, {"amplitude", e.amplitude}};
                       } else {
                         return {};
                       }
                     },
                     c.excitation));
  j.emplace_back("friction_model", tr.friction_model);
  j.emplace_back("epsilon", c.system.epsilon);
  j.emplace_back("method", to_string(sim.integrator.method));
  j.emplace_back("rtol", rtol);
  {
    SummaryArray atol;
    for (double a : sim.integrator.atol) atol.emplace_back(a);
    j.emplace_back("atol", std::move(atol));
  }
  j.emplace_back("duration", sim.duration);
  {
    SummaryObject s;
    if (sc.m) s.emplace_back("mass_kg", *sc.m);
    if (sc.k) s.emplace_back("stiffness_N_per_m", *sc.k);
    if (sc.A) s.emplace_back("amplitude_m", *sc.A);
    if (sc.m && sc.k) s.emplace_back("time_s", time_scale(sc));
    if (sc.k && sc.A) s.emplace_back("force_N", *sc.k * *sc.A);
    j.emplace_back("scales", std::move(s));
  }

  // The friction section, with the Dankowicz state's overshoot of |z| <= delta.
  SummaryObject friction = c.friction_summary;
  if (const auto* dk = dynamic_cast<const Dankowicz*>(c.friction.get())) {
    const double zmax = tr.max_abs_internal.at(0);
    const double overshoot = zmax / dk->parameters().delta - 1.0;
    friction.emplace_back("max_abs_z_over_delta", zmax / dk->parameters().delta);
    if (overshoot > 100.0 * rtol) {
      r.warnings.push_back(fmt::format(
          "the Dankowicz state overshoots its bound: max |z|/delta = 1 + {:.3g} (exact: <= 1; "
          "more than 100 rtol): the integration does not resolve z (tighten rtol or the "
          "internal state's atol)",
          overshoot));
    }
  }
  j.emplace_back("friction", std::move(friction));

  // Modal frequency and half-power damping from the spectrum of the displacement.
  std::optional<ModalEstimate> modal;
  std::string spectrum_note;
  const double dt = sim.output_interval;
  const double tau0 = std::holds_alternative<ImpulseExcitation>(c.excitation)
                          ? std::numbers::pi / std::get<ImpulseExcitation>(c.excitation).Omega
                          : 0.0;
  if (decays) {
    const Periodogram p(uniform_samples(tr, dt), dt);
    const double f_max = c.analysis.f_max > 0.0 ? c.analysis.f_max : std::min(0.5 / dt, 10.0);
    const double f_min = c.analysis.f_min > 0.0 ? c.analysis.f_min : 2.0 / sim.duration;
    r.spectrum = power_spectrum(p, f_min, f_max, c.analysis.bins);
    const bool moves = std::any_of(tr.u.begin(), tr.u.end(), [](double u) { return u != 0.0; });
    if (!moves) {
      spectrum_note = "the mass does not move (zero excitation and initial state): no modal peak";
    } else {
      try {
        modal = modal_estimate(p, f_min, f_max, c.analysis.bins);
      } catch (const NumericalError& e) {
        spectrum_note = e.what();  // an overdamped response has no modal peak: report null
      }
    }
  }
  auto or_null = [](const std::optional<double>& v) {
    return v ? SummaryValue(*v) : SummaryValue(nullptr);
  };
  j.emplace_back("modal_frequency",
                 or_null(modal ? std::optional(modal->frequency) : std::nullopt));
  j.emplace_back("modal_damping",
                 or_null(modal ? std::optional(modal->damping_ratio) : std::nullopt));
  if (modal) {
    j.emplace_back("modal_frequency_undamped", std::isfinite(modal->undamped_frequency)
                                                   ? SummaryValue(modal->undamped_frequency)
                                                   : SummaryValue(nullptr));
    j.emplace_back(
        "modal_note",
        "modal_frequency is the peak of the displacement power spectrum (cycles per unit tau), "
        "the damped peak: a viscously damped mode peaks at f_n sqrt(1 - 2 zeta^2). "
        "modal_frequency_undamped = modal_frequency/sqrt(1 - 2 modal_damping^2) estimates f_n; "
        "modal_damping is the half-power bandwidth (f_high - f_low)/(2 modal_frequency) of the "
        "whole record, dominated by its small-amplitude tail when the damping depends on "
        "amplitude (see free_decay for cycle-by-cycle values)");
    j.emplace_back("modal_half_power", SummaryObject{{"f_low", modal->f_low},
                                                     {"f_high", modal->f_high},
                                                     {"peak_power", modal->peak_power}});
    if (sc.m && sc.k) {
      j.emplace_back("modal_frequency_hz", modal->frequency / time_scale(sc));
      if (std::isfinite(modal->undamped_frequency))
        j.emplace_back("modal_frequency_undamped_hz", modal->undamped_frequency / time_scale(sc));
    }
  } else if (!spectrum_note.empty()) {
    j.emplace_back("modal_note", spectrum_note);
  }

  if (c.joint) j.emplace_back("joint", *c.joint);
  const double eb = tr.energy_balance_error();
  j.emplace_back("energy_balance_error", eb);
  if (eb > 100.0 * rtol) {
    r.warnings.push_back(fmt::format(
        "energy balance error {:.3g} of the input work exceeds 100 rtol = {:.3g}: the integration "
        "is not accurate to its tolerance (tighten rtol/atol, or check for a stiff contact)",
        eb, 100.0 * rtol));
  }
  j.emplace_back("energy",
                 SummaryObject{{"work_base", tr.work_base.back()},
                               {"dissipated_damper", tr.dissipated_damper.back()},
                               {"work_friction", tr.work_friction.back()},
                               {"mechanical_energy_change", tr.energy.back() - tr.initial_energy}});
  if (sc.k && sc.A) j.emplace_back("energy_scale_J", *sc.k * *sc.A * *sc.A);
  j.emplace_back("steps", tr.stats.steps);
  j.emplace_back("rejected_steps", tr.stats.rejected_steps);
  j.emplace_back("rhs_evaluations", tr.stats.rhs_evaluations);
  j.emplace_back("force_evaluations", tr.force_evaluations);
  j.emplace_back("events", tr.stats.events);
  j.emplace_back("stiff_steps", tr.stats.stiff_steps);
  // Stiffness (IntegratorStats::stiff_steps): worth a warning when it makes the run
  // expensive, more than 1e5 steps held by stability and most of the run. (A tanh
  // Coulomb creep is mildly stiff too, F_max k_tan = 9.5, but over ~1000 steps.)
  if (tr.stats.stiff_steps > 100'000 &&
      static_cast<double>(tr.stats.stiff_steps) > 0.5 * static_cast<double>(tr.stats.steps)) {
    std::string example = "e.g. a Dankowicz contact with F_max/delta >> 1 while it slides";
    if (const auto* dk = dynamic_cast<const Dankowicz*>(c.friction.get())) {
      example = fmt::format("here Dankowicz F_max/delta = {:.3g} while it slides",
                            dk->parameters().F_max / dk->parameters().delta);
    }
    r.warnings.push_back(fmt::format(
        "{} of {} steps were held by stability rather than accuracy (Dormand-Prince stiffness "
        "test): the problem is stiff ({}); the explicit integrator stays accurate but is slow",
        tr.stats.stiff_steps, tr.stats.steps, example));
  } else if (tr.stats.steps > 100'000 && static_cast<double>(tr.stats.rejected_steps) >
                                             0.2 * static_cast<double>(tr.stats.steps)) {
    // Frequent rejections reset the stiffness test's run of 15 steps: a stiff or
    // under-resolved problem can show up only here (Dankowicz delta = 1e-9 A: 2.5e6 steps,
    // 6.3e5 rejected, no stiff step counted).
    r.warnings.push_back(fmt::format(
        "{} of {} steps were rejected: the step size is held by stability or by a motion "
        "smaller than the absolute tolerance (the problem may be stiff, e.g. a Dankowicz "
        "delta far below the amplitude); results below atol are noise",
        tr.stats.rejected_steps, tr.stats.steps));
  }

  if (decays) {
    const auto decay =
        free_decay(tr, c.analysis.decay_start >= 0.0 ? c.analysis.decay_start : tau0);
    SummaryArray jd;
    for (const auto& p : decay) {
      jd.emplace_back(SummaryObject{{"tau", p.tau},
                                    {"amplitude", p.amplitude},
                                    {"frequency", p.frequency},
                                    {"damping_ratio", p.damping_ratio}});
    }
    j.emplace_back("free_decay",
                   SummaryObject{{"method",
                                  "logarithmic decrement over full cycles of successive "
                                  "swings"},
                                 {"cycles", std::move(jd)}});
  }
  if (const auto* ramp = std::get_if<RampExcitation>(&c.excitation)) {
    const double thr = c.analysis.stick_velocity * std::abs(ramp->alpha);
    const auto iv = stick_slip_intervals(tr, thr);
    SummaryArray ji;
    for (const auto& i : iv) {
      ji.emplace_back(
          SummaryObject{{"begin", i.begin}, {"end", i.end}, {"state", i.stick ? "stick" : "slip"}});
    }
    j.emplace_back("stick_slip",
                   SummaryObject{{"velocity_threshold", thr}, {"intervals", std::move(ji)}});
    j.emplace_back("first_slip",
                   iv.size() > 1 && iv[0].stick ? SummaryValue(iv[0].end) : SummaryValue(nullptr));
  }
  if (const auto* h = std::get_if<HarmonicExcitation>(&c.excitation)) {
    const double period = 1.0 / h->frequency;
    if (sim.duration >= (c.analysis.loop_cycles + 1) * period) {
      const auto loop = steady_loop(tr, period, c.analysis.loop_cycles);
      j.emplace_back("steady_loop",
                     SummaryObject{{"cycles", c.analysis.loop_cycles},
                                   {"energy_per_cycle", loop.energy_per_cycle},
                                   {"displacement_amplitude", loop.displacement_amplitude},
                                   {"displacement_amplitude_over_base",
                                    loop.displacement_amplitude / std::abs(h->amplitude)},
                                   {"force_amplitude", loop.force_amplitude},
                                   {"mean_displacement", loop.mean_displacement}});
    } else {
      // The analysis asked for cannot be done: say so instead of leaving it out.
      r.warnings.push_back(fmt::format(
          "steady_loop is left out: loop_cycles = {} needs the run to last (loop_cycles + 1) = {} "
          "excitation periods, tau = {:.6g}, but duration = {:.6g} ({:.3g} periods); lengthen "
          "duration or lower [dynamics.analysis] loop_cycles",
          c.analysis.loop_cycles, c.analysis.loop_cycles + 1, (c.analysis.loop_cycles + 1) * period,
          sim.duration, sim.duration / period));
    }
  }
  SummaryArray w;
  for (const auto& s : r.warnings) w.emplace_back(s);
  j.emplace_back("warnings", std::move(w));
  return r;
}

std::vector<Column> time_history_columns(const DynamicsCase& c, const Trajectory& tr) {
  std::vector<Column> cols;
  cols.push_back({"tau", tr.tau});
  cols.push_back({"u", tr.u});
  cols.push_back({"v", tr.v});
  cols.push_back({"y", tr.y});
  cols.push_back({"friction", tr.friction});
  for (std::size_t i = 0; i < tr.internal.size(); ++i) {
    cols.push_back(
        {tr.internal.size() == 1 ? std::string("z") : fmt::format("z{}", i + 1), tr.internal[i]});
  }
  cols.push_back({"work_base", tr.work_base});
  cols.push_back({"dissipated_damper", tr.dissipated_damper});
  cols.push_back({"work_friction", tr.work_friction});
  cols.push_back({"energy", tr.energy});
  cols.push_back({"event", std::vector<double>(tr.is_event.begin(), tr.is_event.end())});
  const CaseScales& s = c.scales;
  auto scaled = [&](const std::vector<double>& x, double f) {
    std::vector<double> out(x.size());
    std::transform(x.begin(), x.end(), out.begin(), [f](double v) { return v * f; });
    return out;
  };
  if (s.m && s.k) cols.push_back({"t[s]", scaled(tr.tau, time_scale(s))});
  if (s.A) cols.push_back({"x[m]", scaled(tr.u, *s.A)});
  if (s.complete()) cols.push_back({"xdot[m/s]", scaled(tr.v, *s.A / time_scale(s))});
  if (s.A) cols.push_back({"base[m]", scaled(tr.y, *s.A)});
  if (s.k && s.A) cols.push_back({"f_s[N]", scaled(tr.friction, *s.k * *s.A)});
  return cols;
}

std::vector<std::string> time_history_names(const DynamicsCase& c) {
  std::vector<std::string> names{"tau", "u", "v", "y", "friction"};
  const std::size_t nz = c.friction->internal_states();
  for (std::size_t i = 0; i < nz; ++i) {
    names.push_back(nz == 1 ? std::string("z") : fmt::format("z{}", i + 1));
  }
  for (const char* n : {"work_base", "dissipated_damper", "work_friction", "energy", "event"}) {
    names.emplace_back(n);
  }
  const CaseScales& s = c.scales;
  if (s.m && s.k) names.emplace_back("t[s]");
  if (s.A) names.emplace_back("x[m]");
  if (s.complete()) names.emplace_back("xdot[m/s]");
  if (s.A) names.emplace_back("base[m]");
  if (s.k && s.A) names.emplace_back("f_s[N]");
  return names;
}

void time_history_row(const DynamicsCase& c, const TrajectorySample& x, std::vector<double>& row) {
  row.assign({x.tau, x.u, x.v, x.y, x.friction});
  row.insert(row.end(), x.internal.begin(), x.internal.end());
  row.insert(row.end(),
             {x.work_base, x.dissipated_damper, x.work_friction, x.energy, x.is_event ? 1.0 : 0.0});
  const CaseScales& s = c.scales;
  if (s.m && s.k) row.push_back(x.tau * time_scale(s));
  if (s.A) row.push_back(x.u * *s.A);
  if (s.complete()) row.push_back(x.v * (*s.A / time_scale(s)));
  if (s.A) row.push_back(x.y * *s.A);
  if (s.k && s.A) row.push_back(x.friction * (*s.k * *s.A));
}

}  // namespace asperity::dynamics
