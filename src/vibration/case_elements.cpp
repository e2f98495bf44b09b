#include "case_parse.hpp"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <set>

#include "../core/toml_case.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/units.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/dynamics/epb.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "asperity/surface/summit_heights.hpp"
#include "asperity/vibration/contact_elements.hpp"
#include "asperity/vibration/rough_contact.hpp"

namespace asperity::vibration::detail {

namespace {

using core::Dimension;
namespace dim = core::dim;
using core::toml_case::at_line;
using core::toml_case::check_keys;
using core::toml_case::collect_lines;
using core::toml_case::number;

// The case file with the lines of every vibration table blanked: what remains is the
// joint part ([joint], [load], [profiles], comments) at its original line numbers, so
// that the joint reader's errors point into the user's file.
std::string joint_text(const std::string& file_text, const toml::table& root) {
  std::set<std::uint32_t> lines;
  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key == "joint" || key == "load" || key == "profiles" || key == "interface") continue;
    lines.insert(k.source().begin.line);
    collect_lines(v, lines);
  }
  return core::toml_case::without_lines(file_text, lines);
}

void add_backbone_summary(SummaryObject& f, const hysteresis::Backbone& b, double P) {
  f.emplace_back("P_N", P);
  f.emplace_back("Q_max_N", b.limit());
  f.emplace_back("mu", b.limit() / P);
  f.emplace_back("k_t_N_per_m", b.initial_stiffness());
}

