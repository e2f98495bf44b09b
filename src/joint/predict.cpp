// Joint predictions: the rough flat of chapter 4 at each preload of a case (ch. 5-6).
#include "asperity/joint/predict.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/parallel.hpp"
#include "asperity/hysteresis/backbones.hpp"

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
  out.contact_area_ratio = flat.contact_area_ratio(out.d_star);
  out.mean_pressure = preload / s->A0;
  auto table = flat.backbone(out.d_star);
  out.backbone = std::make_shared<hysteresis::ScaledBackbone>(table, s->sigma, s->force);
  // Gross slip: beyond the table's end every asperity slips (Q_l = Q_max to < 1e-12).
  out.gross_slip_amplitude = table->table_end() * s->sigma;
  std::vector<std::pair<double, std::optional<double>>> cases;  // (delta_max, imposed)
  for (double a : amplitudes) cases.emplace_back(a, std::nullopt);
  for (double D : imposed)
    cases.emplace_back(joint_amplitude(*out.backbone, D, apparatus_compliance), D);
  std::stable_sort(cases.begin(), cases.end(),
                   [](const auto& l, const auto& r) { return l.first < r.first; });
  for (const auto& [a, D] : cases) {
    AmplitudePrediction p;
    p.delta_max = a;
    p.imposed = D;
    const double x = a / s->sigma;
    p.Q_peak = table->force(x) * s->force;
    // Masing: W = 8 Int Q_l - 4 x Q_l (hysteresis layer), in SI.
    p.energy = hysteresis::energy_per_cycle(*table, x) * s->force * s->sigma;
    p.Q_ratio = p.Q_peak / out.Q_max;
    p.regime = x >= table->table_end() ? "gross slip" : "partial slip";
    out.amplitudes.push_back(p);
  }
  return out;
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
  // The load cases are independent: one per thread (core::parallel_for), each into its
  // own slot, so the result does not depend on the number of threads.
  const std::size_t n = c.preloads.size();
  std::vector<LoadPrediction> loads(n);
  std::mutex progress_mutex;
  std::size_t done = 0;
  core::parallel_for(n, [&](std::size_t i) {
    LoadPrediction lp;
    try {
      lp = predict_load(flat, c.preloads[i], c.amplitudes, c.imposed, c.apparatus.compliance());
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
  return out;
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
