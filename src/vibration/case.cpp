#include "asperity/vibration/case.hpp"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include "../core/toml_case.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/units.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/dynamics/epb.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/surface/rough_flat.hpp"

namespace asperity::vibration {

namespace {

using core::Dimension;
namespace dim = core::dim;
using core::toml_case::at_line;
using core::toml_case::check_keys;
using core::toml_case::collect_lines;
using core::toml_case::line_of;
using core::toml_case::number;
using core::toml_case::subtable;

std::optional<double> plain_number(const toml::node& n) {
  if (n.is_floating_point() || n.is_integer()) return n.value<double>();
  return std::nullopt;
}

// A whole number in [lo, hi].
long long integer(const toml::table& t, const std::string& key, const std::string& where,
                  long long dflt, long long lo, long long hi) {
  const auto* n = t.get(key);
  if (!n) return dflt;
  const auto x = n->value<long long>();
  if (!n->is_integer() || !x) {
    throw InvalidInput(fmt::format("{}.{} must be a whole number{}", where, key, at_line(*n)));
  }
  if (*x < lo || *x > hi) {
    throw InvalidInput(
        fmt::format("{}.{} = {} must lie in [{}, {}]{}", where, key, *x, lo, hi, at_line(*n)));
  }
  return *x;
}

std::string text(const toml::table& t, const std::string& key, const std::string& where,
                 const std::string& dflt) {
  const auto* n = t.get(key);
  if (!n) return dflt;
  if (auto x = n->value<std::string>()) return *x;
  throw InvalidInput(fmt::format("{}.{} must be a string{}", where, key, at_line(*n)));
}

// An SI value: a plain number (SI) or a quantity string with units of dimension d.
std::optional<double> si(const toml::table& t, const std::string& key, const std::string& where,
                         Dimension d) {
  const auto* n = t.get(key);
  if (!n) return std::nullopt;
  const std::string field = where + "." + key;
  if (auto x = plain_number(*n)) {
    if (!std::isfinite(*x))
      throw InvalidInput(fmt::format("{} = {} must be finite{}", field, *x, at_line(*n)));
    return *x;
  }
  if (auto s = n->value<std::string>()) return core::parse_quantity(*s, d, field);
  throw InvalidInput(
      fmt::format("{} must be a number (SI) or a quantity string with units, e.g. "
                  "\"2.5e7 N/m\"{}",
                  field, at_line(*n)));
}

double need_si(const toml::table& t, const std::string& key, const std::string& where, Dimension d,
               const std::string& what) {
  auto v = si(t, key, where, d);
  if (!v) throw InvalidInput(fmt::format("{}: {} needs {}{}", where, what, key, at_line(t)));
  return *v;
}

// A matrix written as an array of rows (or, with `allow_vector`, one row as a flat list).
Eigen::MatrixXd matrix(const toml::node& n, const std::string& field, bool allow_vector) {
  const auto* a = n.as_array();
  if (!a || a->empty()) {
    throw InvalidInput(
        fmt::format("{} must be a non-empty array of rows, e.g. [[1.0, 0.0], [0.0, "
                    "1.0]]{}",
                    field, at_line(n)));
  }
  if (allow_vector && !a->get(0)->is_array()) {
    Eigen::MatrixXd m(1, static_cast<Eigen::Index>(a->size()));
    for (std::size_t j = 0; j < a->size(); ++j) {
      const auto x = plain_number(*a->get(j));
      if (!x || !std::isfinite(*x)) {
        throw InvalidInput(
            fmt::format("{}[{}] must be a finite number{}", field, j, at_line(*a->get(j))));
      }
      m(0, static_cast<Eigen::Index>(j)) = *x;
    }
    return m;
  }
  std::size_t cols = 0;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto* row = a->get(i)->as_array();
    if (!row || row->empty()) {
      throw InvalidInput(fmt::format("{}[{}] must be a non-empty array of numbers (a row){}", field,
                                     i, at_line(*a->get(i))));
    }
    if (i == 0) cols = row->size();
    if (row->size() != cols) {
      throw InvalidInput(
          fmt::format("{}: row {} has {} entries, row 0 has {}: every row needs the "
                      "same number of columns{}",
                      field, i, row->size(), cols, at_line(*row)));
    }
  }
  Eigen::MatrixXd m(static_cast<Eigen::Index>(a->size()), static_cast<Eigen::Index>(cols));
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto* row = a->get(i)->as_array();
    for (std::size_t j = 0; j < cols; ++j) {
      const auto x = plain_number(*row->get(j));
      if (!x || !std::isfinite(*x)) {
        throw InvalidInput(fmt::format("{}[{}][{}] must be a finite number{}", field, i, j,
                                       at_line(*row->get(j))));
      }
      m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = *x;
    }
  }
  return m;
}

