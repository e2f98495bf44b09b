// asperity flat: a nominally flat rough contact (thesis ch. 4), normalized or
// dimensional, with its fretting loop and the response to any displacement history.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/hysteresis/masing.hpp"
#include "asperity/hysteresis/odfalk_vingsbo.hpp"
#include "asperity/hysteresis/table_backbone.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace dim = core::dim;

namespace {

struct FlatOptions {
  // Normalized
  std::optional<std::string> beta, psi, nu, P_star, G_over_E, delta_star_max;
  // Dimensional
  MaterialOptions materials;
  std::optional<std::string> sigma, eta, R, area, P, delta_max;
  // Common
  std::string model = "bke";
  std::optional<std::string> mu_cfc, zeta;
  std::string slip_scaling = "elastic";
  std::string tangential = "mindlin";
  std::optional<std::string> fretting_yield_point, hardening_coefficient;
  bool json = false;
  std::optional<std::string> history_csv, out_csv, loop_csv, plot_png, backbone_csv;
  std::size_t points = 201;
  std::optional<std::string> case_file;  // --case: a joint case's (patched) backbone
};

bool any_material_flag(const MaterialOptions& m) {
  return m.E1 || m.nu1 || m.G1 || m.H1 || m.E2 || m.nu2 || m.G2 || m.H2 || m.H;
}

double number(const std::optional<std::string>& text, const std::string& flag) {
  return required_quantity(text, dim::dimensionless, flag);
}

// A history value beyond `limit` (in the column's own units) is a unit or typing slip: a
// tangential displacement of a joint above 1 m (or 1e6 sigma) is no fretting.
void require_plausible_history(const std::vector<double>& x, double limit, const std::string& file,
                               const std::string& column, const std::string& what) {
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (std::abs(x[i]) > limit) {
      throw InvalidInput(fmt::format(
          "{}: row {} of column {}: {} is not allowed: |{}| must be at most {}; a joint's "
          "tangential displacement beyond that is no fretting (check the unit)",
          file, i + 1, column, core::format_value(x[i]), column, what));
    }
  }
}

// --case CASE.toml --history H.csv --out F.csv [--P 526N]: the force history of a joint
// case (its [interface] field in patches, or the uniform flat) by Masing's rules on its
// SI backbone, the one predict and dynamics use (docs/joints.md).
void run_flat_case(const FlatOptions& o, std::string& out) {
  const bool others = o.beta || o.psi || o.nu || o.P_star || o.G_over_E || o.delta_star_max ||
                      any_material_flag(o.materials) || o.sigma || o.eta || o.R || o.area ||
                      o.delta_max || o.mu_cfc || o.zeta || o.loop_csv || o.plot_png || o.json ||
                      o.fretting_yield_point || o.hardening_coefficient ||
                      lowercase(o.tangential) != "mindlin";
  if (others) {
    throw InvalidInput(
        "--case takes the joint from the case file (its [interface] tangential law too): give only "
        "--history, --out and optionally --P (the preload, when the case has several)");
  }
  if (!o.history_csv || !o.out_csv)
    throw InvalidInput("--case needs --history FILE.csv and --out FILE.csv");
  require_distinct_outputs({{"--out", *o.out_csv}, {"--history", *o.history_csv}});
  joint::require_output_apart_from_inputs(*o.out_csv, {{"the case file", *o.case_file}});
  const auto c = joint::read_case_file(*o.case_file);
  double P = 0.0;
  if (o.P) {
    P = required_quantity(o.P, dim::force, "--P");
    core::require_positive("--P", P);
  } else if (c.preloads.size() == 1) {
    P = c.preloads.front();
  } else {
    throw InvalidInput(fmt::format("{}: {} load cases: choose one with --P (e.g. --P 526N)",
                                   *o.case_file, c.preloads.size()));
  }
  const auto csv = core::read_csv_table(*o.history_csv);
  const auto* col = csv.find("delta");
  if (!col) {
    throw InvalidInput(fmt::format(
        "{}: --case needs a \"delta[unit]\" column (dimensional: the case is)", *o.history_csv));
  }
  const auto x = csv.si_values(*col, dim::length);
  require_plausible_history(x, 1.0, *o.history_csv, "delta [m]", "1 m");
  const auto lp = joint::predict_case_load(c, P);
  // Masing on the case's backbone, or the Odfalk-Vingsbo law in series with it.
  const auto Q =
      lp.odfalk_vingsbo
          ? hysteresis::OdfalkVingsboHysteresis(lp.backbone, *lp.odfalk_vingsbo).forces(x)
          : hysteresis::Hysteresis(lp.backbone).forces(x);
  core::write_csv_table(*o.out_csv, {"delta[m]", "Q[N]"}, {x, Q});
  out = fmt::format(
      "{} at P = {:.6g} N: Q_max = {:.6g} N, stiffness {:.6g} N/um, {} patch{}; wrote {} ({} "
      "forces)\n",
      c.name.empty() ? *o.case_file : c.name, P, lp.Q_max, lp.stiffness * 1e-6, lp.patches.size(),
      lp.patches.size() == 1 ? "" : "es", *o.out_csv, Q.size());
}

