// Joint predictions: the rough flat of chapter 4 at each preload of a case (ch. 5-6).
#include "asperity/joint/predict.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "asperity/contact/material.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/interrupt.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/parallel.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/surface/patched_flat.hpp"

namespace asperity::joint {

double joint_amplitude(const hysteresis::Backbone& b, double imposed, double compliance) {
  if (!(imposed > 0.0) || !std::isfinite(imposed)) {
    throw InvalidInput(fmt::format("imposed amplitude = {:.6g} m must be > 0", imposed));
  }
  if (!(compliance >= 0.0) || !std::isfinite(compliance)) {
    throw InvalidInput(fmt::format("apparatus compliance = {:.6g} m/N must be >= 0", compliance));
  }
  // g(x) = x + c Q_l(x) - imposed rises monotonically from -imposed at 0 to >= 0 at imposed.
  const auto g = [&](double x) { return x + compliance * b.force(x) - imposed; };
  if (g(imposed) <= 0.0) return imposed;
  return core::find_root(g, 0.0, imposed, "joint amplitude under an imposed amplitude");
}

namespace {

// Local exponent n = d ln W / d ln Q_l at x (normalized table), central difference over
// x (1 +- h); empty in gross slip (x at the table's end or beyond), or where Q_l no longer
// grows to rounding.
std::optional<double> local_exponent(const hysteresis::TabulatedBackbone& table, double x) {
  constexpr double h = 1e-3;
  if (!(x > 0.0) || x >= table.table_end()) return std::nullopt;
  // Just below the end of the table the upper point stops there (Q_l = Q_max beyond).
  const double xl = x * (1.0 - h), xh = std::min(x * (1.0 + h), table.table_end());
  const double Ql = table.force(xl), Qh = table.force(xh);
  const double Wl = hysteresis::energy_per_cycle(table, xl);
  const double Wh = hysteresis::energy_per_cycle(table, xh);
  if (!(Qh > Ql) || !(Wl > 0.0) || !(Wh > 0.0)) return std::nullopt;
  const double n = std::log(Wh / Wl) / std::log(Qh / Ql);
  if (!std::isfinite(n)) return std::nullopt;
  return n;
}

// Amplitude rows of a load case on its normalized table (x over sigma, Q over K H A0).
void fill_amplitudes(LoadPrediction& out, const hysteresis::TabulatedBackbone& table, double sigma,
                     double force_scale, const std::vector<double>& amplitudes,
                     const std::vector<double>& imposed, double apparatus_compliance) {
  std::vector<std::pair<double, std::optional<double>>> cases;  // (delta_max, imposed)
  for (double a : amplitudes) cases.emplace_back(a, std::nullopt);
  for (double D : imposed)
    cases.emplace_back(joint_amplitude(*out.backbone, D, apparatus_compliance), D);
  std::stable_sort(cases.begin(), cases.end(),
                   [](const auto& l, const auto& r) { return l.first < r.first; });
  double loaded_area = 0.0;
  for (const auto& p : out.patches) loaded_area += p.patch.area;
  for (const auto& [a, D] : cases) {
    AmplitudePrediction p;
    p.delta_max = a;
    p.imposed = D;
    const double x = a / sigma;
    p.Q_peak = table.force(x) * force_scale;
    // Masing: W = 8 Int Q_l - 4 x Q_l (hysteresis layer), in SI.
    p.energy = hysteresis::energy_per_cycle(table, x) * force_scale * sigma;
    p.Q_ratio = p.Q_peak / out.Q_max;
    p.regime = x >= table.table_end() ? "gross slip" : "partial slip";
    double slipping = 0.0;
    for (const auto& patch : out.patches) {
      const bool gross = a >= patch.gross_slip_amplitude;
      p.patch_gross_slip.push_back(gross ? 1 : 0);
      if (gross) slipping += patch.patch.area;
    }
    p.gross_slip_area_fraction = loaded_area > 0.0 ? slipping / loaded_area : 0.0;
    p.exponent = local_exponent(table, x);
    out.amplitudes.push_back(std::move(p));
  }
}

}  // namespace

LoadPrediction predict_load(const surface::RoughFlat& flat, double preload,
                            const std::vector<double>& amplitudes,
                            const std::vector<double>& imposed, double apparatus_compliance) {
  const auto& s = flat.scales();
  if (!s) throw InvalidInput("predict_load: the rough flat has no dimensional scales");
  LoadPrediction out;
  out.preload = preload;
  out.P_star = preload / s->force;
  if (out.P_star > flat.max_load_star()) {
    throw InvalidInput(fmt::format(
        "preload = {:.6g} N is beyond the model's range (P* = P/(K H A0) = {:.3g} > {:.3g}: the "
        "contact would be nearly complete); lower the preload or enlarge the area",
        preload, out.P_star, flat.max_load_star()));
  }
  out.d_star = flat.separation_star(out.P_star);
  out.separation = out.d_star * s->sigma;
  out.Q_max = flat.static_friction_star(out.d_star) * s->force;
  out.mu = out.Q_max / preload;
  out.stiffness = flat.stiffness_star(out.d_star) * s->force / s->sigma;
  out.interface_stiffness = out.stiffness;
  out.contact_area_ratio = flat.contact_area_ratio(out.d_star);
  out.mean_pressure = preload / s->A0;
  auto table = flat.backbone(out.d_star);
  out.backbone = std::make_shared<hysteresis::ScaledBackbone>(table, s->sigma, s->force);
  // Gross slip: beyond the table's end every asperity slips (Q_l = Q_max to < 1e-12).
  out.gross_slip_amplitude = table->table_end() * s->sigma;
  out.patches.push_back({InterfacePatch{0.0, 0.0, 0.0, 0.0, s->A0, preload}, out.d_star, out.Q_max,
                         out.stiffness, out.gross_slip_amplitude});
  fill_amplitudes(out, *table, s->sigma, s->force, amplitudes, imposed, apparatus_compliance);
  return out;
}

LoadPrediction predict_load(const surface::RoughFlat& flat, double preload,
                            const std::vector<InterfacePatch>& patches,
                            const std::vector<double>& amplitudes,
                            const std::vector<double>& imposed, double apparatus_compliance,
                            double series_compliance) {
  const auto& s = flat.scales();
  if (!s) throw InvalidInput("predict_load: the rough flat has no dimensional scales");
  if (patches.empty()) throw InvalidInput("predict_load: no patch");
  if (!(series_compliance >= 0.0) || !std::isfinite(series_compliance)) {
    throw InvalidInput(
        fmt::format("halves' compliance = {:.6g} m/N must be >= 0", series_compliance));
  }
  LoadPrediction out;
  out.preload = preload;
  out.P_star = preload / s->force;
  out.mean_pressure = preload / s->A0;
  std::vector<surface::FlatPatch> loaded;
  std::vector<InterfacePatch> kept;
  double d_weighted = 0.0, area = 0.0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto& p = patches[i];
    if (!(p.force > 0.0)) continue;  // out of contact
    const double w = p.area / s->A0;
    const double P_star = p.force / (s->force * w);
    const auto where = [&] {
      return fmt::format(
          "patch {} ([{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] mm, {:.4g} N on {:.4g} mm^2, "
          "p = {:.4g} MPa)",
          i + 1, p.x0 * 1e3, p.x1 * 1e3, p.y0 * 1e3, p.y1 * 1e3, p.force, p.area * 1e6,
          p.pressure() * 1e-6);
    };
    if (P_star > flat.max_load_star()) {
      throw InvalidInput(fmt::format(
          "{}: beyond the model's range (P* = {:.3g} > {:.3g}: the contact would be nearly "
          "complete); lower the preload or spread the pressure",
          where(), P_star, flat.max_load_star()));
    }
    if (P_star < 1e-12) {
      throw InvalidInput(fmt::format(
          "{}: P* = {:.3g} is below the model's range (1e-12): a patch so lightly loaded is "
          "out of the statistics of the rough flat; use fewer patches",
          where(), P_star));
    }
    double d = 0.0;
    try {
      d = flat.separation_star(P_star);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: {}", where(), e.what()));
    }
    loaded.push_back({w, d});
    kept.push_back(p);
    d_weighted += p.area * d;
    area += p.area;
    out.contact_area_ratio += w * flat.contact_area_ratio(d);
  }
  if (loaded.empty()) throw InvalidInput("predict_load: no patch carries a normal force");
  auto table = std::make_shared<const surface::PatchedRoughFlatBackbone>(
      flat, loaded, 1e-9, series_compliance * s->force / s->sigma);
  out.halves_compliance = series_compliance;
  out.distinct_patch_sums = table->distinct_sums();
  // Separation: area-weighted mean over the loaded patches (each has its own).
  out.d_star = d_weighted / area;
  out.separation = out.d_star * s->sigma;
  out.Q_max = table->limit() * s->force;
  out.mu = out.Q_max / preload;
  out.stiffness = table->initial_stiffness() * s->force / s->sigma;
  double k_interface = 0.0;
  for (const auto& r : table->responses()) k_interface += r.stiffness_star;
  out.interface_stiffness = k_interface * s->force / s->sigma;
  out.backbone = std::make_shared<hysteresis::ScaledBackbone>(table, s->sigma, s->force);
  out.gross_slip_amplitude = table->table_end() * s->sigma;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const auto& r = table->responses()[i];
    out.patches.push_back({kept[i], loaded[i].d_star, r.static_friction_star * s->force,
                           r.stiffness_star * s->force / s->sigma, r.gross_slip_star * s->sigma});
  }
  fill_amplitudes(out, *table, s->sigma, s->force, amplitudes, imposed, apparatus_compliance);
  return out;
}