// `key` inline or `key_file` (MatrixMarket, relative to base_dir); nullopt if neither.
std::optional<Eigen::MatrixXd> structure_matrix(const toml::table& t, const std::string& key,
                                                const std::string& base_dir) {
  const auto* inl = t.get(key);
  const auto* file = t.get(key + "_file");
  if (inl && file) {
    throw InvalidInput(
        fmt::format("structure: give {} or {}_file, not both{}", key, key, at_line(*file)));
  }
  if (inl) return matrix(*inl, "structure." + key, false);
  if (!file) return std::nullopt;
  const std::string name = text(t, key + "_file", "structure", "");
  std::filesystem::path p(name);
  if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
  return read_matrix_market(p.lexically_normal().string());
}

// {from = .., to = ..} with `convert` turning each node into a value.
std::pair<double, double> range(
    const toml::table& t, const std::string& key, const std::string& where,
    const std::function<double(const toml::node&, const std::string&)>& convert) {
  const auto* n = t.get(key);
  if (!n) {
    throw InvalidInput(
        fmt::format("{} needs {} = {{ from = .., to = .. }}{}", where, key, at_line(t)));
  }
  const auto* r = n->as_table();
  if (!r) {
    throw InvalidInput(
        fmt::format("{}.{} must be a table {{ from = .., to = .. }}{}", where, key, at_line(*n)));
  }
  const std::string w = where + "." + key;
  check_keys(*r, w, {"from", "to"});
  for (const char* k : {"from", "to"}) {
    if (!r->get(k)) throw InvalidInput(fmt::format("{} needs {}{}", w, k, at_line(*r)));
  }
  return {convert(*r->get("from"), w + ".from"), convert(*r->get("to"), w + ".to")};
}

double finite_number(const toml::node& n, const std::string& field) {
  const auto x = plain_number(n);
  if (!x || !std::isfinite(*x))
    throw InvalidInput(fmt::format("{} must be a finite number{}", field, at_line(n)));
  return *x;
}

// Angular frequency [rad/s]: a number (rad/s), or a quantity in Hz (times 2 pi) or rad/s.
double angular_frequency(const toml::node& n, const std::string& field) {
  if (auto s = n.value<std::string>()) {
    const double v = core::parse_quantity(*s, dim::frequency, field);
    if (s->find("Hz") != std::string::npos) return 2.0 * std::numbers::pi * v;
    if (s->find("rad") != std::string::npos) return v;
    throw InvalidInput(fmt::format(
        "{} = \"{}\": write the frequency in Hz (\"10 Hz\") or in rad/s (\"62.8 rad/s\"), or as a "
        "number in rad/s{}",
        field, *s, at_line(n)));
  }
  return finite_number(n, field);
}

void parse_continuation(const toml::table& t, const std::string& where, ContinuationOptions& c) {
  const auto* ct = subtable(t, "continuation", where);
  if (!ct) return;
  const std::string w = where + ".continuation";
  check_keys(*ct, w,
             {"step", "min_step", "max_step", "max_points", "target_iterations", "max_angle",
              "max_iterations", "step_tolerance", "residual_tolerance"});
  c.step = number(*ct, "step", w, c.step);
  c.min_step = number(*ct, "min_step", w, c.min_step);
  c.max_step = number(*ct, "max_step", w, std::max(c.max_step, c.step));
  c.max_points = static_cast<std::size_t>(
      integer(*ct, "max_points", w, static_cast<long long>(c.max_points), 2, 1000000));
  c.target_iterations =
      static_cast<int>(integer(*ct, "target_iterations", w, c.target_iterations, 1, 1000));
  c.max_angle = number(*ct, "max_angle", w, c.max_angle);
  c.newton.max_iterations =
      static_cast<int>(integer(*ct, "max_iterations", w, c.newton.max_iterations, 1, 1000));
  c.newton.step_tolerance = number(*ct, "step_tolerance", w, c.newton.step_tolerance);
  c.newton.residual_tolerance = number(*ct, "residual_tolerance", w, c.newton.residual_tolerance);
  try {
    c.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: {}", w, e.what()));
  }
}

// ---- [joint] ---------------------------------------------------------------------------

// Lines of the case file holding any part of `n`: table headers, keys and values.

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

struct JointBackbone {
  std::shared_ptr<const hysteresis::Backbone> backbone;
  SummaryObject summary;
};