std::shared_ptr<const Element> rough_flat_element(const toml::table& t, const std::string& w,
                                                  const std::optional<JointBackbone>& joint) {
  std::string bb = text(t, "backbone", w, "");
  if (bb.empty()) {
    if (t.get("beta")) {
      bb = "normalized";
    } else if (t.get("E_star")) {
      bb = "dimensional";
    } else if (joint) {
      bb = "joint";
    } else {
      throw InvalidInput(fmt::format(
          "{}: a rough_flat element needs its parameters: backbone = \"dimensional\" (E_star, "
          "G_star, H, nu, sigma, R, eta, A0, P), \"normalized\" (beta, psi, nu, G_over_E, P_star, "
          "sigma, force_scale) or \"joint\" with a [joint] and [load] table{}",
          w, at_line(t)));
    }
  }
  const std::set<std::string> common{"type",
                                     "name",
                                     "T",
                                     "backbone",
                                     "tangential",
                                     "fretting_yield_point",
                                     "hardening_coefficient"};
  auto with = [&](std::set<std::string> keys) {
    keys.insert(common.begin(), common.end());
    return keys;
  };
  // tangential = "odfalk_vingsbo" (Eq. 3.10) with its measured Q_ty and k_p, as in a joint
  // case's [interface] (docs/joints.md); the joint's own law with backbone = "joint".
  const std::set<std::string> law_keys{"tangential", "fretting_yield_point",
                                       "hardening_coefficient"};
  auto element_of = [&](std::shared_ptr<const hysteresis::Backbone> b, SummaryObject d) {
    const std::string law = text(t, "tangential", w, "mindlin");
    if (law == "mindlin") {
      for (const char* k : {"fretting_yield_point", "hardening_coefficient"}) {
        if (t.get(k)) {
          throw InvalidInput(fmt::format(
              "{}.{} is used only with tangential = \"odfalk_vingsbo\"{}", w, k, at_line(t)));
        }
      }
      return make_rough_flat_element(std::move(b), std::move(d));
    }
    if (law != "odfalk_vingsbo") {
      throw InvalidInput(
          fmt::format("{}.tangential = \"{}\": use \"mindlin\" (Cattaneo-Mindlin, the default) or "
                      "\"odfalk_vingsbo\" (Eq. 3.10, with measured fretting_yield_point and "
                      "hardening_coefficient){}",
                      w, law, at_line(t)));
    }
    for (const char* k : {"fretting_yield_point", "hardening_coefficient"}) {
      if (!t.get(k)) {
        throw InvalidInput(fmt::format(
            "{}: tangential = \"odfalk_vingsbo\" needs {} (the Odfalk-Vingsbo law's fretting "
            "yield point Q_ty and hardening coefficient k_p are measured on the joint: the thesis "
            "says they could not be generalized, and asperity never supplies them){}",
            w, k, at_line(t)));
      }
    }
    const std::string what = "tangential = \"odfalk_vingsbo\"";
    const hysteresis::OdfalkVingsboParameters p{
        need_si(t, "fretting_yield_point", w, dim::force, what),
        need_si(t, "hardening_coefficient", w, dim::stiffness, what)};
    return make_odfalk_vingsbo_element(std::move(b), p, std::move(d));
  };
  auto friction_of = [&](contact::FrictionParameters fp) {
    if (t.get("mu_cfc")) fp.mu_cfc = number(t, "mu_cfc", w, fp.mu_cfc);
    return fp;
  };
  if (bb == "joint") {
    check_keys(t, w, with({}));
    for (const auto& k : law_keys) {
      if (t.get(k)) {
        throw InvalidInput(fmt::format(
            "{}.{}: with backbone = \"joint\" the tangential law is the joint's: set it in "
            "[interface] (tangential, fretting_yield_point, hardening_coefficient){}",
            w, k, at_line(t)));
      }
    }
    if (!joint) {
      throw InvalidInput(fmt::format(
          "{}: backbone = \"joint\" needs a [joint] table (and [load]) as for `asperity predict`{}",
          w, at_line(t)));
    }
    SummaryObject d{{"type", "rough_flat"}, {"backbone", "joint"}};
    add_backbone_summary(d, *joint->backbone,
                         std::get<double>(SummaryValue(joint->summary).find("preload_N")->data));
    if (joint->odfalk_vingsbo) {
      return make_odfalk_vingsbo_element(joint->backbone, *joint->odfalk_vingsbo, std::move(d));
    }
    return make_rough_flat_element(joint->backbone, std::move(d));
  }
  if (bb == "dimensional") {
    check_keys(t, w,
               with({"E_star", "G_star", "H", "nu", "sigma", "R", "eta", "A0", "P",
                     "asperity_model", "mu_cfc"}));
    const std::string what = "a dimensional rough_flat";
    dynamics::EpbContact c{.E_star = need_si(t, "E_star", w, dim::pressure, what),
                           .G_star = need_si(t, "G_star", w, dim::pressure, what),
                           .H = need_si(t, "H", w, dim::pressure, what),
                           .nu = 0.3,
                           .sigma = need_si(t, "sigma", w, dim::length, what),
                           .R = need_si(t, "R", w, dim::length, what),
                           .eta = need_si(t, "eta", w, dim::inverse_area, what),
                           .A0 = need_si(t, "A0", w, dim::area, what),
                           .P = need_si(t, "P", w, dim::force, what),
                           .model = core::toml_case::named_choice(t, "asperity_model", w, "bke",
                                                                  contact::parse_model_name),
                           .friction = {}};
    if (!t.get("nu")) throw InvalidInput(fmt::format("{}: {} needs nu{}", w, what, at_line(t)));
    c.nu = number(t, "nu", w, 0.3);
    c.friction = friction_of(c.friction);
    const auto b = dynamics::epb_backbone(c);
    SummaryObject d{{"type", "rough_flat"},
                    {"backbone", "dimensional"},
                    {"asperity_model", std::string(contact::to_string(c.model))},
                    {"E_star_Pa", c.E_star},
                    {"G_star_Pa", c.G_star},
                    {"H_Pa", c.H},
                    {"nu", c.nu},
                    {"sigma_m", c.sigma},
                    {"R_m", c.R},
                    {"eta_per_m2", c.eta},
                    {"A0_m2", c.A0}};
    add_backbone_summary(d, *b, c.P);
    return element_of(b, std::move(d));
  }
  if (bb == "normalized") {
    check_keys(t, w,
               with({"beta", "psi", "nu", "G_over_E", "P_star", "sigma", "force_scale",
                     "asperity_model", "mu_cfc"}));
    for (const char* k : {"beta", "psi", "nu", "G_over_E", "P_star", "sigma", "force_scale"}) {
      if (!t.get(k)) {
        throw InvalidInput(fmt::format(
            "{}: a normalized rough_flat needs {} (beta, psi, nu, G_over_E, P_star = P/(K H A0), "
            "and the SI scales sigma [m] and force_scale = K H A0 [N]){}",
            w, k, at_line(t)));
      }
    }
    surface::RoughFlatParameters rp;
    rp.model =
        core::toml_case::named_choice(t, "asperity_model", w, "bke", contact::parse_model_name);
    rp.beta = number(t, "beta", w, 0.0);
    rp.psi = number(t, "psi", w, 0.0);
    rp.nu = number(t, "nu", w, 0.3);
    rp.G_over_E = number(t, "G_over_E", w, 0.0);
    rp.friction = friction_of(rp.friction);
    const double P_star = number(t, "P_star", w, 0.0);
    const double sigma = *si(t, "sigma", w, dim::length);
    const double force_scale = *si(t, "force_scale", w, dim::force);
    core::require_positive(w + ".P_star", P_star);
    core::require_positive(w + ".sigma", sigma);
    core::require_positive(w + ".force_scale", force_scale);
    const surface::RoughFlat flat(rp);
    const double d_star = flat.separation_star(P_star);
    const auto b =
        std::make_shared<hysteresis::ScaledBackbone>(flat.backbone(d_star), sigma, force_scale);
    SummaryObject d{{"type", "rough_flat"},
                    {"backbone", "normalized"},
                    {"asperity_model", std::string(contact::to_string(rp.model))},
                    {"beta", rp.beta},
                    {"psi", rp.psi},
                    {"nu", rp.nu},
                    {"G_over_E", rp.G_over_E},
                    {"P_star", P_star},
                    {"d_star", d_star},
                    {"sigma_m", sigma},
                    {"force_scale_N", force_scale}};
    add_backbone_summary(d, *b, P_star * force_scale);
    return element_of(b, std::move(d));
  }
  throw InvalidInput(
      fmt::format("{}.backbone = \"{}\": use \"dimensional\", \"normalized\" or \"joint\"{}", w, bb,
                  at_line(t)));
}