namespace {

double case_halves_compliance(const JointCase& c) {
  if (!c.interface.halves) return 0.0;
  return halves_compliance({c.halves[0].material.E, c.halves[1].material.E}, *c.interface.halves);
}

}  // namespace

std::vector<InterfacePatch> case_patches(const JointCase& c, double preload) {
  const double eta = c.combined_roughness().eta();
  return interface_patches(c.interface, c.area, preload, kMinAsperitiesPerPatch / eta);
}

LoadPrediction predict_single_load(const JointCase& c, const std::string& where,
                                   const std::string& consumer) {
  if (c.preloads.size() != 1) {
    throw InvalidInput(
        fmt::format("{}{} one preload; the [load] table gives {} (a sweep): keep one", where,
                    consumer, c.preloads.size()));
  }
  try {
    // Uniform, or the summed backbone of an [interface]'s patches (joint/interface.hpp).
    return predict_case_load(c, c.preloads.front());
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}{}", where, e.what()));
  }
}

namespace {

// Amplitude rows under the Odfalk-Vingsbo law (hysteresis::odfalk_vingsbo_cycle): the force
// amplitude and energy of its steady cycle; the regime and the slip map from the elastic
// amplitude (the interface's own slip; the plastic slip is in series with all of it).
void fill_odfalk_vingsbo_amplitudes(LoadPrediction& out,
                                    const hysteresis::OdfalkVingsboParameters& p,
                                    const std::vector<double>& amplitudes,
                                    const std::vector<double>& imposed,
                                    double apparatus_compliance) {
  out.odfalk_vingsbo = p;
  const auto& b = *out.backbone;
  std::vector<std::pair<double, std::optional<double>>> cases;  // (delta_max, imposed)
  for (double a : amplitudes) cases.emplace_back(a, std::nullopt);
  for (double D : imposed) {
    if (!(D > 0.0) || !std::isfinite(D))
      throw InvalidInput(fmt::format("imposed amplitude = {:.6g} m must be > 0", D));
    // delta + c Q_m(delta) = D, rising in delta.
    const auto g = [&](double x) {
      return x + apparatus_compliance * hysteresis::odfalk_vingsbo_cycle(b, p, x).Q_m - D;
    };
    cases.emplace_back(g(D) <= 0.0 ? D : core::find_root(g, 0.0, D, "joint amplitude"), D);
  }
  std::stable_sort(cases.begin(), cases.end(),
                   [](const auto& l, const auto& r) { return l.first < r.first; });
  double loaded_area = 0.0;
  for (const auto& patch : out.patches) loaded_area += patch.patch.area;
  for (const auto& [a, D] : cases) {
    const auto cycle = hysteresis::odfalk_vingsbo_cycle(b, p, a);
    AmplitudePrediction r;
    r.delta_max = a;
    r.imposed = D;
    r.Q_peak = cycle.Q_m;
    r.energy = cycle.energy;
    r.Q_ratio = cycle.Q_m / out.Q_max;
    const bool gross = cycle.elastic_amplitude >= out.gross_slip_amplitude;
    r.regime = gross ? "gross slip" : "partial slip";
    double slipping = 0.0;
    for (const auto& patch : out.patches) {
      const bool g = cycle.elastic_amplitude >= patch.gross_slip_amplitude;
      r.patch_gross_slip.push_back(g ? 1 : 0);
      if (g) slipping += patch.patch.area;
    }
    r.gross_slip_area_fraction = loaded_area > 0.0 ? slipping / loaded_area : 0.0;
    if (!gross && a > 0.0) {
      // n = d ln W / d ln Q_m, central difference over delta_max (1 +- 1e-3) as local_exponent.
      const auto lo = hysteresis::odfalk_vingsbo_cycle(b, p, a * (1.0 - 1e-3));
      const auto hi = hysteresis::odfalk_vingsbo_cycle(b, p, a * (1.0 + 1e-3));
      if (hi.Q_m > lo.Q_m && lo.energy > 0.0 && hi.energy > 0.0) {
        const double n = std::log(hi.energy / lo.energy) / std::log(hi.Q_m / lo.Q_m);
        if (std::isfinite(n)) r.exponent = n;
      }
    }
    out.amplitudes.push_back(std::move(r));
  }
}

// One load case of `c` on its rough flat (uniform or patched), with its tangential law.
LoadPrediction case_load(const JointCase& c, const surface::RoughFlat& flat, double preload,
                         const std::vector<double>& amplitudes,
                         const std::vector<double>& imposed) {
  const auto& ov = c.interface.odfalk_vingsbo;
  const std::vector<double> none;
  const auto& A = ov ? none : amplitudes;
  const auto& D = ov ? none : imposed;
  LoadPrediction lp = c.interface.is_default()
                          ? predict_load(flat, preload, A, D, c.apparatus.compliance())
                          : predict_load(flat, preload, case_patches(c, preload), A, D,
                                         c.apparatus.compliance(), case_halves_compliance(c));
  if (ov) fill_odfalk_vingsbo_amplitudes(lp, *ov, amplitudes, imposed, c.apparatus.compliance());
  return lp;
}

}  // namespace