void run_flat(const FlatOptions& o, std::string& out) {
  if (o.case_file) return run_flat_case(o, out);
  const auto model = contact::parse_model_name(lowercase(o.model));
  const std::string model_name(contact::to_string(model));
  contact::FrictionParameters friction;
  if (o.mu_cfc) {
    friction.mu_cfc = number(o.mu_cfc, "--mu-cfc");
    core::require_positive("--mu-cfc", friction.mu_cfc);
  } else if (model == contact::ModelName::cfc) {
    throw InvalidInput("the cfc model needs its friction coefficient: give --mu-cfc (e.g. 0.3)");
  }
  if (o.zeta) {
    friction.zeta = number(o.zeta, "--zeta");
    core::require_positive("--zeta", friction.zeta);
  }
  surface::SlipScaling scaling;
  if (lowercase(o.slip_scaling) == "elastic") {
    scaling = surface::SlipScaling::elastic;
  } else if (lowercase(o.slip_scaling) == "own-law") {
    scaling = surface::SlipScaling::own_law;
  } else {
    throw InvalidInput(fmt::format(
        "--slip-scaling \"{}\" is unknown: allowed are elastic (Eq. 4.8, default) and own-law",
        o.slip_scaling));
  }

  // The tangential law: Cattaneo-Mindlin, or the Odfalk-Vingsbo parallelogram (Eq. 3.10) in
  // series with it, whose two parameters only a measurement gives.
  std::optional<hysteresis::OdfalkVingsboParameters> ov;
  const std::string law = lowercase(o.tangential);
  if (law == "odfalk-vingsbo" || law == "odfalk_vingsbo") {
    if (!o.fretting_yield_point || !o.hardening_coefficient) {
      throw InvalidInput(fmt::format(
          "--tangential odfalk-vingsbo needs {}: the Odfalk-Vingsbo law (Eq. 3.10) takes the "
          "fretting yield point Q_ty and the hardening coefficient k_p, which the thesis says are "
          "obtained experimentally and could not be generalized (section 3.3); asperity has no "
          "physics-based value for them and fits none: give both from fretting loops measured on "
          "this contact, e.g. --fretting-yield-point 20N --hardening-coefficient 5N/um",
          !o.fretting_yield_point ? "--fretting-yield-point" : "--hardening-coefficient"));
    }
    ov = hysteresis::OdfalkVingsboParameters{
        .fretting_yield_point =
            required_quantity(o.fretting_yield_point, dim::force, "--fretting-yield-point"),
        .hardening_coefficient =
            required_quantity(o.hardening_coefficient, dim::stiffness, "--hardening-coefficient")};
    core::require_positive("--fretting-yield-point", ov->fretting_yield_point);
    core::require_finite("--fretting-yield-point", ov->fretting_yield_point);
    core::require_positive("--hardening-coefficient", ov->hardening_coefficient);
    core::require_finite("--hardening-coefficient", ov->hardening_coefficient);
  } else if (law == "mindlin") {
    if (o.fretting_yield_point || o.hardening_coefficient) {
      throw InvalidInput(
          "--fretting-yield-point and --hardening-coefficient are used only with --tangential "
          "odfalk-vingsbo");
    }
  } else {
    throw InvalidInput(fmt::format(
        "--tangential \"{}\" is unknown: allowed are mindlin (Cattaneo-Mindlin, default) and "
        "odfalk-vingsbo (Eq. 3.10, with measured --fretting-yield-point and "
        "--hardening-coefficient)",
        o.tangential));
  }

  const bool dimensional =
      any_material_flag(o.materials) || o.sigma || o.eta || o.R || o.area || o.P || o.delta_max;
  const bool normalized = o.beta || o.psi || o.nu || o.P_star || o.G_over_E || o.delta_star_max;
  if (dimensional && normalized) {
    throw InvalidInput(
        "mixing normalized flags (--beta --psi --nu --P-star --G-over-E --delta-star-max) with "
        "dimensional ones (materials, --sigma --eta --R --area --P --delta-max): use one set");
  }
  if (ov && normalized) {
    throw InvalidInput(
        "--tangential odfalk-vingsbo takes its measured Q_ty [N] and k_p [N/m] in SI: give the "
        "dimensional inputs (materials, --sigma --eta --R --area --P)");
  }
  if (!dimensional && !normalized) {
    throw InvalidInput(
        "give either the normalized inputs (--beta --psi --nu --P-star) or the "
        "dimensional ones (materials, --sigma --eta --R --area --P)");
  }

  std::optional<surface::RoughFlat> flat;
  double P_star = 0.0;
  std::optional<double> amplitude_star;
  if (normalized) {
    surface::RoughFlatParameters p{.model = model, .friction = friction, .slip_scaling = scaling};
    p.beta = number(o.beta, "--beta");
    p.psi = number(o.psi, "--psi");
    p.nu = number(o.nu, "--nu");
    core::require_in_half_open("--nu", p.nu, 0.0, 0.5);
    // Identical materials: G*/E* = (1 - nu)/(2 (2 - nu)).
    p.G_over_E =
        o.G_over_E ? number(o.G_over_E, "--G-over-E") : (1.0 - p.nu) / (2.0 * (2.0 - p.nu));
    core::require_positive("--G-over-E", p.G_over_E);
    core::require_positive("--psi", p.psi);
    // The library's limits, under the flags' names (rough_flat.hpp).
    if (!(p.psi >= surface::kMinPlasticityIndex)) {
      throw InvalidInput(fmt::format(
          "--psi {} is not allowed: the plasticity index must be at least {}; below it "
          "omega_c/sigma = (sigma_a/sigma)/psi^2 exceeds 350, no asperity yields and the "
          "asperity friction laws give mu of 10 and more (BKE at P* = 1e-3: 14 at psi = 0.05, "
          "49.9 at 0.01; the thesis uses psi = 0.5 to 4.7)",
          core::format_value(p.psi), surface::kMinPlasticityIndex));
    }
    if (!(p.beta <= surface::kMaxRoughnessParameter)) {
      throw InvalidInput(fmt::format(
          "--beta {} is not allowed: beta = sigma R eta must be at most 1/pi = 0.318, beyond "
          "which the asperity caps within one sigma of their summits would cover more than the "
          "nominal area (engineering surfaces: 0.02-0.06)",
          core::format_value(p.beta)));
    }
    flat.emplace(p);
    P_star = number(o.P_star, "--P-star");
    core::require_positive("--P-star", P_star);
    if (o.delta_star_max) {
      amplitude_star = number(o.delta_star_max, "--delta-star-max");
      core::require_non_negative("--delta-star-max", *amplitude_star);
    }
  } else {
    const auto [b1, b2] = o.materials.parse();
    const double sigma = required_quantity(o.sigma, dim::length, "--sigma");
    const double eta = required_quantity(o.eta, dim::inverse_area, "--eta");
    const double R = required_quantity(o.R, dim::length, "--R");
    const double A0 = required_quantity(o.area, dim::area, "--area");
    const double P = required_quantity(o.P, dim::force, "--P");
    core::require_positive("--sigma", sigma);
    core::require_positive("--eta", eta);
    core::require_positive("--R", R);
    core::require_positive("--area", A0);
    core::require_positive("--P", P);
    flat.emplace(
        surface::RoughFlat::from_dimensional(b1, b2, sigma, eta, R, A0, model, friction, scaling));
    P_star = P / flat->scales()->force;
    if (o.delta_max) {
      const double dm = required_quantity(o.delta_max, dim::length, "--delta-max");
      core::require_non_negative("--delta-max", dm);
      amplitude_star = dm / sigma;
    }
  }
  const std::size_t points = o.points;  // checked by whole_number_in on the text
  // Every input is checked, and the history read, before anything is computed or written.
  if ((o.loop_csv || o.plot_png) && !amplitude_star) {
    throw InvalidInput("--loop and --plot need an amplitude: give --delta-star-max or --delta-max");
  }
  if (o.history_csv && !o.out_csv)
    throw InvalidInput("--history needs --out FILE.csv for the forces");
  if (o.out_csv && !o.history_csv)
    throw InvalidInput("--out writes the force history of --history: give both");
  if (is_standard_output(o.plot_png))
    throw InvalidInput("--plot - is not allowed: a PNG goes to a file, give its name");
  require_one_stdout(
      o.json, {{"--loop", o.loop_csv}, {"--out", o.out_csv}, {"--backbone", o.backbone_csv}});
  const bool stdout_is_data = o.json || is_standard_output(o.loop_csv) ||
                              is_standard_output(o.out_csv) || is_standard_output(o.backbone_csv);
  require_distinct_outputs({{"--loop", o.loop_csv.value_or("")},
                            {"--plot", o.plot_png.value_or("")},
                            {"--out", o.out_csv.value_or("")},
                            {"--backbone", o.backbone_csv.value_or("")},
                            {"--history", o.history_csv.value_or("")}});
  // Every output's directory must exist before anything is written (no output is left
  // behind by a later one that cannot be written).
  for (const auto& [flag, path] :
       {std::pair{"--loop", o.loop_csv}, std::pair{"--plot", o.plot_png},
        std::pair{"--out", o.out_csv}, std::pair{"--backbone", o.backbone_csv}}) {
    if (!path || is_standard_output(*path)) continue;
    const auto dir = std::filesystem::absolute(*path).parent_path();
    if (!std::filesystem::is_directory(dir)) {
      throw InvalidInput(
          fmt::format("{} {}: the directory \"{}\" does not exist", flag, *path, dir.string()));
    }
  }
  const auto& scales = flat->scales();
  if (o.backbone_csv && ov) {
    throw InvalidInput(
        "--backbone writes a Masing backbone for a masing_table element; the Odfalk-Vingsbo law "
        "is not Masing's (its plastic slip starts at -+Q_ty, not at a scaled reversal): leave out "
        "--backbone or --tangential");
  }
  if (o.backbone_csv && !scales) {
    throw InvalidInput(
        "--backbone writes the backbone in SI (N against m) for a masing_table element: give the "
        "dimensional inputs (--sigma, --eta, --R, --area, --P and the materials)");
  }
  std::vector<double> history_star;
  bool history_si = false;
  if (o.history_csv) {
    const auto csv = core::read_csv_table(*o.history_csv);
    const auto* c_star = csv.find("delta_star");
    const auto* c_si = csv.find("delta");
    if (c_star && c_si) {
      throw InvalidInput(
          fmt::format("{}: both a \"delta_star\" and a \"delta\" column: keep the one you mean",
                      *o.history_csv));
    }
    if (c_star) {
      history_star = csv.si_values(*c_star, dim::dimensionless);
      require_plausible_history(history_star, 1e6, *o.history_csv, "delta_star",
                                "1e6 (a million times sigma)");
    } else if (c_si) {
      if (!scales) {
        throw InvalidInput(
            fmt::format("{}: a \"delta\" column needs the dimensional inputs; with "
                        "normalized inputs give a \"delta_star\" column",
                        *o.history_csv));
      }
      history_star = csv.si_values(*c_si, dim::length);
      require_plausible_history(history_star, 1.0, *o.history_csv, "delta [m]", "1 m");
      for (auto& v : history_star) v /= scales->sigma;
      history_si = true;
    } else {
      throw InvalidInput(
          fmt::format("{}: no \"delta_star\" column and no \"delta[unit]\" column in the header",
                      *o.history_csv));
    }
  }

  const auto& params = flat->parameters();
  const double d = flat->separation_star(P_star);
  const double Q_max = flat->static_friction_star(d);
  const double k = flat->stiffness_star(d);
  // The table (one load case) only when a displacement needs it.
  const bool need_table = amplitude_star || o.history_csv || o.backbone_csv;
  if (need_table && !(Q_max > 0.0)) {
    if (o.loop_csv || o.plot_png || o.history_csv || o.backbone_csv) {
      throw InvalidInput(
          fmt::format("the {} model carries no friction force here (Q*_max = 0)", model_name));
    }
  }
  std::shared_ptr<const surface::RoughFlatBackbone> table;
  if (need_table && Q_max > 0.0) table = flat->backbone(d);
  // The Odfalk-Vingsbo parameters on the normalized table's scales (x/sigma, Q/(K H A0)).
  std::optional<hysteresis::OdfalkVingsboParameters> ov_star;
  if (ov) {
    ov_star = hysteresis::OdfalkVingsboParameters{
        .fretting_yield_point = ov->fretting_yield_point / scales->force,
        .hardening_coefficient = ov->hardening_coefficient * scales->sigma / scales->force};
  }

  // Inputs outside the range of the thesis's laws, and an implausible result: said on
  // stderr and in the JSON's "warnings".
  std::vector<std::string> warnings = flat->warnings();
  if (scales) {
    for (auto& w : contact::hardness_warnings(scales->pair.H, scales->pair.E_star))
      warnings.push_back(std::move(w));
  }
  if (auto w = surface::friction_coefficient_warning(Q_max / P_star); !w.empty())
    warnings.push_back(std::move(w));

  std::optional<double> Q_amp, energy;
  std::optional<std::string> regime;
  if (amplitude_star && ov_star && table) {
    // Eq. 3.10's steady cycle: the regime from the elastic (interface) amplitude.
    const auto cycle = hysteresis::odfalk_vingsbo_cycle(*table, *ov_star, *amplitude_star);
    Q_amp = cycle.Q_m;
    energy = cycle.energy;
    regime = cycle.elastic_amplitude >= table->table_end() ? "gross_slip" : "partial_slip";
  } else if (amplitude_star) {
    Q_amp = table ? table->force(*amplitude_star) : 0.0;
    energy = table ? hysteresis::energy_per_cycle(*table, *amplitude_star) : 0.0;
    // Gross slip when the loading curve has reached the static friction (to the table's
    // saturation tolerance).
    regime = (!table || *amplitude_star >= table->table_end()) ? "gross_slip" : "partial_slip";
  }

  if (o.json) {
    Json j;
    j["model"] = model_name;
    j["beta"] = params.beta;
    j["psi"] = params.psi;
    j["nu"] = params.nu;
    j["G_over_E"] = params.G_over_E;
    j["sigma_a_over_sigma"] = flat->sigma_a_over_sigma();
    j["omega_c_star"] = flat->omega_c_star();
    j["separation_star"] = d;
    j["P_star"] = P_star;
    j["Q_max_star"] = Q_max;
    j["mu"] = Q_max / P_star;
    j["stiffness_star"] = k;
    j["contact_area_ratio"] = flat->contact_area_ratio(d);
    j["contact_fraction"] = flat->contact_fraction(d);
    if (table) j["table_error"] = table->verified_error();
    if (amplitude_star) {
      j["delta_max_star"] = *amplitude_star;
      j["Q_at_delta_max_star"] = *Q_amp;
      j["energy_star"] = *energy;
      j["regime"] = *regime;
    }
    if (scales) {
      j["separation"] = d * scales->sigma;
      j["P"] = P_star * scales->force;
      j["Q_max"] = Q_max * scales->force;
      j["stiffness"] = k * scales->force / scales->sigma;
      j["real_contact_area"] = flat->contact_area_ratio(d) * scales->A0;
      j["contacting_asperities"] = flat->contact_fraction(d) * scales->eta * scales->A0;
      if (amplitude_star) {
        j["delta_max"] = *amplitude_star * scales->sigma;
        j["Q_at_delta_max"] = *Q_amp * scales->force;
        j["energy"] = *energy * scales->force * scales->sigma;
      }
    }
    j["tangential"] = ov ? Json{{"law", "odfalk_vingsbo"},
                                {"fretting_yield_point", ov->fretting_yield_point},
                                {"hardening_coefficient", ov->hardening_coefficient}}
                         : Json{{"law", "mindlin"}};
    j["warnings"] = warnings;
    out += json_output(j);
  } else if (!stdout_is_data) {
    out += fmt::format(
        "rough flat, {} model: beta = {:.4g}, psi = {:.4g}, nu = {:.3g}, G*/E* = {:.4g}, "
        "sigma_a/sigma = {:.4g}, omega_c/sigma = {:.4g}\n",
        model_name, params.beta, params.psi, params.nu, params.G_over_E, flat->sigma_a_over_sigma(),
        flat->omega_c_star());
    out += fmt::format(
        "  P* = {:.5g}   separation d* = {:.5g}   Q*_max = {:.5g}   mu = {:.4g}   "
        "stiffness* = {:.5g}\n",
        P_star, d, Q_max, Q_max / P_star, k);
    if (ov) {
      out += fmt::format(
          "  tangential law: Odfalk-Vingsbo (Eq. 3.10), Q_ty = {:.5g} N, k_p = {:.5g} N/um, as "
          "given (measured, not predicted)\n",
          ov->fretting_yield_point, ov->hardening_coefficient * 1e-6);
    }
    if (scales) {
      out += fmt::format(
          "  P = {:.5g} N   separation = {:.4g} um   Q_max = {:.5g} N   "
          "stiffness = {:.5g} N/um   real contact area = {:.4g} mm^2   "
          "contacting asperities = {:.4g}\n",
          P_star * scales->force, d * scales->sigma * 1e6, Q_max * scales->force,
          k * scales->force / scales->sigma * 1e-6, flat->contact_area_ratio(d) * scales->A0 * 1e6,
          flat->contact_fraction(d) * scales->eta * scales->A0);
    }
    if (amplitude_star) {
      out +=
          fmt::format("  amplitude delta* = {:.5g}: Q* = {:.5g}, energy per cycle* = {:.5g}, {}\n",
                      *amplitude_star, *Q_amp, *energy, *regime);
      if (scales) {
        out += fmt::format(
            "  amplitude delta = {:.5g} um: Q = {:.5g} N, energy per cycle = {:.5g} uJ\n",
            *amplitude_star * scales->sigma * 1e6, *Q_amp * scales->force,
            *energy * scales->force * scales->sigma * 1e6);
      }
    }
  }

  const double xs = scales ? scales->sigma : 1.0;
  const double fs = scales ? scales->force : 1.0;
  // Every output is written into a temporary first and renamed at the end: all or none.
  core::OutputSet outputs;
  if (o.loop_csv || o.plot_png) {
    std::optional<hysteresis::Hysteresis> masing;
    std::optional<hysteresis::OdfalkVingsboHysteresis> elastic_plastic;
    if (ov_star) {
      elastic_plastic.emplace(table, *ov_star);
    } else {
      masing.emplace(table);
    }
    const auto update = [&](double v) {
      return elastic_plastic ? elastic_plastic->update(v) : masing->update(v);
    };
    const double dm = *amplitude_star;
    std::vector<double> x, q;
    const std::size_t n = points;
    auto run = [&](double from, double to) {
      for (std::size_t i = 1; i <= n; ++i) {
        const double v = from + (to - from) * static_cast<double>(i) / static_cast<double>(n);
        x.push_back(v);
        q.push_back(update(v));
      }
    };
    x.push_back(0.0);
    q.push_back(0.0);
    run(0.0, dm);
    run(dm, -dm);
    run(-dm, dm);
    if (o.loop_csv) {
      std::vector<double> xo(x), qo(q);
      for (auto& v : xo) v *= xs;
      for (auto& v : qo) v *= fs;
      write_output(outputs, *o.loop_csv,
                   csv_text(scales ? std::vector<std::string>{"delta[m]", "Q[N]"}
                                   : std::vector<std::string>{"delta_star", "Q_star"},
                            {xo, qo}),
                   out);
    }
    if (o.plot_png) {
      Series s{.title = model_name};
      for (std::size_t i = 0; i < x.size(); ++i) {
        s.x.push_back(scales ? x[i] * xs * 1e6 : x[i]);
        s.y.push_back(scales ? q[i] * fs : q[i]);
      }
      plot_png(*o.plot_png,
               PlotSpec{.title = ov ? "Fretting loop of the rough flat (Masing on Eq. 4.10 + "
                                      "Odfalk-Vingsbo Eq. 3.10)"
                                    : "Fretting loop of the rough flat (Masing on Eq. 4.10)",
                        .xlabel = scales ? "delta [µm]" : "delta* = delta/sigma",
                        .ylabel = scales ? "Q [N]" : "Q* = Q/(K H A0)",
                        .series = {s}},
               &outputs);
    }
  }
  if (o.history_csv) {
    auto Q = ov_star ? hysteresis::OdfalkVingsboHysteresis(table, *ov_star).forces(history_star)
                     : hysteresis::Hysteresis(table).forces(history_star);
    if (history_si) {
      for (auto& v : history_star) v *= scales->sigma;
      for (auto& v : Q) v *= scales->force;
    }
    // Moved, not copied, into the table: memory holds the two columns once; a file is
    // written in 1 MiB chunks (core::write_csv_table), standard output as before.
    std::vector<std::vector<double>> columns;
    columns.push_back(std::move(history_star));
    columns.push_back(std::move(Q));
    const std::vector<std::string> header = history_si
                                                ? std::vector<std::string>{"delta[m]", "Q[N]"}
                                                : std::vector<std::string>{"delta_star", "Q_star"};
    if (is_standard_output(*o.out_csv)) {
      write_output(*o.out_csv, csv_text(header, columns), out);
    } else {
      outputs.add_streamed(*o.out_csv, [&](const core::ChunkSink& sink) {
        core::write_csv_chunks(header, columns, sink);
      });
    }
  }
  if (o.backbone_csv) {
    // The virgin curve in SI, as predict --out's backbones.csv (hysteresis::tabulate).
    const hysteresis::ScaledBackbone si(table, scales->sigma, scales->force);
    auto [x, Q] = hysteresis::tabulate(si);
    for (auto& v : x) v *= 1e6;  // um, as backbones.csv
    write_output(outputs, *o.backbone_csv, csv_text({"delta[um]", "Q[N]"}, {x, Q}), out);
  }
  outputs.commit();
  std::vector<std::string> written;
  for (const auto& f : {o.loop_csv, o.plot_png, o.out_csv, o.backbone_csv}) {
    if (f && !is_standard_output(*f)) written.push_back(*f);
  }
  report_written(written, stdout_is_data, out);
  for (const auto& text : warnings) fmt::print(stderr, "warning: {}\n", text);
}

}  // namespace