// A masing_table element: the backbone from `table` (a CSV file with columns delta or x
// [length] and Q or force [force], units in the header, as `asperity predict --out` writes
// backbones.csv; with a preload column, `preload` selects its rows) or from inline
// `displacement` [m] and `force` [N] arrays.
std::shared_ptr<const Element> masing_table_element(const toml::table& t, const std::string& w,
                                                    const std::string& base_dir) {
  const bool file = t.get("table") != nullptr;
  const bool inline_table = t.get("displacement") || t.get("force");
  if (file == inline_table) {
    throw InvalidInput(fmt::format(
        "{}: a masing_table element needs its backbone: table = \"backbone.csv\" (columns "
        "delta[um],Q[N]) or displacement = [...] (m) and force = [...] (N), not both{}",
        w, at_line(t)));
  }
  if (!file) {
    std::vector<double> x, Q;
    for (const auto& [key, out] : {std::pair{"displacement", &x}, std::pair{"force", &Q}}) {
      const auto* a = t.get(key) ? t.get(key)->as_array() : nullptr;
      if (!a) {
        throw InvalidInput(fmt::format("{}.{}: needs an array of numbers (SI: {}){}", w, key,
                                       std::string_view(key) == "force" ? "N" : "m", at_line(t)));
      }
      for (std::size_t i = 0; i < a->size(); ++i) {
        const auto v = plain_number(*a->get(i));
        if (!v) {
          throw InvalidInput(
              fmt::format("{}.{}[{}]: not a number{}", w, key, i + 1, at_line(*a->get(i))));
        }
        out->push_back(*v);
      }
    }
    return make_masing_table_element(std::move(x), std::move(Q), w);
  }
  std::filesystem::path path(text(t, "table", w, ""));
  if (path.is_relative()) path = std::filesystem::path(base_dir) / path;
  const auto table = core::read_csv_table(path.string());
  auto column = [&](std::initializer_list<const char*> names) -> const core::CsvColumn* {
    for (const char* n : names)
      if (const auto* c = table.find(n)) return c;
    return nullptr;
  };
  const auto* cx = column({"delta", "x", "displacement"});
  const auto* cq = column({"Q", "force"});
  if (!cx || !cq) {
    throw InvalidInput(fmt::format(
        "{}.table: {} needs a displacement column (delta, x or displacement, with a length unit) "
        "and a force column (Q or force){}",
        w, path.string(), at_line(t)));
  }
  auto x = table.si_values(*cx, dim::length);
  auto Q = table.si_values(*cq, dim::force);
  const auto* cp = table.find("preload");
  const auto want = si(t, "preload", w, dim::force);
  if (cp) {
    const auto P = table.si_values(*cp, dim::force);
    std::vector<double> preloads;
    for (double p : P)
      if (std::find(preloads.begin(), preloads.end(), p) == preloads.end()) preloads.push_back(p);
    if (!want && preloads.size() > 1) {
      std::string list;
      for (double p : preloads) list += fmt::format("{}{:.6g} N", list.empty() ? "" : ", ", p);
      throw InvalidInput(fmt::format(
          "{}: {} holds the backbones of {} preloads ({}): choose one with preload = \"...\"{}", w,
          path.string(), preloads.size(), list, at_line(t)));
    }
    // A table holds at least one row (read_csv_table), so preloads is not empty.
    const double chosen = want.value_or(preloads.empty() ? 0.0 : preloads[0]);
    std::vector<double> xs, Qs;
    for (std::size_t i = 0; i < P.size(); ++i) {
      // The file prints 12 digits: a preload typed back matches to 1e-9.
      if (std::abs(P[i] - chosen) <= 1e-9 * std::abs(chosen)) {
        xs.push_back(x[i]);
        Qs.push_back(Q[i]);
      }
    }
    if (xs.empty()) {
      std::string list;
      for (double p : preloads) list += fmt::format("{}{:.6g} N", list.empty() ? "" : ", ", p);
      throw InvalidInput(fmt::format("{}.preload = {:.6g} N: {} has the preloads {}{}", w, chosen,
                                     path.string(), list, at_line(t)));
    }
    x = std::move(xs);
    Q = std::move(Qs);
  } else if (want) {
    throw InvalidInput(
        fmt::format("{}.preload: {} has no preload column{}", w, path.string(), at_line(t)));
  }
  return make_masing_table_element(std::move(x), std::move(Q), path.string());
}

}  // namespace