LoadPrediction predict_case_load(const JointCase& c, double preload,
                                 const std::vector<double>& amplitudes,
                                 const std::vector<double>& imposed) {
  return case_load(c, c.rough_flat(), preload, amplitudes, imposed);
}

JointPrediction predict(const JointCase& c,
                        const std::function<void(std::size_t, std::size_t)>& progress) {
  c.validate();
  const auto flat = c.rough_flat();
  JointPrediction out;
  out.combined = c.combined_roughness();
  out.sigma = out.combined.sigma();
  out.eta = out.combined.eta();
  out.R = out.combined.R();
  out.beta = flat.parameters().beta;
  out.psi = flat.parameters().psi;
  out.force_scale = flat.scales()->force;
  out.warnings = flat.warnings();
  for (auto& w : contact::hardness_warnings(flat.scales()->pair.H, flat.scales()->pair.E_star))
    out.warnings.push_back(std::move(w));
  // The load cases are independent: one per thread (core::parallel_for), each into its
  // own slot, so the result does not depend on the number of threads.
  const std::size_t n = c.preloads.size();
  std::vector<LoadPrediction> loads(n);
  std::mutex progress_mutex;
  std::size_t done = 0;
  core::parallel_for(n, [&](std::size_t i) {
    core::check_interrupt();
    LoadPrediction lp;
    try {
      lp = case_load(c, flat, c.preloads[i], c.amplitudes, c.imposed);
    } catch (const InvalidInput& e) {
      // Name where this load case came from (file, line, key).
      if (i < c.preload_origin.size())
        throw InvalidInput(fmt::format("{}: {}", c.preload_origin[i], e.what()));
      throw;
    }
    if (c.bolts && i < c.bolts->torques.size()) lp.torque = c.bolts->torques[i];
    loads[i] = std::move(lp);
    if (progress) {
      const std::lock_guard lock(progress_mutex);
      progress(++done, n);
    }
  });
  out.loads = std::move(loads);
  // In the order of the preloads, whatever the threads' order.
  for (const auto& lp : out.loads) {
    if (auto w = surface::friction_coefficient_warning(lp.mu); !w.empty())
      out.warnings.push_back(fmt::format("at {:.5g} N: {}", lp.preload, w));
  }
  return out;
}