JointBackbone joint_backbone(const std::string& path, const std::string& base_dir,
                             const std::string& file_text, const toml::table& root) {
  const joint::JointCase jc = joint::parse_case(joint_text(file_text, root), path, base_dir);
  const auto load_line = root.get("load")        ? root.get("load")->source().begin.line
                         : root.get("interface") ? root.get("interface")->source().begin.line
                                                 : 0;
  if (jc.preloads.size() != 1) {
    throw InvalidInput(fmt::format(
        "{}:{}: load: a rough_flat element takes one preload; the [load] table gives {} (a "
        "sweep): keep one",
        path, load_line, jc.preloads.size()));
  }
  const double P = jc.preloads.front();
  const joint::LoadPrediction lp = [&] {
    try {
      // Uniform, or the summed backbone of an [interface]'s patches (joint/interface.hpp).
      return joint::predict_case_load(jc, P);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}:{}: load: {}", path, load_line, e.what()));
    }
  }();
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
  return j;
}

// ---- elements --------------------------------------------------------------------------

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
  const std::set<std::string> common{"type", "name", "T", "backbone"};
  auto with = [&](std::set<std::string> keys) {
    keys.insert(common.begin(), common.end());
    return keys;
  };
  auto friction_of = [&](contact::FrictionParameters fp) {
    if (t.get("mu_cfc")) fp.mu_cfc = number(t, "mu_cfc", w, fp.mu_cfc);
    return fp;
  };
  if (bb == "joint") {
    check_keys(t, w, with({}));
    if (!joint) {
      throw InvalidInput(fmt::format(
          "{}: backbone = \"joint\" needs a [joint] table (and [load]) as for `asperity predict`{}",
          w, at_line(t)));
    }
    SummaryObject d{{"type", "rough_flat"}, {"backbone", "joint"}};
    add_backbone_summary(d, *joint->backbone,
                         std::get<double>(SummaryValue(joint->summary).find("preload_N")->data));
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
                           .model = contact::parse_model_name(text(t, "asperity_model", w, "bke")),
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
    return make_rough_flat_element(b, std::move(d));
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
    rp.model = contact::parse_model_name(text(t, "asperity_model", w, "bke"));
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
    return make_rough_flat_element(b, std::move(d));
  }
  throw InvalidInput(
      fmt::format("{}.backbone = \"{}\": use \"dimensional\", \"normalized\" or \"joint\"{}", w, bb,
                  at_line(t)));
}