JointBackbone joint_backbone(const std::string& path, const std::string& base_dir,
                             const std::string& file_text, const toml::table& root) {
  const joint::JointCase jc = joint::parse_case(joint_text(file_text, root), path, base_dir);
  const auto load_line = root.get("load")        ? root.get("load")->source().begin.line
                         : root.get("interface") ? root.get("interface")->source().begin.line
                                                 : 0;
  const joint::LoadPrediction lp = joint::predict_single_load(
      jc, fmt::format("{}:{}: load: ", path, load_line), "a rough_flat element takes");
  const double P = jc.preloads.front();
  JointBackbone j;
  j.backbone = lp.backbone;
  j.summary = SummaryObject{{"name", jc.name},
                            {"model", std::string(contact::to_string(jc.model))},
                            {"area_m2", jc.area},
                            {"preload_N", P},
                            {"separation_m", lp.separation},
                            {"Q_max_N", lp.Q_max},
                            {"mu", lp.mu},
                            {"stiffness_N_per_m", lp.stiffness}};
  j.odfalk_vingsbo = lp.odfalk_vingsbo;
  return j;
}

PlacedElement parse_element(const toml::table& t, std::size_t index, Eigen::Index dofs,
                            const std::optional<JointBackbone>& joint, const std::string& base_dir,
                            const fem::ReducedModel* model) {
  const std::string w = fmt::format("element[{}]", index + 1);
  if (!t.get("type")) {
    throw InvalidInput(fmt::format(
        "{}: needs type = \"rough_flat\" | \"jenkins\" | \"iwan4\" | \"masing_table\" | "
        "\"coulomb\" | \"elastic_dry_friction_2d\" | \"polynomial_stiffness\" | "
        "\"cubic_damping\" | \"unilateral_spring\" | \"elastic_dry_friction_3d\" | "
        "\"rough_contact\"{}",
        w, at_line(t)));
  }
  const std::string type = text(t, "type", w, "");
  const std::set<std::string> common{"type", "name", "T"};
  auto keys = [&](std::set<std::string> k) {
    k.insert(common.begin(), common.end());
    return k;
  };
  const Dimension force = dim::force, stiffness = dim::stiffness;
  std::shared_ptr<const Element> e;
  if (type == "jenkins") {
    check_keys(t, w, keys({"k_t", "F_s"}));
    e = make_jenkins_element(need_si(t, "k_t", w, stiffness, "a jenkins element"),
                             need_si(t, "F_s", w, force, "a jenkins element"));
  } else if (type == "coulomb") {
    check_keys(t, w, keys({"F_s", "k_tan"}));
    e = make_coulomb_element(need_si(t, "F_s", w, force, "a coulomb element"),
                             need_si(t, "k_tan", w, Dimension{-1, 0, 1}, "a coulomb element"));
  } else if (type == "iwan4") {
    check_keys(t, w, keys({"F_S", "K_T", "chi", "beta"}));
    for (const char* k : {"chi", "beta"}) {
      if (!t.get(k)) {
        throw InvalidInput(fmt::format(
            "{}: an iwan4 element needs {} (Segalman's four parameters F_S, K_T, chi in (-1, 0], "
            "beta >= 0 are all required; e.g. chi = -0.5, beta = 0.1){}",
            w, k, at_line(t)));
      }
    }
    dynamics::SegalmanIwanParameters p{.F_S = need_si(t, "F_S", w, force, "an iwan4 element"),
                                       .K_T = need_si(t, "K_T", w, stiffness, "an iwan4 element"),
                                       .chi = number(t, "chi", w, 0.0),
                                       .beta = number(t, "beta", w, 0.0)};
    e = make_iwan4_element(p);
  } else if (type == "elastic_dry_friction_2d") {
    check_keys(t, w, keys({"k_t", "k_n", "mu", "N0"}));
    const std::string what = "an elastic_dry_friction_2d element";
    if (!t.get("mu")) throw InvalidInput(fmt::format("{}: {} needs mu{}", w, what, at_line(t)));
    ElasticDryFriction2dParameters p{.k_t = need_si(t, "k_t", w, stiffness, what),
                                     .k_n = need_si(t, "k_n", w, stiffness, what),
                                     .mu = number(t, "mu", w, 0.0),
                                     .N0 = si(t, "N0", w, force).value_or(0.0)};
    e = make_elastic_dry_friction_2d_element(p);
  } else if (type == "polynomial_stiffness") {
    check_keys(t, w, keys({"k1", "k2", "k3"}));
    PolynomialStiffnessParameters p{.k1 = si(t, "k1", w, stiffness).value_or(0.0),
                                    .k2 = si(t, "k2", w, Dimension{-1, 1, -2}).value_or(0.0),
                                    .k3 = si(t, "k3", w, Dimension{-2, 1, -2}).value_or(0.0)};
    if (p.k1 == 0.0 && p.k2 == 0.0 && p.k3 == 0.0) {
      throw InvalidInput(fmt::format(
          "{}: a polynomial_stiffness element needs k1 [N/m], k2 [N/m^2] or k3 [N/m^3] (f = k1 u "
          "+ k2 u^2 + k3 u^3; Duffing: k3){}",
          w, at_line(t)));
    }
    e = make_polynomial_stiffness_element(p);
  } else if (type == "cubic_damping") {
    check_keys(t, w, keys({"c3"}));
    e = make_cubic_damping_element(
        need_si(t, "c3", w, Dimension{-2, 1, 1}, "a cubic_damping element (f = c3 v^3)"));
  } else if (type == "elastic_dry_friction_3d") {
    check_keys(t, w, keys({"k_t", "k_n", "mu", "N0"}));
    const std::string what = "an elastic_dry_friction_3d element";
    if (!t.get("mu")) throw InvalidInput(fmt::format("{}: {} needs mu{}", w, what, at_line(t)));
    ElasticDryFriction3dParameters p{.k_t = need_si(t, "k_t", w, stiffness, what),
                                     .k_n = need_si(t, "k_n", w, stiffness, what),
                                     .mu = number(t, "mu", w, 0.0),
                                     .N0 = si(t, "N0", w, force).value_or(0.0)};
    e = make_elastic_dry_friction_3d_element(p);
  } else if (type == "unilateral_spring") {
    check_keys(t, w, keys({"k", "gap", "N0"}));
    UnilateralSpringParameters p{
        .k = need_si(t, "k", w, stiffness,
                     "a unilateral_spring element (f = max(N0 + k (u - gap), 0))"),
        .gap = si(t, "gap", w, dim::length).value_or(0.0),
        .N0 = si(t, "N0", w, force).value_or(0.0)};
    e = make_unilateral_spring_element(p);
  } else if (type == "rough_flat") {
    e = rough_flat_element(t, w, joint);
  } else if (type == "masing_table") {
    check_keys(t, w, keys({"table", "preload", "displacement", "force"}));
    e = masing_table_element(t, w, base_dir);
  } else if (type == "rough_contact") {
    check_keys(t, w,
               keys({"E_star", "G_star", "H", "nu", "sigma", "R", "eta", "asperity_model", "mu_cfc",
                     "pressure", "area", "summit_heights"}));
    const std::string what = "a rough_contact element";
    if (!t.get("nu")) throw InvalidInput(fmt::format("{}: {} needs nu{}", w, what, at_line(t)));
    // A measured summit-height table (Eq. 4.4 over it): its standard deviation is sigma.
    std::shared_ptr<const surface::SummitHeightTable> heights;
    if (t.get("summit_heights")) {
      if (t.get("sigma"))
        throw InvalidInput(
            fmt::format("{}: give sigma or summit_heights (whose standard deviation is the "
                        "summits' sigma), not both{}",
                        w, at_line(t)));
      const std::string file =
          (std::filesystem::path(base_dir) / text(t, "summit_heights", w, "")).string();
      try {
        heights = std::make_shared<const surface::SummitHeightTable>(
            surface::read_summit_height_table(file));
      } catch (const InvalidInput& err) {
        throw InvalidInput(fmt::format("{}.summit_heights: {}{}", w, err.what(), at_line(t)));
      }
    }
    RoughInterfaceParameters rp{.E_star = need_si(t, "E_star", w, dim::pressure, what),
                                .G_star = need_si(t, "G_star", w, dim::pressure, what),
                                .H = need_si(t, "H", w, dim::pressure, what),
                                .nu = number(t, "nu", w, 0.3),
                                .sigma = heights ? heights->standard_deviation()
                                                 : need_si(t, "sigma", w, dim::length, what),
                                .R = need_si(t, "R", w, dim::length, what),
                                .eta = need_si(t, "eta", w, dim::inverse_area, what),
                                .model = core::toml_case::named_choice(
                                    t, "asperity_model", w, "bke", contact::parse_model_name),
                                .friction = {},
                                .summit_sigma = heights != nullptr,
                                .summit_heights = heights};
    if (t.get("mu_cfc")) rp.friction.mu_cfc = number(t, "mu_cfc", w, 0.0);
    const double p0 = need_si(t, "pressure", w, dim::pressure, what);
    const double area = need_si(t, "area", w, dim::area, what);
    // Tables from p0/8 to 8 p0 (48 backbones): the normal pressure of a vibrating element
    // stays within them unless it nearly opens (below: shape frozen, scaled) or is pressed
    // eight times harder than by its prestress (refused, naming the element).
    core::require_positive(w + ".pressure", p0);
    const auto surface = std::make_shared<const RoughContactSurface>(rp, p0 / 8.0, p0 * 8.0);
    e = std::make_shared<RoughContactElement>(surface, area, p0, w);
  } else {
    throw InvalidInput(
        fmt::format("{}.type = \"{}\" is not known: use rough_flat, jenkins, iwan4, masing_table, "
                    "coulomb, elastic_dry_friction_2d, polynomial_stiffness, cubic_damping, "
                    "unilateral_spring, elastic_dry_friction_3d or rough_contact{}",
                    w, type, at_line(t)));
  }
  PlacedElement pe;
  pe.element = e;
  pe.name = text(t, "name", w, fmt::format("element {}", index + 1));
  const auto* T = t.get("T");
  if (!T) {
    throw InvalidInput(fmt::format(
        "{}: needs T, the map from the structure's {} DOFs to the element's {} direction(s) (one "
        "row per direction){}",
        w, dofs, e->directions(), at_line(t)));
  }
  if (const auto* ref = T->as_table()) {
    // Rows of the reduced model's Q: an interface element's relative displacements.
    if (!model)
      throw InvalidInput(fmt::format(
          "{}.T names an interface element, which needs [structure] model = \"FILE\" (a reduced "
          "model of `asperity structure`){}",
          w, at_line(*T)));
    check_keys(*ref, w + ".T", {"interface_element", "directions"});
    const auto ne = static_cast<std::int64_t>(model->elements.size());
    const auto* ie = ref->get("interface_element");
    const auto e_idx = ie ? ie->value<std::int64_t>() : std::nullopt;
    if (!e_idx || !ie->is_integer() || *e_idx < 0 || *e_idx >= ne)
      throw InvalidInput(
          fmt::format("{}.T.interface_element: give an element index 0 .. {} of the "
                      "reduced model{}",
                      w, ne - 1, at_line(*T)));
    const auto* dirs = ref->get("directions") ? ref->get("directions")->as_array() : nullptr;
    if (!dirs || dirs->empty())
      throw InvalidInput(
          fmt::format("{}.T.directions: list the element directions, e.g. [\"t1\", "
                      "\"n\"] (t1, t2 tangential, n normal){}",
                      w, at_line(*T)));
    pe.T.resize(static_cast<Eigen::Index>(dirs->size()), dofs);
    for (std::size_t k = 0; k < dirs->size(); ++k) {
      const auto d = (*dirs)[k].value<std::string>();
      // "-n": the closure (the negative of Q's normal row, the opening), as rough_contact takes.
      const int col = !d           ? -1
                      : *d == "t1" ? 0
                      : *d == "t2" ? 1
                      : *d == "n"  ? 2
                      : *d == "-n" ? 3
                                   : -1;
      if (col < 0)
        throw InvalidInput(fmt::format(
            "{}.T.directions[{}]: use \"t1\", \"t2\", \"n\" (opening) or \"-n\" (closure){}", w,
            k + 1, at_line(*T)));
      pe.T.row(static_cast<Eigen::Index>(k)) =
          col == 3 ? Eigen::RowVectorXd(-model->Q.row(3 * *e_idx + 2))
                   : Eigen::RowVectorXd(model->Q.row(3 * *e_idx + col));
    }
  } else {
    pe.T = matrix(*T, w + ".T", true);
  }
  if (pe.T.cols() != dofs) {
    throw InvalidInput(fmt::format(
        "{}.T has {} column(s) but the structure has {} DOFs: give one column per DOF{}", w,
        pe.T.cols(), dofs, at_line(*T)));
  }
  if (pe.T.rows() != static_cast<Eigen::Index>(e->directions())) {
    throw InvalidInput(fmt::format(
        "{}.T has {} row(s) but a {} element has {} direction(s): give one row per direction{}", w,
        pe.T.rows(), type, e->directions(), at_line(*T)));
  }
  if (pe.T.cwiseAbs().maxCoeff() == 0.0) {
    throw InvalidInput(
        fmt::format("{}.T is zero: the element would not touch the structure{}", w, at_line(*T)));
  }
  return pe;
}