std::pair<std::vector<double>, std::vector<double>> steady_loop(const LoadPrediction& load,
                                                                double delta_max, std::size_t n) {
  if (!load.odfalk_vingsbo) return steady_loop(*load.backbone, delta_max, n);
  if (!(delta_max > 0.0)) throw InvalidInput("steady_loop: delta_max must be > 0");
  if (n < 2) n = 2;
  hysteresis::OdfalkVingsboHysteresis h(load.backbone, *load.odfalk_vingsbo);
  // Virgin loading to delta_max, then the loop from there (symmetric from the first reversal).
  for (std::size_t i = 1; i <= n; ++i)
    h.update(delta_max * static_cast<double>(i) / static_cast<double>(n));
  std::vector<double> x{delta_max}, Q{h.Q()};
  for (const auto& [a, b] : {std::pair{delta_max, -delta_max}, std::pair{-delta_max, delta_max}}) {
    for (std::size_t i = 1; i <= n; ++i) {
      const double xi = a + (b - a) * static_cast<double>(i) / static_cast<double>(n);
      x.push_back(xi);
      Q.push_back(h.update(xi));
    }
  }
  return {x, Q};
}

std::pair<std::vector<double>, std::vector<double>> steady_loop(const hysteresis::Backbone& b,
                                                                double delta_max, std::size_t n) {
  if (!(delta_max > 0.0)) throw InvalidInput("steady_loop: delta_max must be > 0");
  if (n < 2) n = 2;
  const double Qm = b.force(delta_max);
  std::vector<double> x, Q;
  x.reserve(2 * n + 1);
  Q.reserve(2 * n + 1);
  for (std::size_t i = 0; i <= n; ++i) {  // unloading: Q_m - 2 Q_l((x_m - x)/2)
    const double xi = delta_max - 2.0 * delta_max * static_cast<double>(i) / static_cast<double>(n);
    x.push_back(xi);
    Q.push_back(Qm - 2.0 * b.force((delta_max - xi) / 2.0));
  }
  for (std::size_t i = 1; i <= n; ++i) {  // reloading: -Q_m + 2 Q_l((x + x_m)/2)
    const double xi =
        -delta_max + 2.0 * delta_max * static_cast<double>(i) / static_cast<double>(n);
    x.push_back(xi);
    Q.push_back(-Qm + 2.0 * b.force((xi + delta_max) / 2.0));
  }
  return {x, Q};
}

}  // namespace asperity::joint
