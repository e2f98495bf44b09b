// asperity sphere: one asperity (a sphere on a flat) with the four physics-based
// partial slip models of chapter 3.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

using contact::ModelName;
using core::Dimension;
namespace dim = core::dim;

namespace {

struct SphereOptions {
  MaterialOptions materials;
  std::optional<std::string> R1, R2;
  std::optional<std::string> P, omega_star, delta_max, Q_max;
  std::optional<std::string> mu_cfc, zeta;
  std::string model = "all";
  bool json = false;
  std::optional<std::string> loop_csv, plot_png, energy_csv;
  std::size_t points = 101;
};

double dimensionless(const std::optional<std::string>& text, const std::string& flag) {
  return required_quantity(text, dim::dimensionless, flag);
}

struct ModelResult {
  contact::PartialSlipModel model;
  std::optional<double> delta_max;  // amplitude applied or reached
  std::optional<double> Q_at_delta_max;
  std::optional<double> energy;
  std::optional<contact::SlipRegime> regime;
};

Json opt(const std::optional<double>& v) {
  return v ? Json(*v) : Json(nullptr);
}

void run_sphere(const SphereOptions& o, std::string& out) {
  const auto [b1, b2] = o.materials.parse();
  const double R1 = required_quantity(o.R1, dim::length, "--R1");
  const double R2 =
      o.R2 ? required_quantity(o.R2, dim::length, "--R2") : std::numeric_limits<double>::infinity();
  core::require_positive("--R1", R1);
  if (o.R2) core::require_positive("--R2", R2);
  const auto pair = contact::ContactPair::combine(b1, b2, R1, R2);

  std::vector<ModelName> models;
  if (o.model == "all") {
    models.assign(contact::kAllModels.begin(), contact::kAllModels.end());
  } else {
    try {
      models.push_back(contact::parse_model_name(o.model));
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("--model: {} (or all)", e.what()));
    }
  }
  contact::FrictionParameters params;
  const bool wants_cfc = std::find(models.begin(), models.end(), ModelName::cfc) != models.end();
  if (o.mu_cfc) {
    params.mu_cfc = dimensionless(o.mu_cfc, "--mu-cfc");
    core::require_positive("--mu-cfc", params.mu_cfc);
  } else if (wants_cfc) {
    throw InvalidInput(
        "the cfc model needs its friction coefficient: give --mu-cfc (s/H of the softer "
        "material, e.g. 0.284), or choose another --model");
  }
  if (o.zeta) {
    params.zeta = dimensionless(o.zeta, "--zeta");
    core::require_positive("--zeta", params.zeta);
  }
  params.validate();

  if (o.P && o.omega_star) throw InvalidInput("give either --P or --omega-star, not both");
  if (!o.P && !o.omega_star)
    throw InvalidInput("the normal load is required: give --P or --omega-star");
  if (o.delta_max && o.Q_max) throw InvalidInput("give either --delta-max or --Q-max, not both");
  const double P = o.P ? required_quantity(o.P, dim::force, "--P") : 0.0;
  const double w = o.omega_star ? dimensionless(o.omega_star, "--omega-star") : 0.0;
  if (o.P && !(P > 0.0)) {
    throw InvalidInput(fmt::format("--P = {} N is not allowed: the normal load must be > 0", P));
  }
  if (o.omega_star && !(w > 0.0)) {
    throw InvalidInput(fmt::format("--omega-star = {} is not allowed: it must be > 0", w));
  }
  const auto delta_amp = quantity(o.delta_max, dim::length, "--delta-max");
  const auto force_amp = quantity(o.Q_max, dim::force, "--Q-max");
  if (delta_amp && !(*delta_amp >= 0.0)) {
    throw InvalidInput(
        fmt::format("--delta-max = {} m is not allowed: the amplitude must be >= 0", *delta_amp));
  }
  if (force_amp && !(*force_amp >= 0.0)) {
    throw InvalidInput(
        fmt::format("--Q-max = {} N is not allowed: the amplitude must be >= 0", *force_amp));
  }
  if (o.points < 2 || o.points > 100000) throw InvalidInput("--points must lie in [2, 100000]");