void add_flat_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<FlatOptions>();
  auto* cmd = app.add_subcommand(
      "flat",
      "A nominally flat rough contact (thesis ch. 4): separation, static friction, stiffness, "
      "fretting loop and energy per cycle, normalized (--beta --psi --nu --P-star) or "
      "dimensional (materials, --sigma --eta --R --area --P).");
  cmd->add_option("--beta", o->beta, "roughness parameter sigma R eta (> 0.01928)");
  cmd->add_option("--psi", o->psi, "plasticity index on sigma_a (> 0)");
  cmd->add_option("--nu", o->nu, "Poisson's ratio of the softer material");
  cmd->add_option("--P-star", o->P_star, "normal load over K H A0");
  cmd->add_option("--G-over-E", o->G_over_E,
                  "G*/E* (default: (1-nu)/(2(2-nu)), identical materials)");
  cmd->add_option("--delta-star-max", o->delta_star_max, "displacement amplitude over sigma");
  o->materials.add_to(cmd, "body 1", "body 2");
  for (const char* flag : {"--E1", "--nu1", "--E2", "--nu2"})
    cmd->get_option(flag)->required(false);
  cmd->add_option("--sigma", o->sigma, "combined rms roughness, e.g. 2.677um");
  cmd->add_option("--eta", o->eta, "areal density of asperities, e.g. 2.91e-4um^-2");
  cmd->add_option("--R", o->R, "mean asperity radius, e.g. 30.14um");
  cmd->add_option("--area", o->area, "nominal contact area, e.g. 170mm^2");
  cmd->add_option("--P,--preload", o->P, "normal load, e.g. 526N");
  cmd->add_option("--delta-max", o->delta_max, "displacement amplitude, e.g. 1um");
  cmd->add_option("--model", o->model, "cfc, ceb, ke or bke (default: bke)");
  cmd->add_option("--mu-cfc", o->mu_cfc, "friction coefficient of the cfc model");
  cmd->add_option("--zeta", o->zeta, "CEB yield depth over contact radius (default: 0.48)");
  cmd->add_option("--slip-scaling", o->slip_scaling,
                  "elastic (Eq. 4.8) or own-law (each law's a/P) (default: elastic)");
  cmd->add_option(
      "--tangential", o->tangential,
      "tangential law: mindlin or odfalk-vingsbo (Eq. 3.10, phenomenological: "
      "needs the measured --fretting-yield-point and --hardening-coefficient) (default: mindlin)");
  cmd->add_option("--fretting-yield-point", o->fretting_yield_point,
                  "Odfalk-Vingsbo Q_ty, measured, e.g. 20N");
  cmd->add_option("--hardening-coefficient", o->hardening_coefficient,
                  "Odfalk-Vingsbo k_p, measured, e.g. 5N/um");
  cmd->add_flag("--json", o->json, "print one JSON object instead of a table");
  cmd->add_option("--history", o->history_csv,
                  "displacement history CSV (column delta_star, or delta[unit])");
  cmd->add_option("--out", o->out_csv,
                  "where --history writes the force history (CSV file; - for standard output)");
  cmd->add_option("--backbone", o->backbone_csv,
                  "write the backbone Q[N] against delta[um] (401 points to where Q is within 1e-9 "
                  "of Q_max, one on the plateau) for a masing_table vibration element; needs the "
                  "dimensional inputs (- for standard output)");
  cmd->add_option("--loop", o->loop_csv,
                  "write the fretting loop to this CSV file (- for standard output)");
  cmd->add_option("--plot", o->plot_png, "draw the fretting loop into this PNG file");
  cmd->add_option("--points", o->points, "points per loop branch, in [2, 100000] (default: 201)")
      ->check(whole_number_in(2, 100000));
  cmd->add_option("--case", o->case_file,
                  "a joint case file (as for predict, with its [interface]): with --history "
                  "and --out, the force history on its backbone at --P (or its one preload)");
  cmd->callback([o, &action] {
    action = [o] { return run_guarded([o](std::string& out) { run_flat(*o, out); }); };
  });
}

}  // namespace asperity::cli