PlacedElement parse_element(const toml::table& t, std::size_t index, Eigen::Index dofs,
                            const std::optional<JointBackbone>& joint) {
  const std::string w = fmt::format("element[{}]", index);
  if (!t.get("type")) {
    throw InvalidInput(
        fmt::format("{}: needs type = \"rough_flat\" | \"jenkins\" | \"iwan4\" | \"coulomb\" | "
                    "\"elastic_dry_friction_2d\"{}",
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
  } else if (type == "rough_flat") {
    e = rough_flat_element(t, w, joint);
  } else {
    throw InvalidInput(
        fmt::format("{}.type = \"{}\" is not known: use rough_flat, jenkins, iwan4, coulomb or "
                    "elastic_dry_friction_2d{}",
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
  pe.T = matrix(*T, w + ".T", true);
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

// The force coefficients of a [[frequency_response]] in the unknowns' layout.
Eigen::VectorXd force_vector(const HarmonicBasis& basis, Eigen::Index dofs,
                             const Eigen::MatrixXd& fc, const Eigen::MatrixXd& fs) {
  const auto nc = static_cast<Eigen::Index>(basis.coefficients());
  Eigen::VectorXd F = Eigen::VectorXd::Zero(nc * dofs);
  const auto& h = basis.harmonics();
  for (Eigen::Index r = 0; r < static_cast<Eigen::Index>(h.size()); ++r) {
    const int hr = h[static_cast<std::size_t>(r)];
    for (Eigen::Index d = 0; d < dofs; ++d) {
      if (r < fc.rows()) F(d * nc + basis.index_of(hr, 0)) = fc(r, d);
      if (r < fs.rows() && hr > 0) F(d * nc + basis.index_of(hr, 1)) = fs(r, d);
    }
  }
  return F;
}

}  // namespace

VibrationCase parse_case_text(const std::string& file_text, const std::string& path,
                              const std::string& base_dir) {
  toml::table root;
  try {
    root = toml::parse(file_text, path);
  } catch (const toml::parse_error& e) {
    throw InvalidInput(
        fmt::format("{}: {} (line {})", path, e.description(), e.source().begin.line));
  }
  check_keys(root, path,
             {"structure", "element", "harmonic_balance", "nonlinear_mode", "frequency_response",
              "quasi_static_mode", "joint", "load", "profiles", "interface"});
  if (!root.get("joint")) {
    for (const char* k : {"load", "profiles", "interface"}) {
      if (root.get(k)) {
        throw InvalidInput(
            fmt::format("{}: [{}] belongs to a [joint] table, which is missing (line {})", path, k,
                        root.get(k)->source().begin.line));
      }
    }
  }
  VibrationCase c;
  c.source = path;

  // [structure]
  const toml::table* st = subtable(root, "structure", "");
  if (!st) throw InvalidInput(fmt::format("{}: the case file needs a [structure] table", path));
  const std::string S = "structure";
  check_keys(*st, S,
             {"mass", "mass_file", "stiffness", "stiffness_file", "damping", "damping_file",
              "rayleigh", "output_dofs"});
  auto M = structure_matrix(*st, "mass", base_dir);
  auto K = structure_matrix(*st, "stiffness", base_dir);
  if (!M) throw InvalidInput(fmt::format("structure needs mass (or mass_file){}", at_line(*st)));
  if (!K) {
    throw InvalidInput(
        fmt::format("structure needs stiffness (or stiffness_file){}", at_line(*st)));
  }
  c.structure.M = std::move(*M);
  c.structure.K = std::move(*K);
  auto Cm = structure_matrix(*st, "damping", base_dir);
  if (const auto* r = subtable(*st, "rayleigh", S)) {
    if (Cm) {
      throw InvalidInput(
          fmt::format("structure: give damping (or damping_file) or rayleigh, not "
                      "both{}",
                      at_line(*r)));
    }
    check_keys(*r, S + ".rayleigh", {"alpha", "beta"});
    c.rayleigh.alpha = number(*r, "alpha", S + ".rayleigh", 0.0);
    c.rayleigh.beta = number(*r, "beta", S + ".rayleigh", 0.0);
    c.damping = "rayleigh";
  } else if (Cm) {
    c.structure.C = std::move(*Cm);
    c.damping = "matrix";
  }
  try {
    if (c.damping == "rayleigh") {
      // Sizes and symmetry first, so that the Rayleigh sum is well formed.
      c.structure.validate();
      c.structure.C = rayleigh(c.structure.M, c.structure.K, c.rayleigh);
    }
    c.structure.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: structure: {}", path, e.what()));
  }
  const Eigen::Index n = c.structure.dofs();
  if (const auto* od = st->get("output_dofs")) {
    const auto* a = od->as_array();
    if (!a || a->empty()) {
      throw InvalidInput(
          fmt::format("structure.output_dofs must be a non-empty list of DOFs (0 .. "
                      "{}){}",
                      n - 1, at_line(*od)));
    }
    for (std::size_t k = 0; k < a->size(); ++k) {
      const auto v = (*a)[k].value<long long>();
      if (!(*a)[k].is_integer() || !v || *v < 0 || *v >= n) {
        throw InvalidInput(fmt::format("structure.output_dofs[{}]: DOFs are numbered 0 .. {}{}", k,
                                       n - 1, at_line((*a)[k])));
      }
      c.output_dofs.push_back(static_cast<Eigen::Index>(*v));
    }
  } else {
    for (Eigen::Index d = 0; d < n; ++d) c.output_dofs.push_back(d);
  }

  // [joint] (for rough_flat elements)
  std::optional<JointBackbone> joint;
  if (root.get("joint")) {
    joint = joint_backbone(path, base_dir, file_text, root);
    c.joint = joint->summary;
  }

  // [[element]]
  if (const auto* en = root.get("element")) {
    const auto* arr = en->as_array();
    if (!arr || !arr->is_array_of_tables()) {
      throw InvalidInput(
          fmt::format("element must be an array of tables: write [[element]]{}", at_line(*en)));
    }
    for (std::size_t k = 0; k < arr->size(); ++k) {
      c.elements.push_back(parse_element(*arr->get(k)->as_table(), k, n, joint));
    }
  }
  if (joint) {
    const bool used = std::any_of(c.elements.begin(), c.elements.end(), [](const auto& e) {
      const SummaryValue described(e.element->describe());  // find() points into it
      const auto* b = described.find("backbone");
      return b && std::holds_alternative<std::string>(b->data) &&
             std::get<std::string>(b->data) == "joint";
    });
    if (!used) {
      throw InvalidInput(fmt::format(
          "{}: the [joint] table is not used: add an [[element]] with type = \"rough_flat\" and "
          "backbone = \"joint\", or remove [joint]",
          path));
    }
  }

  // [harmonic_balance]
  if (const auto* hb = subtable(root, "harmonic_balance", "")) {
    const std::string w = "harmonic_balance";
    check_keys(*hb, w, {"harmonics", "max", "time_points"});
    if (hb->get("harmonics") && hb->get("max")) {
      throw InvalidInput(
          fmt::format("harmonic_balance: give harmonics or max, not both{}", at_line(*hb)));
    }
    if (const auto* hn = hb->get("harmonics")) {
      const auto* a = hn->as_array();
      if (!a || a->empty()) {
        throw InvalidInput(fmt::format(
            "harmonic_balance.harmonics must be a list of harmonics, e.g. [0, 1, 2, 3]{}",
            at_line(*hn)));
      }
      c.harmonic_balance.harmonics.clear();
      for (std::size_t k = 0; k < a->size(); ++k) {
        const auto v = (*a)[k].value<long long>();
        if (!(*a)[k].is_integer() || !v || *v < 0 || *v > 1000) {
          throw InvalidInput(
              fmt::format("harmonic_balance.harmonics[{}] must be a whole number in [0, 1000]{}", k,
                          at_line((*a)[k])));
        }
        c.harmonic_balance.harmonics.push_back(static_cast<int>(*v));
      }
    } else if (hb->get("max")) {
      const auto H = integer(*hb, "max", w, 3, 1, 1000);
      c.harmonic_balance.harmonics.clear();
      for (int h = 0; h <= H; ++h) c.harmonic_balance.harmonics.push_back(h);
    }
    c.harmonic_balance.time_points = static_cast<std::size_t>(integer(
        *hb, "time_points", w, static_cast<long long>(c.harmonic_balance.time_points), 2, 1 << 20));
  }
  {
    const auto& h = c.harmonic_balance.harmonics;
    if (std::find(h.begin(), h.end(), 1) == h.end()) {
      std::string list;
      for (int x : h) list += (list.empty() ? "" : ", ") + std::to_string(x);
      throw InvalidInput(fmt::format(
          "harmonic_balance.harmonics = [{}] lacks harmonic 1, the fundamental every analysis "
          "needs: add 1",
          list));
    }
    try {
      c.harmonic_balance.validate();
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("harmonic_balance: {}", e.what()));
    }
  }
  const HarmonicBasis basis(c.harmonic_balance);
  const std::size_t nh = basis.harmonics().size();

  // [nonlinear_mode]
  if (const auto* t = subtable(root, "nonlinear_mode", "")) {
    const std::string w = "nonlinear_mode";
    check_keys(*t, w, {"mode", "log10_amplitude", "continuation"});
    NonlinearModeOptions o;
    o.mode = static_cast<int>(integer(*t, "mode", w, 1, 1, n));
    const auto [from, to] = range(*t, "log10_amplitude", w, finite_number);
    o.log10_amplitude_from = from;
    o.log10_amplitude_to = to;
    parse_continuation(*t, w, o.continuation);
    o.validate();
    c.nonlinear_mode = o;
  }

  // [[frequency_response]]
  if (const auto* fn = root.get("frequency_response")) {
    const auto* arr = fn->as_array();
    if (!arr || !arr->is_array_of_tables()) {
      throw InvalidInput(fmt::format(
          "frequency_response must be an array of tables: write [[frequency_response]]{}",
          at_line(*fn)));
    }
    for (std::size_t k = 0; k < arr->size(); ++k) {
      const toml::table& t = *arr->get(k)->as_table();
      const std::string w = fmt::format("frequency_response[{}]", k);
      check_keys(t, w,
                 {"force_cos", "force_sin", "force_per_omega_cos", "force_per_omega_sin",
                  "force_per_omega2_cos", "force_per_omega2_sin", "force_scales", "omega",
                  "continuation"});
      FrequencyResponseCase fr;
      // One (cos, sin) pair of coefficient tables: rows harmonics, columns DOFs.
      auto pair = [&](const std::string& prefix, Eigen::MatrixXd& cos_part,
                      Eigen::MatrixXd& sin_part) {
        cos_part = Eigen::MatrixXd::Zero(0, n);
        sin_part = Eigen::MatrixXd::Zero(0, n);
        for (const std::string kind : {"_cos", "_sin"}) {
          const std::string key = prefix + kind;
          const auto* fnode = t.get(key);
          if (!fnode) continue;
          Eigen::MatrixXd m = matrix(*fnode, w + "." + key, false);
          if (m.cols() != n) {
            throw InvalidInput(fmt::format(
                "{}.{} has {} column(s) but the structure has {} DOFs: one column per DOF{}", w,
                key, m.cols(), n, at_line(*fnode)));
          }
          if (static_cast<std::size_t>(m.rows()) > nh) {
            throw InvalidInput(fmt::format(
                "{}.{} has {} rows but {} harmonics are kept: one row per harmonic in the order "
                "of harmonic_balance.harmonics{}",
                w, key, m.rows(), nh, at_line(*fnode)));
          }
          if (kind == "_sin" && basis.harmonics().front() == 0 && m.rows() > 0 &&
              m.row(0).cwiseAbs().maxCoeff() > 0.0) {
            throw InvalidInput(fmt::format(
                "{}.{}: the first row belongs to harmonic 0, which has no sine part: make it "
                "zero{}",
                w, key, at_line(*fnode)));
          }
          (kind == "_cos" ? cos_part : sin_part) = std::move(m);
        }
        return force_vector(basis, n, cos_part, sin_part);
      };
      FrequencyResponseOptions& o = fr.options;
      o.force = pair("force", fr.force_cos, fr.force_sin);
      if (!t.get("force_cos") && !t.get("force_sin")) {
        throw InvalidInput(
            fmt::format("{} needs force_cos and/or force_sin (rows: harmonics, columns: DOFs){}", w,
                        at_line(t)));
      }
      Eigen::MatrixXd c1, s1, c2, s2;
      if (t.get("force_per_omega_cos") || t.get("force_per_omega_sin"))
        o.force_per_omega = pair("force_per_omega", c1, s1);
      if (t.get("force_per_omega2_cos") || t.get("force_per_omega2_sin"))
        o.force_per_omega2 = pair("force_per_omega2", c2, s2);
      if (const auto* sn = t.get("force_scales")) {
        const auto* a = sn->as_array();
        if (!a || a->empty()) {
          throw InvalidInput(fmt::format("{}.force_scales must be a non-empty list of numbers{}", w,
                                         at_line(*sn)));
        }
        o.force_scales.clear();
        for (std::size_t j = 0; j < a->size(); ++j) {
          o.force_scales.push_back(
              finite_number(*a->get(j), fmt::format("{}.force_scales[{}]", w, j)));
        }
      }
      const auto [from, to] = range(t, "omega", w, angular_frequency);
      o.omega_from = from;
      o.omega_to = to;
      parse_continuation(t, w, o.continuation);
      try {
        o.validate(static_cast<Eigen::Index>(basis.coefficients()) * n);
      } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("{}: {}", w, e.what()));
      }
      c.frequency_responses.push_back(std::move(fr));
    }
  }

  // [quasi_static_mode]
  if (const auto* t = subtable(root, "quasi_static_mode", "")) {
    const std::string w = "quasi_static_mode";
    check_keys(*t, w, {"mode", "amplitude", "points"});
    QuasiStaticModeOptions o;
    o.mode = static_cast<int>(integer(*t, "mode", w, 1, 1, n));
    const auto [from, to] = range(*t, "amplitude", w, finite_number);
    o.amplitude_from = from;
    o.amplitude_to = to;
    o.points = static_cast<std::size_t>(integer(*t, "points", w, 60, 2, 100000));
    o.validate();
    c.quasi_static_mode = o;
  }
  if (!c.nonlinear_mode && c.frequency_responses.empty() && !c.quasi_static_mode) {
    throw InvalidInput(fmt::format(
        "{}: nothing to run: add [nonlinear_mode], [[frequency_response]] or [quasi_static_mode]",
        path));
  }
  return c;
}

VibrationCase read_case_file(const std::string& path) {
  const std::string file_text =
      core::read_input_file(path, core::kMaxCaseFileBytes, "the case file");
  core::require_utf8(file_text, path, "the case file");
  const auto dir = std::filesystem::path(path).parent_path();
  return parse_case_text(file_text, path, dir.empty() ? "." : dir.string());
}

// ---- run -------------------------------------------------------------------------------

namespace {

SummaryArray array(const Eigen::VectorXd& v) {
  SummaryArray a;
  a.reserve(static_cast<std::size_t>(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) a.emplace_back(v(i));
  return a;
}

// Rows of a matrix (points x outputs) as [[...], ...].
SummaryArray rows(const Eigen::MatrixXd& m) {
  SummaryArray a;
  for (Eigen::Index i = 0; i < m.rows(); ++i) a.emplace_back(array(m.row(i).transpose()));
  return a;
}

SummaryArray matrix_summary(const Eigen::MatrixXd& m) {
  return rows(m);
}

struct Work {
  std::size_t points = 0, newton = 0, residuals = 0, jacobians = 0, rejected = 0, turning = 0;
  double wall = 0.0;
  bool complete = true;
  std::string stop_reason;
};

SummaryObject solver_summary(const Work& w) {
  return {{"points", w.points},
          {"newton_iterations", w.newton},
          {"residual_evaluations", w.residuals},
          {"jacobian_evaluations", w.jacobians},
          {"rejected_steps", w.rejected},
          {"turning_points", w.turning},
          {"wall_time_s", w.wall},
          {"complete", w.complete},
          {"stop_reason", w.stop_reason}};
}

void add_continuation(Work& w, const ContinuationResult& c) {
  w.points += c.points.size();
  w.newton += c.newton_iterations;
  w.rejected += c.rejected_steps;
  w.turning += c.turning_points;
  if (!c.complete && w.complete) {
    w.complete = false;
    w.stop_reason = c.stop_reason;
  } else if (w.complete) {
    w.stop_reason = c.stop_reason;
  }
}

}  // namespace

VibrationResult run_case(const VibrationCase& c, const CaseProgress& progress) {
  using clock = std::chrono::steady_clock;
  VibrationResult r;
  const HarmonicBalance hb(c.structure, c.elements, c.harmonic_balance);
  SummaryObject& j = r.summary;
  const Eigen::Index n = c.structure.dofs();

  // The case echoed.
  j.emplace_back("case", c.source);
  {
    SummaryObject s{{"dofs", static_cast<std::size_t>(n)}, {"damping", c.damping}};
    if (c.damping == "rayleigh") {
      s.emplace_back("rayleigh",
                     SummaryObject{{"alpha_per_s", c.rayleigh.alpha}, {"beta_s", c.rayleigh.beta}});
    }
    SummaryArray od;
    for (auto d : c.output_dofs) od.emplace_back(static_cast<std::size_t>(d));
    s.emplace_back("output_dofs", std::move(od));
    const LinearModes free_modes = linear_modes(c.structure.K, c.structure.M);
    const LinearModes stuck = linear_modes(hb.stuck_stiffness(), c.structure.M);
    SummaryArray fs, fss;
    for (Eigen::Index i = 0; i < free_modes.omega.size(); ++i) {
      fs.emplace_back(free_modes.omega(i) / (2.0 * std::numbers::pi));
      fss.emplace_back(stuck.omega(i) / (2.0 * std::numbers::pi));
    }
    s.emplace_back("linear_frequencies_hz_without_elements", std::move(fs));
    s.emplace_back("linear_frequencies_hz_elements_stuck", std::move(fss));
    j.emplace_back("structure", std::move(s));
  }
  {
    SummaryArray es;
    for (const auto& pe : c.elements) {
      SummaryObject e{{"name", pe.name}, {"type", pe.element->type()}};
      e.emplace_back("T", matrix_summary(pe.T));
      for (auto& kv : pe.element->describe()) {
        if (kv.first != "type") e.push_back(kv);
      }
      es.emplace_back(std::move(e));
    }
    j.emplace_back("elements", std::move(es));
  }
  {
    SummaryArray h;
    for (int x : c.harmonic_balance.harmonics) h.emplace_back(x);
    j.emplace_back("harmonic_balance",
                   SummaryObject{{"harmonics", std::move(h)},
                                 {"time_points", c.harmonic_balance.time_points},
                                 {"unknowns", static_cast<std::size_t>(hb.unknowns())}});
  }
  if (c.joint) j.emplace_back("joint", *c.joint);

  Work total;
  const auto t_all = clock::now();
  auto counters = [&hb] { return hb.counters(); };
  auto account = [&](Work& w, const WorkCounters& before, clock::time_point t0) {
    const WorkCounters after = counters();
    w.residuals = after.residual_evaluations - before.residual_evaluations;
    w.jacobians = after.jacobian_evaluations - before.jacobian_evaluations;
    w.wall = std::chrono::duration<double>(clock::now() - t0).count();
  };
  auto cannot_start = [](const std::string& analysis, const NumericalError& e) {
    return InvalidInput(fmt::format(
        "{}: {} (change the start of the range, the force, or the continuation settings)", analysis,
        e.what()));
  };

  if (c.nonlinear_mode) {
    Work w;
    const auto before = counters();
    const auto t0 = clock::now();
    try {
      r.nonlinear_mode = nonlinear_mode(
          hb, *c.nonlinear_mode, c.output_dofs,
          progress ? ProgressFunction([&](double x) { progress("nonlinear_mode", x); })
                   : ProgressFunction{});
    } catch (const NumericalError& e) {
      throw cannot_start("nonlinear_mode", e);
    }
    const NonlinearModeResult& m = *r.nonlinear_mode;
    add_continuation(w, m.continuation);
    account(w, before, t0);
    r.warnings.insert(r.warnings.end(), m.warnings.begin(), m.warnings.end());
    j.emplace_back("nonlinear_mode", SummaryObject{{"mode", c.nonlinear_mode->mode},
                                                   {"linear_omega_rad_s", m.linear_omega},
                                                   {"linear_damping_ratio", m.linear_damping_ratio},
                                                   {"log10_amplitude", array(m.log10_amplitude)},
                                                   {"amplitude", array(m.amplitude)},
                                                   {"omega_rad_s", array(m.omega)},
                                                   {"frequency_hz", array(m.frequency_hz)},
                                                   {"damping_ratio", array(m.damping_ratio)},
                                                   {"xi_per_s", array(m.xi)},
                                                   {"output_amplitude", rows(m.output_amplitude)},
                                                   {"solver", solver_summary(w)}});
    total.points += w.points;
    total.newton += w.newton;
    total.rejected += w.rejected;
    total.turning += w.turning;
    if (!w.complete && total.complete) {
      total.complete = false;
      total.stop_reason = "nonlinear_mode: " + w.stop_reason;
    }
  }

  if (!c.frequency_responses.empty()) {
    SummaryArray curves;
    std::size_t total_curves = 0, done_curves = 0;
    for (const auto& fr : c.frequency_responses) total_curves += fr.options.force_scales.size();
    for (std::size_t k = 0; k < c.frequency_responses.size(); ++k) {
      const FrequencyResponseOptions& all = c.frequency_responses[k].options;
      for (const double scale : all.force_scales) {
        // One curve per call, so that each has its own counters and wall time.
        FrequencyResponseOptions one = all;
        one.force_scales = {scale};
        const auto before = counters();
        const auto t0 = clock::now();
        std::vector<FrequencyResponseCurve> cs;
        try {
          const double nk = static_cast<double>(total_curves);
          const double d0 = static_cast<double>(done_curves);
          cs = frequency_response(hb, one, c.output_dofs,
                                  progress ? ProgressFunction([&](double x) {
                                    progress("frequency_response", (d0 + x) / nk);
                                  })
                                           : ProgressFunction{});
        } catch (const NumericalError& e) {
          throw cannot_start(
              fmt::format("frequency_response[{}] at force scale {}", k, core::format_value(scale)),
              e);
        }
        ++done_curves;
        FrequencyResponseCurve& cv = cs.front();
        Work w;
        add_continuation(w, cv.continuation);
        account(w, before, t0);
        r.warnings.insert(r.warnings.end(), cv.warnings.begin(), cv.warnings.end());
        SummaryArray ha;  // per point, per output, per harmonic
        for (Eigen::Index p = 0; p < cv.omega.size(); ++p) {
          SummaryArray per_output;
          for (const auto& hm : cv.harmonic_amplitude)
            per_output.emplace_back(array(hm.row(p).transpose()));
          ha.emplace_back(std::move(per_output));
        }
        SummaryObject o{{"table", k},
                        {"force_scale", cv.force_scale},
                        {"omega_rad_s", array(cv.omega)},
                        {"frequency_hz", array(cv.omega / (2.0 * std::numbers::pi))},
                        {"output_amplitude", rows(cv.output_amplitude)},
                        {"max_displacement", rows(cv.max_displacement)},
                        {"harmonic_amplitude", std::move(ha)}};
        o.emplace_back("solver", solver_summary(w));
        curves.emplace_back(std::move(o));
        total.points += w.points;
        total.newton += w.newton;
        total.rejected += w.rejected;
        total.turning += w.turning;
        if (!w.complete && total.complete) {
          total.complete = false;
          total.stop_reason = fmt::format("frequency_response[{}] at force scale {}: {}", k,
                                          core::format_value(cv.force_scale), w.stop_reason);
        }
        r.frequency_response.push_back(std::move(cv));
        r.frequency_response_table.push_back(k);
      }
    }
    j.emplace_back("frequency_response", std::move(curves));
  }

  if (c.quasi_static_mode) {
    Work w;
    const auto before = counters();
    const auto t0 = clock::now();
    if (progress) progress("quasi_static_mode", 0.0);
    try {
      r.quasi_static_mode = quasi_static_mode(hb, *c.quasi_static_mode);
    } catch (const NumericalError& e) {
      throw InvalidInput(fmt::format("quasi_static_mode: {}", e.what()));
    }
    if (progress) progress("quasi_static_mode", 1.0);
    const QuasiStaticModeResult& q = *r.quasi_static_mode;
    w.points = static_cast<std::size_t>(q.amplitude.size());
    w.newton = q.newton_iterations;
    w.stop_reason = "reached the end of the amplitude range";
    account(w, before, t0);
    r.warnings.insert(r.warnings.end(), q.warnings.begin(), q.warnings.end());
    j.emplace_back("quasi_static_mode", SummaryObject{{"mode", c.quasi_static_mode->mode},
                                                      {"linear_omega_rad_s", q.linear_omega},
                                                      {"amplitude", array(q.amplitude)},
                                                      {"omega_rad_s", array(q.omega)},
                                                      {"frequency_hz", array(q.frequency_hz)},
                                                      {"damping_ratio", array(q.damping_ratio)},
                                                      {"modal_force", array(q.modal_force)},
                                                      {"dissipation_J", array(q.dissipation)},
                                                      {"solver", solver_summary(w)}});
    total.points += w.points;
    total.newton += w.newton;
  }
  {
    const WorkCounters wc = counters();
    total.residuals = wc.residual_evaluations;
    total.jacobians = wc.jacobian_evaluations;
    total.wall = std::chrono::duration<double>(clock::now() - t_all).count();
    if (total.complete) total.stop_reason = "every analysis reached the end of its range";
    r.complete = total.complete;
    r.stop_reason = total.stop_reason;
    j.emplace_back("solver", solver_summary(total));
  }
  SummaryArray w;
  for (const auto& s : r.warnings) w.emplace_back(s);
  j.emplace_back("warnings", std::move(w));
  return r;
}

}  // namespace asperity::vibration