  std::vector<ModelResult> results;
  for (ModelName m : models) {
    auto model = o.P ? contact::PartialSlipModel::from_load(pair, m, P, params)
                     : contact::PartialSlipModel::from_interference_star(pair, m, w, params);
    ModelResult r{model, std::nullopt, std::nullopt, std::nullopt, std::nullopt};
    const auto& c = model.contact();
    if (delta_amp) {
      r.delta_max = *delta_amp;
      r.Q_at_delta_max = c.loading_force(*delta_amp);
      r.energy = c.energy_per_cycle(*delta_amp);
      r.regime = c.regime_for_displacement(*delta_amp);
    } else if (force_amp) {
      if (*force_amp <= c.Q_max() && c.Q_max() > 0.0) {
        r.delta_max = c.loading_displacement(*force_amp);
        r.Q_at_delta_max = *force_amp;
        r.energy = c.energy_per_cycle_for_force(*force_amp);
        r.regime = *force_amp < c.Q_max() ? contact::SlipRegime::partial_slip
                                          : contact::SlipRegime::gross_slip;
      } else {
        r.regime = contact::SlipRegime::gross_slip;  // force control beyond mu P: sliding
      }
    }
    results.push_back(r);
  }

  const auto crit = pair.critical();
  if (o.json) {
    Json j;
    j["E_star"] = pair.E_star;
    j["G_star"] = pair.G_star;
    j["R"] = pair.R;
    j["K"] = pair.K();
    j["H"] = pair.H;
    j["nu"] = pair.nu;
    j["critical"] = {{"omega_c", crit.omega_c}, {"a_c", crit.a_c}, {"P_c", crit.P_c}};
    if (delta_amp) j["delta_max"] = *delta_amp;
    if (force_amp) j["Q_max_applied"] = *force_amp;
    Json jm = Json::object();
    for (const auto& r : results) {
      Json e;
      e["omega"] = r.model.omega();
      e["omega_star"] = r.model.omega_star();
      e["a"] = r.model.a();
      e["P"] = r.model.P();
      e["mu"] = r.model.mu();
      e["K_T"] = r.model.K_T();
      e["Q_max"] = r.model.Q_max();
      e["slip_displacement"] = r.model.contact().slip_displacement();
      if (delta_amp || force_amp) {
        e["delta_max"] = opt(r.delta_max);
        e["Q_at_delta_max"] = opt(r.Q_at_delta_max);
        e["energy"] = opt(r.energy);
        e["regime"] = to_string(*r.regime);
      }
      jm[std::string(to_string(r.model.model()))] = e;
    }
    j["models"] = jm;
    out += j.dump(2) + "\n";
  } else {
    out += fmt::format(
        "sphere on {}: R = {:.4g} mm, E* = {:.4g} GPa, G* = {:.4g} GPa, "
        "H = {:.4g} GPa, nu = {:.3g}, K = {:.4g}\n",
        std::isinf(R2) ? "flat" : "sphere", pair.R * 1e3, pair.E_star * 1e-9, pair.G_star * 1e-9,
        pair.H * 1e-9, pair.nu, pair.K());
    out += fmt::format(
        "critical values (Eq. 3.5): omega_c = {:.4g} um, a_c = {:.4g} mm, "
        "P_c = {:.4g} N\n\n",
        crit.omega_c * 1e6, crit.a_c * 1e3, crit.P_c);
    out += fmt::format("{:<6}{:>9}{:>12}{:>10}{:>10}{:>9}{:>12}{:>11}", "model", "omega*",
                       "omega[um]", "a[um]", "P[N]", "mu", "K_T[N/um]", "Q_max[N]");
    if (delta_amp || force_amp) {
      out += fmt::format("{:>14}{:>10}{:>13}  {}", "delta_max[um]", "Q[N]", "energy[nJ]", "regime");
    }
    out += "\n";
    for (const auto& r : results) {
      out += fmt::format("{:<6}{:>9.4g}{:>12.4g}{:>10.4g}{:>10.4g}{:>9.4g}{:>12.4g}{:>11.4g}",
                         to_string(r.model.model()), r.model.omega_star(), r.model.omega() * 1e6,
                         r.model.a() * 1e6, r.model.P(), r.model.mu(), r.model.K_T() * 1e-6,
                         r.model.Q_max());
      if (r.regime) {
        auto cell = [](const std::optional<double>& v, double scale) {
          return v ? fmt::format("{:.4g}", *v * scale) : std::string("-");
        };
        out += fmt::format(
            "{:>14}{:>10}{:>13}  {}", cell(r.delta_max, 1e6), cell(r.Q_at_delta_max, 1.0),
            cell(r.energy, 1e9),
            r.delta_max ? to_string(*r.regime) : "gross_slip (slides under force control)");
      }
      out += "\n";
    }
  }