bool places_every_interface_element(const toml::table& t) {
  const auto* T = t.get("T") ? t.get("T")->as_table() : nullptr;
  const auto* ie = T ? T->get("interface_element") : nullptr;
  return ie && ie->value<std::string>() == "all";
}

std::vector<PlacedElement> parse_interface_rough_contact(const toml::table& t, std::size_t index,
                                                         Eigen::Index dofs,
                                                         const fem::ReducedModel* model,
                                                         std::vector<std::string>& warnings,
                                                         std::vector<ElementSite>& sites) {
  const std::string w = fmt::format("element[{}]", index + 1);
  if (text(t, "type", w, "") != "rough_contact") {
    throw InvalidInput(
        fmt::format("{}.T.interface_element = \"all\" places rough_contact elements only (type = "
                    "\"rough_contact\"); other types take one interface element each{}",
                    w, at_line(t)));
  }
  check_keys(t, w, {"type", "name", "T", "asperity_model", "mu_cfc"});
  if (!model || !model->rough) {
    throw InvalidInput(fmt::format(
        "{}.T.interface_element = \"all\" needs [structure] model = \"FILE\" written by "
        "`asperity structure` with a [rough_contact] table (the file holds the rough surface and "
        "each element's prestress pressure){}",
        w, at_line(t)));
  }
  const auto& T = *t.get("T")->as_table();
  check_keys(T, w + ".T", {"interface_element", "directions"});
  if (const auto* d = T.get("directions")) {
    const auto* a = d->as_array();
    const bool standard = a && a->size() == 3 && (*a)[0].value<std::string>() == "t1" &&
                          (*a)[1].value<std::string>() == "t2" &&
                          (*a)[2].value<std::string>() == "-n";
    if (!standard)
      throw InvalidInput(fmt::format(
          "{}.T.directions: rough_contact elements on every interface element take [\"t1\", "
          "\"t2\", \"-n\"] (the default: tangential, then the closure){}",
          w, at_line(T)));
  }
  contact::FrictionParameters friction{};
  if (t.get("mu_cfc")) friction.mu_cfc = number(t, "mu_cfc", w, 0.0);
  const fem::RoughInterfaceRecord& r = *model->rough;
  auto placed = interface_rough_contact(
      *model,
      core::toml_case::named_choice(t, "asperity_model", w, r.model, contact::parse_model_name),
      friction, text(t, "name", w, "interface element"), w);
  if (placed.elements.size() < static_cast<std::size_t>(r.pressure.size())) {
    warnings.push_back(fmt::format(
        "{}: {} of the {} interface elements are out of contact at the rough prestress (less "
        "than one asperity expected in contact) and are left out",
        w, static_cast<std::size_t>(r.pressure.size()) - placed.elements.size(),
        r.pressure.size()));
  }
  for (const Eigen::Index e : placed.interface_elements) {
    const fem::InterfaceElement& ie = model->elements[static_cast<std::size_t>(e)];
    sites.push_back({.interface_element = e, .centroid = ie.centroid, .area = ie.area});
  }
  if (model->dofs() != dofs) {
    throw InvalidInput(fmt::format("{}: the reduced model has {} DOFs, the structure {}{}", w,
                                   model->dofs(), dofs, at_line(t)));
  }
  return std::move(placed.elements);
}

}  // namespace asperity::vibration::detail
