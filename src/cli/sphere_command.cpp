// asperity sphere: one asperity (a sphere on a flat) with the four physics-based
// partial slip models of chapter 3.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
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
  std::string interference = "hertz";
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

struct SkippedModel {
  ModelName model;
  std::string reason;
};

Json opt(const std::optional<double>& v) {
  return v ? Json(*v) : Json(nullptr);
}

/// A positive double that is neither infinite nor below the normal range (where
/// products and quotients of it lose all digits or overflow).
bool representable(double v) {
  return std::isfinite(v) && v >= std::numeric_limits<double>::min();
}

/// What the user gave for the normal load and the amplitude, for messages about
/// quantities derived from them.
struct InputsText {
  std::string load;       // "--P = 35 N" or "--omega-star = 0.3"
  std::string amplitude;  // "--delta-max = 1.5e-06 m", "--Q-max = ..." or ""
};

/// Evaluates one model and checks every number it reports, mapping a quantity beyond
/// the double range back to the flags that caused it.
ModelResult evaluate(const contact::ContactPair& pair, ModelName m, const SphereOptions& o,
                     const contact::FrictionParameters& params,
                     contact::InterferenceReading reading, double P, double w,
                     const std::optional<double>& delta_amp, const std::optional<double>& force_amp,
                     const InputsText& in) {
  const auto name = std::string(to_string(m));
  const double P_c = pair.critical().P_c;
  if (!o.P) {
    // P = P_c P*(omega*) (B.1-B.4, or B.1 for the hertz reading) must be a double.
    const contact::AsperityLaws laws(m, pair.nu, params);
    const double P_star = reading == contact::InterferenceReading::hertz
                              ? contact::normal_load_star(contact::NormalLaw::hertz, w, pair.nu)
                              : laws.load_star(w);
    if (!representable(P_star * P_c)) {
      throw InvalidInput(fmt::format(
          "{} is too large: the {} model's normal load P = P_c P*(omega*) = {} N is beyond "
          "the double range (P_c = {} N); give a smaller --omega-star",
          in.load, name, core::format_value(P_star * P_c), core::format_value(P_c)));
    }
  }
  std::optional<contact::PartialSlipModel> built;
  try {
    built = o.P ? contact::PartialSlipModel::from_load(pair, m, P, params, reading)
                : contact::PartialSlipModel::from_interference_star(pair, m, w, params, reading);
  } catch (const InvalidInput& e) {
    // Not expected after the checks above; keep the cause but name the inputs.
    throw InvalidInput(
        fmt::format("{}: the {} model cannot be evaluated: {}", in.load, name, e.what()));
  }
  ModelResult r{*built, std::nullopt, std::nullopt, std::nullopt, std::nullopt};
  const auto& c = r.model.contact();
  if (delta_amp) {
    const double s = c.slip_displacement();
    if (s > 0.0 && !std::isfinite(*delta_amp / s)) {
      throw InvalidInput(fmt::format(
          "{} is too large: it is {} times the {} model's slip displacement {} m, beyond the "
          "double range; give a smaller --delta-max",
          in.amplitude, core::format_value(*delta_amp / s), name, core::format_value(s)));
    }
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
  // Every reported number must be finite; name the quantity and the inputs if not.
  const std::pair<const char*, double> reported[] = {
      {"interference omega [m]", r.model.omega()},
      {"contact radius a [m]", r.model.a()},
      {"normal load P [N]", r.model.P()},
      {"friction coefficient mu", r.model.mu()},
      {"tangential stiffness K_T = 8 G* a [N/m]", r.model.K_T()},
      {"static friction force Q_max = mu P [N]", r.model.Q_max()},
      {"slip displacement [m]", c.slip_displacement()},
      {"tangential force at the amplitude [N]", r.Q_at_delta_max.value_or(0.0)},
      {"energy per cycle [J]", r.energy.value_or(0.0)},
      {"displacement amplitude [m]", r.delta_max.value_or(0.0)}};
  for (const auto& [what, v] : reported) {
    if (!std::isfinite(v)) {
      throw InvalidInput(fmt::format(
          "{}{}{}: the {} model's {} is {}, outside the double range; the inputs are too "
          "large or too far apart in magnitude",
          in.load, in.amplitude.empty() ? "" : " with ", in.amplitude, name, what,
          core::format_value(v)));
    }
  }
  return r;
}

// CEB's c1 (B.11), through which zeta enters: mu_CEB's surface branch grows as 1/|c1|.
double ceb_c1(double zeta) {
  return -1.0 + 1.5 * zeta * std::atan(1.0 / zeta) - zeta * zeta / (2.0 * (1.0 + zeta * zeta));
}

// Inputs that the equations accept but no contact of the thesis resembles: each a warning
// with its physical reason (the numbers are still what the equations give).
std::vector<std::string> plausibility_warnings(const SphereOptions& o, double R1, double R2,
                                               const contact::FrictionParameters& params) {
  std::vector<std::string> w;
  // Spheres of the thesis's comparisons: 1.55 um (Table 3.3) and 2.5 mm (Table 3.1).
  for (const auto& [flag, R] : {std::pair{"--R1", R1}, std::pair{"--R2", R2}}) {
    if (std::isfinite(R) && R > 1.0) {
      w.push_back(fmt::format(
          "{} = {} m is a sphere larger than 1 m: the laws of chapter 3 were compared with "
          "spheres of 1.55 um (Table 3.3) and 2.5 mm (Table 3.1); check the unit",
          flag, core::format_value(R)));
    }
  }
  // Blau's metal-on-metal friction coefficients: 0.2 to 1.5 (thesis, after Eq. 4.14).
  if (o.mu_cfc && params.mu_cfc > 1.5) {
    w.push_back(fmt::format(
        "--mu-cfc = {} is above 1.5, the largest metal-on-metal friction coefficient that the "
        "thesis cites (Blau: 0.2-1.5); CFC's mu = s/H (B.10), the softer material's shear "
        "strength over its hardness, is 0.284 for the steel of Table 3.2 and 0.259 for silica",
        core::format_value(params.mu_cfc)));
  }
  // zeta enters CEB's mu through 1/|c1| (B.11); a factor 2 either way from the thesis's
  // zeta = 0.48 (nu = 0.3, under B.13) is no longer that yield depth.
  const double ratio = std::abs(ceb_c1(0.48)) / std::abs(ceb_c1(params.zeta));
  if (o.zeta && !(ratio >= 0.5 && ratio <= 2.0)) {
    w.push_back(fmt::format(
        "--zeta = {} (depth of first yield over the contact radius) makes CEB's |c1| (B.11) "
        "{:.3g} times that of the thesis's zeta = 0.48 (nu = 0.3), so CEB's friction coefficient "
        "{:.3g} times as large; first yield under a Hertz contact lies at about half the contact "
        "radius",
        core::format_value(params.zeta), 1.0 / ratio, ratio));
  }
  return w;
}

void run_sphere(const SphereOptions& o, std::string& out) {
  const auto materials = o.materials.parse_described();
  const auto& b1 = materials.body1;
  const auto& b2 = materials.body2;
  const double R1 = required_quantity(o.R1, dim::length, "--R1");
  const double R2 =
      o.R2 ? required_quantity(o.R2, dim::length, "--R2") : std::numeric_limits<double>::infinity();
  core::require_positive("--R1", R1);
  if (o.R2) core::require_positive("--R2", R2);
  contact::InterferenceReading reading;
  try {
    reading = contact::parse_interference_reading(lowercase(o.interference));
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("--interference: {}", e.what()));
  }
  const auto pair = [&] {
    try {
      return contact::ContactPair::combine(b1, b2, R1, R2);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("--E1/--E2/--G1/--G2: {}", e.what()));
    }
  }();
  const auto crit = pair.critical();
  // Eq. 3.5: the critical values scale the whole model; moduli, hardness and radii of
  // wildly different magnitudes can put them outside the double range.
  if (!representable(pair.G_star)) {
    throw InvalidInput(fmt::format(
        "the shear moduli (--G1, --G2, or E/(2(1+nu)) without them) give G* = {} Pa, which "
        "must be a finite number > 0 in the double range: check their magnitudes",
        core::format_value(pair.G_star)));
  }
  if (!representable(pair.E_star) || !representable(crit.omega_c) || !representable(crit.a_c) ||
      !representable(crit.P_c)) {
    throw InvalidInput(fmt::format(
        "--E1/--E2 (E* = {} Pa), the hardness (H = {} Pa) and --R1/--R2 (R = {} m) give the "
        "critical values (Eq. 3.5) omega_c = {} m, a_c = {} m, P_c = {} N, which must be "
        "finite numbers > 0 in the double range: check the magnitudes of these inputs",
        core::format_value(pair.E_star), core::format_value(pair.H), core::format_value(pair.R),
        core::format_value(crit.omega_c), core::format_value(crit.a_c),
        core::format_value(crit.P_c)));
  }

  std::vector<ModelName> models;
  std::vector<SkippedModel> skipped;
  // BKE's fits (l_c, delta_c > 0) need the softer material's nu in about (0.118, 0.5).
  std::string bke_unusable;
  try {
    (void)contact::BkeConstants::for_poisson(pair.nu);
  } catch (const InvalidInput&) {
    bke_unusable = fmt::format(
        "the softer material's Poisson's ratio nu = {} (--nu{}) is outside the range of the BKE "
        "fits, about (0.118, 0.5)",
        core::format_value(pair.nu),
        materials.softer_body == 0 ? std::string("1/--nu2")
                                   : std::to_string(materials.softer_body));
  }
  if (lowercase(o.model) == "all") {
    for (ModelName m : contact::kAllModels) {
      if (m == ModelName::bke && !bke_unusable.empty()) {
        skipped.push_back({m, bke_unusable});
      } else {
        models.push_back(m);
      }
    }
  } else {
    try {
      models.push_back(contact::parse_model_name(lowercase(o.model)));
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("--model: {} (or all)", e.what()));
    }
    if (models.front() == ModelName::bke && !bke_unusable.empty()) {
      throw InvalidInput(fmt::format(
          "--model bke: {}; change --nu1/--nu2 or choose another --model (cfc, ceb, ke)",
          bke_unusable));
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
    throw InvalidInput(fmt::format("--P = {} N is not allowed: the normal load must be > 0",
                                   core::format_value(P)));
  }
  if (o.omega_star && !(w > 0.0)) {
    throw InvalidInput(
        fmt::format("--omega-star = {} is not allowed: it must be > 0", core::format_value(w)));
  }
  if (o.P && !representable(P / crit.P_c)) {
    throw InvalidInput(fmt::format(
        "--P = {} N is too {}: it is {} times the critical load P_c = {} N (Eq. 3.5), outside "
        "the double range; give a load closer to P_c",
        core::format_value(P), P > crit.P_c ? "large" : "small", core::format_value(P / crit.P_c),
        core::format_value(crit.P_c)));
  }
  const auto delta_amp = quantity(o.delta_max, dim::length, "--delta-max");
  const auto force_amp = quantity(o.Q_max, dim::force, "--Q-max");
  if (delta_amp && !(*delta_amp >= 0.0)) {
    throw InvalidInput(fmt::format("--delta-max = {} m is not allowed: the amplitude must be >= 0",
                                   core::format_value(*delta_amp)));
  }
  if (force_amp && !(*force_amp >= 0.0)) {
    throw InvalidInput(fmt::format("--Q-max = {} N is not allowed: the amplitude must be >= 0",
                                   core::format_value(*force_amp)));
  }
  const std::size_t points = o.points;  // checked by whole_number_in on the text
  if ((o.loop_csv || o.plot_png) && !(delta_amp || force_amp)) {
    throw InvalidInput("--loop and --plot need an amplitude: give --delta-max or --Q-max");
  }
  if (is_standard_output(o.plot_png))
    throw InvalidInput("--plot - is not allowed: a PNG goes to a file, give its name");
  require_one_stdout(o.json, {{"--loop", o.loop_csv}, {"--energy-curve", o.energy_csv}});
  const bool stdout_is_data =
      o.json || is_standard_output(o.loop_csv) || is_standard_output(o.energy_csv);
  require_distinct_outputs({{"--loop", o.loop_csv.value_or("")},
                            {"--plot", o.plot_png.value_or("")},
                            {"--energy-curve", o.energy_csv.value_or("")}});

  InputsText in;
  in.load = o.P ? fmt::format("--P = {} N", core::format_value(P))
                : fmt::format("--omega-star = {}", core::format_value(w));
  if (delta_amp) in.amplitude = fmt::format("--delta-max = {} m", core::format_value(*delta_amp));
  if (force_amp) in.amplitude = fmt::format("--Q-max = {} N", core::format_value(*force_amp));

  std::vector<ModelResult> results;
  for (ModelName m : models) {
    results.push_back(evaluate(pair, m, o, params, reading, P, w, delta_amp, force_amp, in));
  }

  // The laws of chapter 3 are small-strain contact mechanics: a << R. Say so when a load
  // pushes a model past it (the numbers are still what the equations give).
  std::vector<std::string> warnings = contact::hardness_warnings(pair.H, pair.E_star);
  for (auto& text : plausibility_warnings(o, R1, R2, params)) warnings.push_back(std::move(text));
  for (const auto& r : results) {
    if (r.model.a() > 0.3 * pair.R) {
      warnings.push_back(fmt::format(
          "{}: contact radius a = {:.4g} mm is {:.3g} R: beyond the small-contact assumption "
          "(a << R) of the asperity laws (B.1-B.8)",
          to_string(r.model.model()), r.model.a() * 1e3, r.model.a() / pair.R));
    }
  }
  const char* reading_text =
      reading == contact::InterferenceReading::hertz
          ? "hertz (Hertz's interference and contact radius for every model, each with its own "
            "mu: the thesis's Table 3.2; --interference own: each model's own normal law)"
          : "own (each model's normal law gives its interference and contact radius; "
            "--interference hertz: the thesis's Table 3.2 reading)";
  if (o.json) {
    Json j;
    j["E_star"] = pair.E_star;
    j["G_star"] = pair.G_star;
    j["R"] = pair.R;
    j["K"] = pair.K();
    j["H"] = pair.H;
    j["nu"] = pair.nu;
    j["softer_body"] = materials.softer_body == 0 ? Json(nullptr) : Json(materials.softer_body);
    j["softer_rule"] = materials.softer_rule;
    j["critical"] = {{"omega_c", crit.omega_c}, {"a_c", crit.a_c}, {"P_c", crit.P_c}};
    j["interference"] = std::string(to_string(reading));
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
    for (const auto& sk : skipped) jm[std::string(to_string(sk.model))] = {{"skipped", sk.reason}};
    j["models"] = jm;
    j["warnings"] = warnings;
    out += json_output(j);
  } else if (!stdout_is_data) {
    out += fmt::format(
        "sphere on {}: R = {:.4g} mm, E* = {:.4g} GPa, G* = {:.4g} GPa, "
        "H = {:.4g} GPa, nu = {:.3g}, K = {:.4g}\n",
        std::isinf(R2) ? "flat" : "sphere", pair.R * 1e3, pair.E_star * 1e-9, pair.G_star * 1e-9,
        pair.H * 1e-9, pair.nu, pair.K());
    out += fmt::format("softer material (H, nu): {}{}\n",
                       materials.softer_body == 0 ? std::string()
                                                  : fmt::format("body {}, ", materials.softer_body),
                       materials.softer_rule);
    out += fmt::format(
        "critical values (Eq. 3.5): omega_c = {:.4g} um, a_c = {:.4g} mm, "
        "P_c = {:.4g} N\n",
        crit.omega_c * 1e6, crit.a_c * 1e3, crit.P_c);
    out += fmt::format("interference: {}\n\n", reading_text);
    // Every cell starts with a space, so that wide numbers never run together.
    out += fmt::format("{:<5} {:>8} {:>11} {:>9} {:>9} {:>8} {:>11} {:>10}", "model", "omega*",
                       "omega[um]", "a[um]", "P[N]", "mu", "K_T[N/um]", "Q_max[N]");
    if (delta_amp || force_amp) {
      out +=
          fmt::format(" {:>13} {:>9} {:>12}  {}", "delta_max[um]", "Q[N]", "energy[nJ]", "regime");
    }
    out += "\n";
    for (const auto& r : results) {
      out += fmt::format("{:<5} {:>8.4g} {:>11.4g} {:>9.4g} {:>9.4g} {:>8.4g} {:>11.4g} {:>10.4g}",
                         to_string(r.model.model()), r.model.omega_star(), r.model.omega() * 1e6,
                         r.model.a() * 1e6, r.model.P(), r.model.mu(), r.model.K_T() * 1e-6,
                         r.model.Q_max());
      if (r.regime) {
        auto cell = [](const std::optional<double>& v, double scale) {
          return v ? fmt::format("{:.4g}", *v * scale) : std::string("-");
        };
        out += fmt::format(
            " {:>13} {:>9} {:>12}  {}", cell(r.delta_max, 1e6), cell(r.Q_at_delta_max, 1.0),
            cell(r.energy, 1e9),
            r.delta_max ? to_string(*r.regime) : "gross_slip (slides under force control)");
      }
      out += "\n";
    }
    for (const auto& sk : skipped) {
      out += fmt::format("{:<5} skipped: {}\n", to_string(sk.model), sk.reason);
    }
  }

  // Every output is written into a temporary first and renamed at the end: all or none.
  core::OutputSet outputs;
  if (o.loop_csv || o.plot_png) {
    std::ostringstream csv;
    csv << "model,branch,delta[m],Q[N]\n";
    PlotSpec plot{.title = "Fretting loops (Cattaneo-Mindlin with physics-based mu)",
                  .xlabel = "tangential displacement delta [µm]",
                  .ylabel = "tangential force Q [N]"};
    const char* branch_names[] = {"loading", "unloading", "reloading"};
    for (const auto& r : results) {
      if (!r.delta_max) continue;
      const auto loop = r.model.contact().loop(*r.delta_max, points);
      Series s{.title = std::string(to_string(r.model.model()))};
      for (std::size_t i = 0; i < loop.delta.size(); ++i) {
        csv << fmt::format("{},{},{:.12g},{:.12g}\n", to_string(r.model.model()),
                           branch_names[loop.branch[i]], loop.delta[i], loop.Q[i]);
        s.x.push_back(loop.delta[i] * 1e6);
        s.y.push_back(loop.Q[i]);
      }
      plot.series.push_back(std::move(s));
    }
    if (o.loop_csv) write_output(outputs, *o.loop_csv, csv.str(), out);
    if (o.plot_png) plot_png(*o.plot_png, plot, &outputs);
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
      for (std::size_t i = 0; i < points; ++i) {
        const double d = top * static_cast<double>(i) / static_cast<double>(points - 1);
        csv << fmt::format("{},{:.12g},{:.12g}\n", to_string(r.model.model()), d,
                           r.model.contact().energy_per_cycle(d));
      }
    }
    write_output(outputs, *o.energy_csv, csv.str(), out);
  }
  outputs.commit();
  std::vector<std::string> written;
  for (const auto& f : {o.loop_csv, o.plot_png, o.energy_csv}) {
    if (f) written.push_back(*f);
  }
  report_written(written, stdout_is_data, out);
  for (const auto& text : warnings) fmt::print(stderr, "warning: {}\n", text);
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
  cmd->add_option("--P,--preload", o->P, "normal load");
  cmd->add_option("--omega-star", o->omega_star, "interference over omega_c, instead of --P");
  cmd->add_option("--delta-max", o->delta_max, "tangential displacement amplitude");
  cmd->add_option("--Q-max", o->Q_max, "tangential force amplitude, instead of --delta-max");
  cmd->add_option("--model", o->model,
                  "cfc, ceb, ke, bke or all (all skips bke, with a note, when the softer "
                  "material's nu is outside its fits' range, about (0.118, 0.5)) (default: all)");
  cmd->add_option("--interference", o->interference,
                  "normal state of the models: hertz = Hertz's interference and contact radius "
                  "for every model, each with its own mu (the thesis's Table 3.2: 'the "
                  "penetration for all the models is estimated to be 2.77 um'); own = each "
                  "model's own normal law (B.1-B.8) for the load (default: hertz)");
  cmd->add_option("--mu-cfc", o->mu_cfc, "friction coefficient of the cfc model (s/H)");
  cmd->add_option("--zeta", o->zeta, "CEB yield depth over contact radius (default: 0.48)");
  cmd->add_flag("--json", o->json, "print one JSON object (SI units) instead of a table");
  cmd->add_option("--loop", o->loop_csv,
                  "write the fretting loop points to this CSV file (- for standard output)");
  cmd->add_option("--plot", o->plot_png, "draw the fretting loops into this PNG file");
  cmd->add_option("--energy-curve", o->energy_csv,
                  "write energy per cycle against displacement amplitude to this CSV file (- for "
                  "standard output)");
  cmd->add_option("--points", o->points, "points per loop branch, in [2, 100000] (default: 101)")
      ->check(whole_number_in(2, 100000));
  cmd->callback([o, &action] {
    action = [o] { return run_guarded([o](std::string& out) { run_sphere(*o, out); }); };
  });
}

}  // namespace asperity::cli