  if ((o.loop_csv || o.plot_png) && !(delta_amp || force_amp)) {
    throw InvalidInput("--loop and --plot need an amplitude: give --delta-max or --Q-max");
  }
  if (o.loop_csv || o.plot_png) {
    std::ostringstream csv;
    csv << "model,branch,delta[m],Q[N]\n";
    PlotSpec plot{.title = "Fretting loops (Cattaneo-Mindlin with physics-based mu)",
                  .xlabel = "tangential displacement delta [um]",
                  .ylabel = "tangential force Q [N]"};
    const char* branch_names[] = {"loading", "unloading", "reloading"};
    for (const auto& r : results) {
      if (!r.delta_max) continue;
      const auto loop = r.model.contact().loop(*r.delta_max, o.points);
      Series s{.title = std::string(to_string(r.model.model()))};
      for (std::size_t i = 0; i < loop.delta.size(); ++i) {
        csv << fmt::format("{},{},{:.12g},{:.12g}\n", to_string(r.model.model()),
                           branch_names[loop.branch[i]], loop.delta[i], loop.Q[i]);
        s.x.push_back(loop.delta[i] * 1e6);
        s.y.push_back(loop.Q[i]);
      }
      plot.series.push_back(std::move(s));
    }
    if (o.loop_csv) write_file_atomically(*o.loop_csv, csv.str());
    if (o.plot_png) plot_png(*o.plot_png, plot);
  }
  if (o.energy_csv) {
    // Energy per cycle against displacement amplitude, up to the given amplitude or,
    // without one, to twice the largest gross-slip displacement.
    double top = 0.0;
    for (const auto& r : results) top = std::max(top, 2.0 * r.model.contact().slip_displacement());
    if (delta_amp || force_amp) {
      top = 0.0;
      for (const auto& r : results) top = std::max(top, r.delta_max.value_or(0.0));
    }
    if (!(top > 0.0)) throw InvalidInput("--energy-curve: no model carries a friction force");
    std::ostringstream csv;
    csv << "model,delta_max[m],energy[J]\n";
    for (const auto& r : results) {
      for (std::size_t i = 0; i < o.points; ++i) {
        const double d = top * static_cast<double>(i) / static_cast<double>(o.points - 1);
        csv << fmt::format("{},{:.12g},{:.12g}\n", to_string(r.model.model()), d,
                           r.model.contact().energy_per_cycle(d));
      }
    }
    write_file_atomically(*o.energy_csv, csv.str());
  }
}

}  // namespace

void add_sphere_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<SphereOptions>();
  auto* cmd = app.add_subcommand(
      "sphere",
      "One asperity: a sphere on a flat (or two spheres) under a normal load, with the CFC, "
      "CEB, KE and BKE partial slip models (thesis ch. 3). Quantities carry units, e.g. "
      "207GPa, 2.5mm, 35N, 1.5um.");
  o->materials.add_to(cmd, "body 1 (the sphere)", "body 2 (the flat)");
  cmd->add_option("--R1", o->R1, "radius of body 1")->required();
  cmd->add_option("--R2", o->R2, "radius of body 2 (default: a flat)");
  cmd->add_option("--P", o->P, "normal load");
  cmd->add_option("--omega-star", o->omega_star, "interference over omega_c, instead of --P");
  cmd->add_option("--delta-max", o->delta_max, "tangential displacement amplitude");
  cmd->add_option("--Q-max", o->Q_max, "tangential force amplitude, instead of --delta-max");
  cmd->add_option("--model", o->model, "cfc, ceb, ke, bke or all")->default_str("all");
  cmd->add_option("--mu-cfc", o->mu_cfc, "friction coefficient of the cfc model (s/H)");
  cmd->add_option("--zeta", o->zeta, "CEB yield depth over contact radius (default 0.48)");
  cmd->add_flag("--json", o->json, "print one JSON object (SI units) instead of a table");
  cmd->add_option("--loop", o->loop_csv, "write the fretting loop points to this CSV file");
  cmd->add_option("--plot", o->plot_png, "draw the fretting loops into this PNG file");
  cmd->add_option("--energy-curve", o->energy_csv,
                  "write energy per cycle against displacement amplitude to this CSV file");
  cmd->add_option("--points", o->points, "points per loop branch (default 101)");
  cmd->callback([o, &action] {
    action = [o] { return run_guarded([o](std::string& out) { run_sphere(*o, out); }); };
  });
}

}  // namespace asperity::cli
