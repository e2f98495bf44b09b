#include "asperity/dynamics/case.hpp"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <set>

#include "../core/toml_case.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/units.hpp"
#include "asperity/dynamics/epb.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/predict.hpp"
#include "case_parse.hpp"

namespace asperity::dynamics {

namespace detail {

double time_scale(const CaseScales& s) {
  return std::sqrt(*s.m / *s.k);
}

}  // namespace detail

namespace {

using core::Dimension;
namespace dim = core::dim;
using core::toml_case::check_keys;
using core::toml_case::collect_lines;
using core::toml_case::number;
using core::toml_case::subtable;
using detail::time_scale;

// A value that is a plain number (non-dimensional) or a quantity string with units
// converted by `to_nondim` (which needs the scales).
std::optional<double> value(const toml::table& t, const std::string& key, const std::string& where,
                            Dimension d, const CaseScales& s,
                            const std::function<double(double, const CaseScales&)>& to_nondim) {
  const auto* n = t.get(key);
  if (!n) return std::nullopt;
  const std::string field = where + "." + key;
  if (auto x = n->value<double>(); x && (n->is_floating_point() || n->is_integer())) {
    if (!std::isfinite(*x)) throw InvalidInput(fmt::format("{} = {} must be finite", field, *x));
    return *x;
  }
  if (auto str = n->value<std::string>()) {
    const double si = core::parse_quantity(*str, d, field);
    if (d == dim::dimensionless) return si;
    if (!s.complete()) {
      throw InvalidInput(fmt::format(
          "{} = \"{}\" has units: give mass, stiffness and amplitude in [dynamics] to convert "
          "it, or give a non-dimensional number",
          field, *str));
    }
    return to_nondim(si, s);
  }
  throw InvalidInput(fmt::format("{} must be a number or a quantity string", field));
}

std::string text(const toml::table& t, const std::string& key, const std::string& where,
                 const std::string& dflt) {
  const auto* n = t.get(key);
  if (!n) return dflt;
  if (auto x = n->value<std::string>()) return *x;
  throw InvalidInput(fmt::format("{}.{} must be a string", where, key));
}

std::pair<hysteresis::MemoryRule, std::string> memory_rule(const toml::table& t) {
  const std::string m = text(t, "memory", "dynamics.friction", "masing");
  if (m == "masing") return {hysteresis::MemoryRule::masing, m};
  if (m == "reset_at_reversal" || m == "eq7.10") {
    return {hysteresis::MemoryRule::reset_at_reversal, "reset_at_reversal"};
  }
  throw InvalidInput(fmt::format(
      "dynamics.friction.memory = \"{}\": use \"masing\" or \"reset_at_reversal\" (Eq. 7.10)", m));
}

// The derived quantities of a physics-based law from an SI backbone: Q_max, the
// tangential stiffness at a reversal k_t, mu = Q_max/P, and their non-dimensional
// values F~max = Q_max/(k A), k_t/k (section 7.2).
void add_backbone_summary(SummaryObject& f, const hysteresis::Backbone& si, double P,
                          const CaseScales& s) {
  f.emplace_back("P_N", P);
  f.emplace_back("Q_max_N", si.limit());
  f.emplace_back("mu", si.limit() / P);
  f.emplace_back("k_t_N_per_m", si.initial_stiffness());
  f.emplace_back("F_max_tilde", si.limit() / (*s.k * *s.A));
  f.emplace_back("k_t_over_k", si.initial_stiffness() / *s.k);
}

// ---- [joint] ---------------------------------------------------------------------------

// Adds the lines of the case file that hold any part of `n` (a node of the [dynamics]
// tree): the headers of its tables, its keys and its values.

// The case file with every line of its [dynamics] tree blanked: what remains is the
// joint part ([joint], [load], [profiles], comments) at its original line numbers, so
// that the joint reader's errors point into the user's file.
std::string joint_text(const std::string& text, const toml::node& dynamics) {
  std::set<std::uint32_t> lines;
  collect_lines(dynamics, lines);
  return core::toml_case::without_lines(text, lines);
}

// The physics-based law of a joint described as for `asperity predict`: the joint's
// rough flat (RoughFlat::from_dimensional from the halves' materials and combined
// roughness, the area and the asperity model) at the [load]'s single preload, its SI
// backbone seen in the variables of section 7.2 through k and A.
std::unique_ptr<FrictionModel> joint_friction(DynamicsCase& c, const std::string& base_dir,
                                              const std::string& file_text, const toml::table& root,
                                              const toml::table* friction) {
  const std::string& path = c.source;
  const CaseScales& s = c.scales;
  hysteresis::MemoryRule rule = hysteresis::MemoryRule::masing;
  std::string rule_name = "masing";
  if (friction) {
    const std::string where = "dynamics.friction";
    const std::string model = text(*friction, "model", where, "physics");
    const std::string bb = text(*friction, "backbone", where, "joint");
    if (model != "physics" || bb != "joint") {
      throw InvalidInput(fmt::format(
          "{}: model = \"{}\", backbone = \"{}\" conflicts with the [joint] table, which gives the "
          "physics-based law (model = \"physics\", backbone = \"joint\"): remove one of them",
          where, model, bb));
    }
    check_keys(*friction, where, {"model", "backbone", "memory"});
    const auto m = memory_rule(*friction);
    rule = m.first;
    rule_name = m.second;
  }
  if (!s.k || !s.A) {
    throw InvalidInput(
        "dynamics: the [joint] friction law needs the scales stiffness and amplitude in [dynamics] "
        "(forces are divided by k A, displacements by A)");
  }
  const joint::JointCase jc =
      joint::parse_case(joint_text(file_text, *root.get("dynamics")), path, base_dir);
  // [load] is there unless an [interface] map gives the load (joint::parse_case checks).
  const auto load_line = root.get("load") ? root.get("load")->source().begin.line
                                          : root.get("interface")->source().begin.line;
  const joint::LoadPrediction lp = joint::predict_single_load(
      jc, fmt::format("{}:{}: load: ", path, load_line), "`asperity dynamics` runs");
  if (lp.odfalk_vingsbo) {
    throw InvalidInput(fmt::format(
        "{}: interface.tangential = \"odfalk_vingsbo\" is not available in `asperity dynamics`, "
        "whose friction models are Masing's (the thesis's ch. 7): use the joint in a `vibration` "
        "case (a rough_flat element takes the law) or tangential = \"mindlin\"",
        jc.interface.origin));
  }
  const double P = jc.preloads.front();
  const double kA = *s.k * *s.A;
  c.joint = SummaryObject{{"name", jc.name},
                          {"model", std::string(contact::to_string(jc.model))},
                          {"area", jc.area},
                          {"preload", P},
                          {"separation", lp.separation},
                          {"Q_max", lp.Q_max},
                          {"mu", lp.mu},
                          {"stiffness", lp.stiffness},
                          {"F_max_tilde", lp.Q_max / kA},
                          {"stiffness_tilde", lp.stiffness / *s.k}};
  SummaryObject& f = c.friction_summary;
  f = {{"model", "physics"},
       {"backbone", "joint"},
       {"memory", rule_name},
       {"asperity_model", std::string(contact::to_string(jc.model))},
       {"A0_m2", jc.area}};
  add_backbone_summary(f, *lp.backbone, P, s);
  return make_physics_based(lp.backbone, *s.k, *s.A, rule);
}

// The physics-based (EPB) law of section 7.3 from Table 7.2-style inputs: combined
// E*, G*, hardness H and Poisson's ratio nu of the softer material, combined roughness
// (sigma, R, eta), nominal area A0 and normal load P (or P~ = P/(k A), the reading of
// Table 7.2's "P~ = 5" under which mu P~ = F~max = 1.5 with mu ~ 0.3); see
// dynamics/epb.hpp. Its SI backbone is seen in the variables of section 7.2 through k, A.
std::unique_ptr<FrictionModel> rough_flat_friction(const toml::table& t, const CaseScales& s,
                                                   hysteresis::MemoryRule rule,
                                                   const std::string& rule_name, SummaryObject& f) {
  const std::string where = "dynamics.friction";
  check_keys(t, where,
             {"model", "backbone", "memory", "asperity_model", "mu_cfc", "E_star", "G_star", "H",
              "nu", "sigma", "R", "eta", "A0", "P", "P_tilde"});
  if (!s.k || !s.A) {
    throw InvalidInput(
        "dynamics.friction: the rough_flat backbone needs the scales stiffness and amplitude in "
        "[dynamics] (forces are divided by k A, displacements by A)");
  }
  auto q = [&](const std::string& key, Dimension d) {
    const auto* n = t.get(key);
    if (!n) throw InvalidInput(fmt::format("{}: the rough_flat backbone needs {}", where, key));
    if (auto str = n->value<std::string>()) return core::parse_quantity(*str, d, where + "." + key);
    throw InvalidInput(
        fmt::format("{}.{} must be a quantity with units, e.g. \"2.7 um\"", where, key));
  };
  const double E_star = q("E_star", dim::pressure);
  const double G_star = q("G_star", dim::pressure);
  const double H = q("H", dim::pressure);
  const double sigma = q("sigma", dim::length);
  const double R = q("R", dim::length);
  const double eta = q("eta", dim::inverse_area);
  const double A0 = q("A0", dim::area);
  if (!t.get("nu")) throw InvalidInput(where + ": the rough_flat backbone needs nu");
  const double nu = number(t, "nu", where, 0.3);
  double P = 0.0;
  if (t.get("P") && t.get("P_tilde")) throw InvalidInput(where + ": give P or P_tilde, not both");
  if (t.get("P")) {
    P = q("P", dim::force);
  } else if (t.get("P_tilde")) {
    P = number(t, "P_tilde", where, 5.0) * *s.k * *s.A;
  } else {
    throw InvalidInput(where +
                       ": the rough_flat backbone needs the normal load: P (e.g. \"9 N\") or "
                       "P_tilde = P/(k A)");
  }
  if (!(P > 0.0))
    throw InvalidInput(fmt::format("{}: the normal load P = {} N must be > 0", where, P));
  EpbContact c{.E_star = E_star,
               .G_star = G_star,
               .H = H,
               .nu = nu,
               .sigma = sigma,
               .R = R,
               .eta = eta,
               .A0 = A0,
               .P = P,
               .model = core::toml_case::named_choice(t, "asperity_model", where, "bke",
                                                      contact::parse_model_name)};
  if (t.get("mu_cfc")) c.friction.mu_cfc = number(t, "mu_cfc", where, 0.3);
  const auto si = epb_backbone(c);
  f = {{"model", "physics"},  {"backbone", "rough_flat"},
       {"memory", rule_name}, {"asperity_model", std::string(contact::to_string(c.model))},
       {"E_star_Pa", E_star}, {"G_star_Pa", G_star},
       {"H_Pa", H},           {"nu", nu},
       {"sigma_m", sigma},    {"R_m", R},
       {"eta_per_m2", eta},   {"A0_m2", A0}};
  add_backbone_summary(f, *si, P, s);
  return make_physics_based(si, *s.k, *s.A, rule);
}

std::unique_ptr<FrictionModel> parse_friction(const toml::table* t, const CaseScales& s,
                                              SummaryObject& f) {
  const std::string where = "dynamics.friction";
  if (!t) {
    f = {{"model", "none"}};
    return std::make_unique<NoFriction>();
  }
  const std::string model = text(*t, "model", where, "none");
  auto force = [&](const std::string& key) {
    return value(*t, key, where, dim::force, s,
                 [](double x, const CaseScales& sc) { return x / (*sc.k * *sc.A); });
  };
  auto length = [&](const std::string& key) {
    return value(*t, key, where, dim::length, s,
                 [](double x, const CaseScales& sc) { return x / *sc.A; });
  };
  auto stiff = [&](const std::string& key) {
    return value(*t, key, where, dim::stiffness, s,
                 [](double x, const CaseScales& sc) { return x / *sc.k; });
  };
  auto need = [&](const std::optional<double>& v, const std::string& key) {
    if (!v) throw InvalidInput(fmt::format("{}: model \"{}\" needs {}", where, model, key));
    return *v;
  };
  // SI values of non-dimensional parameters, when the scales allow.
  const bool kA = s.k && s.A;
  if (model == "none") {
    check_keys(*t, where, {"model"});
    f = {{"model", "none"}};
    return std::make_unique<NoFriction>();
  }
  if (model == "coulomb") {
    check_keys(*t, where, {"model", "F_max", "k_tan"});
    const auto k_tan =
        value(*t, "k_tan", where, Dimension{-1, 0, 1}, s,
              [](double x, const CaseScales& sc) { return x * *sc.A * std::sqrt(*sc.k / *sc.m); });
    const RegularizedCoulombParameters p{.F_max = need(force("F_max"), "F_max"),
                                         .k_tan = need(k_tan, "k_tan")};
    f = {{"model", "coulomb"}, {"F_max_tilde", p.F_max}, {"k_tan_tilde", p.k_tan}};
    if (kA) f.emplace_back("F_max_N", p.F_max * *s.k * *s.A);
    if (s.complete()) f.emplace_back("k_tan_s_per_m", p.k_tan / (*s.A * std::sqrt(*s.k / *s.m)));
    return std::make_unique<RegularizedCoulomb>(p);
  }
  if (model == "dankowicz") {
    check_keys(*t, where, {"model", "F_max", "delta"});
    const DankowiczParameters p{.F_max = need(force("F_max"), "F_max"),
                                .delta = need(length("delta"), "delta")};
    auto m = std::make_unique<Dankowicz>(p);  // validates
    f = {{"model", "dankowicz"},
         {"F_max_tilde", p.F_max},
         {"delta_tilde", p.delta},
         {"contact_stiffness_tilde", p.F_max / p.delta}};
    if (kA) {
      f.emplace_back("F_max_N", p.F_max * *s.k * *s.A);
      f.emplace_back("delta_m", p.delta * *s.A);
    }
    return m;
  }
  if (model == "jenkins") {
    check_keys(*t, where, {"model", "F_max", "stiffness"});
    const double kj = need(stiff("stiffness"), "stiffness");
    const double F = need(force("F_max"), "F_max");
    auto m = make_jenkins(kj, F);
    f = {{"model", "jenkins"}, {"F_max_tilde", F}, {"stiffness_tilde", kj}};
    return m;
  }
  if (model == "iwan") {
    check_keys(*t, where, {"model", "F_S", "K_T", "chi", "beta"});
    // chi and beta shape the slip-strength density (Segalman 2005): no default that a
    // user could mistake for a property of the joint.
    for (const char* key : {"chi", "beta"}) {
      if (!t->get(key)) {
        throw InvalidInput(fmt::format(
            "{}: model \"iwan\" needs {} (Segalman's four parameters F_S, K_T, chi in (-1, 0], "
            "beta >= 0 are all required; e.g. chi = -0.5, beta = 0.1)",
            where, key));
      }
    }
    const SegalmanIwanParameters p{.F_S = need(force("F_S"), "F_S"),
                                   .K_T = need(stiff("K_T"), "K_T"),
                                   .chi = number(*t, "chi", where, 0.0),
                                   .beta = number(*t, "beta", where, 0.0)};
    auto m = make_segalman_iwan(p);
    const SegalmanBackbone bb(p);
    f = {{"model", "iwan"}, {"F_S_tilde", p.F_S}, {"K_T_tilde", p.K_T},
         {"chi", p.chi},    {"beta", p.beta},     {"phi_max_tilde", bb.phi_max()}};
    return m;
  }
  if (model == "physics") {
    const auto [rule, rule_name] = memory_rule(*t);
    const std::string bb = text(*t, "backbone", where, "rough_flat");
    if (bb == "rough_flat") return rough_flat_friction(*t, s, rule, rule_name, f);
    if (bb == "joint") {
      throw InvalidInput(fmt::format(
          "{}.backbone = \"joint\" needs a [joint] table (and [load]) as for `asperity predict`",
          where));
    }
    if (bb != "mindlin") {
      throw InvalidInput(fmt::format(
          "{}.backbone = \"{}\": use \"rough_flat\", \"mindlin\" or \"joint\"", where, bb));
    }
    // A Cattaneo-Mindlin-shaped saturating backbone (the shape of the CFC limit:
    // Q = F_max (1 - (1 - x/s)^{3/2}) up to the slip displacement s) through Masing's
    // rules: a two-parameter stand-in, not the rough flat.
    check_keys(*t, where, {"model", "backbone", "F_max", "slip_displacement", "memory"});
    const double F = need(force("F_max"), "F_max");
    const double sd = need(length("slip_displacement"), "slip_displacement");
    if (!(F > 0.0 && sd > 0.0)) {
      throw InvalidInput(fmt::format("{}: F_max and slip_displacement must be > 0", where));
    }
    auto backbone = std::make_shared<hysteresis::FunctionBackbone>(
        [F, sd](double x) { return x >= sd ? F : F * (1.0 - std::pow(1.0 - x / sd, 1.5)); }, F,
        1.5 * F / sd);
    f = {{"model", "physics"}, {"backbone", "mindlin"},         {"memory", rule_name},
         {"F_max_tilde", F},   {"slip_displacement_tilde", sd}, {"k_t_over_k", 1.5 * F / sd}};
    return std::make_unique<HysteresisFriction>(backbone, rule, "physics");
  }
  throw InvalidInput(fmt::format(
      "{}.model = \"{}\" is not known: use none, coulomb, dankowicz, jenkins, iwan or physics",
      where, model));
}

}  // namespace

DynamicsCase parse_case_text(const std::string& file_text, const std::string& path,
                             const std::string& base_dir) {
  const toml::table root = core::toml_case::parse(file_text, path);
  check_keys(root, path, {"dynamics", "joint", "load", "profiles", "interface"});
  if (!root.get("joint")) {
    for (const char* k : {"load", "profiles", "interface"}) {
      if (root.get(k)) {
        throw InvalidInput(
            fmt::format("{}: [{}] belongs to a [joint] table, which is missing (line {})", path, k,
                        root.get(k)->source().begin.line));
      }
    }
  }
  const toml::table* d = subtable(root, "dynamics", "");
  if (!d) throw InvalidInput(fmt::format("{}: the case file needs a [dynamics] table", path));
  const std::string W = "dynamics";
  check_keys(*d, W,
             {"excitation", "epsilon", "mass", "stiffness", "damping", "amplitude", "duration",
              "impulse", "ramp", "harmonic", "free", "friction", "integrator", "analysis"});
  DynamicsCase c;
  c.source = path;
  auto q = [&](const std::string& key, Dimension dm) -> std::optional<double> {
    const auto* n = d->get(key);
    if (!n) return std::nullopt;
    auto s = n->value<std::string>();
    if (!s)
      throw InvalidInput(
          fmt::format("dynamics.{} must be a quantity with units, e.g. \"10 kg\"", key));
    return core::parse_quantity(*s, dm, "dynamics." + key);
  };
  c.scales.m = q("mass", dim::mass);
  c.scales.k = q("stiffness", dim::stiffness);
  c.scales.A = q("amplitude", dim::length);
  const auto damping = q("damping", Dimension{0, 1, -1});
  if (c.scales.m && !(*c.scales.m > 0.0))
    throw InvalidInput(fmt::format("dynamics.mass = {} kg must be > 0", *c.scales.m));
  if (c.scales.k && !(*c.scales.k > 0.0))
    throw InvalidInput(fmt::format("dynamics.stiffness = {} N/m must be > 0", *c.scales.k));
  if (c.scales.A && !(*c.scales.A > 0.0))
    throw InvalidInput(fmt::format("dynamics.amplitude = {} m must be > 0", *c.scales.A));
  if (d->get("epsilon") && damping)
    throw InvalidInput("dynamics: give epsilon or damping, not both");
  if (damping) {
    if (!c.scales.m || !c.scales.k) throw InvalidInput("dynamics.damping needs mass and stiffness");
    DimensionalScales ds{.m = *c.scales.m, .k = *c.scales.k, .A = c.scales.A.value_or(1.0)};
    c.system.epsilon = ds.epsilon(*damping);
  } else {
    c.system.epsilon = number(*d, "epsilon", W, 0.032);
  }
  c.system.validate();

  const auto duration = value(*d, "duration", W, dim::time, c.scales,
                              [](double t, const CaseScales& s) { return t / time_scale(s); });
  c.simulation.duration = duration.value_or(100.0);

  c.excitation_name = text(*d, "excitation", W, "impulse");
  const CaseScales& sc = c.scales;
  if (c.excitation_name == "impulse") {
    ImpulseExcitation e;
    if (const auto* t = subtable(*d, "impulse", W)) {
      check_keys(*t, W + ".impulse", {"Omega", "amplitude"});
      e.Omega =
          value(*t, "Omega", W + ".impulse", dim::frequency, sc, [](double w, const CaseScales& s) {
            return w * time_scale(s);
          }).value_or(e.Omega);
      e.amplitude = number(*t, "amplitude", W + ".impulse", 1.0);
    }
    c.excitation = e;
  } else if (c.excitation_name == "ramp") {
    RampExcitation e;
    if (const auto* t = subtable(*d, "ramp", W)) {
      check_keys(*t, W + ".ramp", {"alpha"});
      e.alpha =
          value(*t, "alpha", W + ".ramp", dim::velocity, sc, [](double b, const CaseScales& s) {
            return b * time_scale(s) / *s.A;
          }).value_or(1.0);
    }
    c.excitation = e;
  } else if (c.excitation_name == "harmonic") {
    HarmonicExcitation e;
    if (const auto* t = subtable(*d, "harmonic", W)) {
      check_keys(*t, W + ".harmonic", {"frequency", "amplitude"});
      e.frequency = value(*t, "frequency", W + ".harmonic", dim::frequency, sc,
                          [](double f, const CaseScales& s) { return f * time_scale(s); })
                        .value_or(1.0);
      e.amplitude = number(*t, "amplitude", W + ".harmonic", 1.0);
    }
    c.excitation = e;
  } else if (c.excitation_name == "free") {
    c.excitation = FreeVibration{};
  } else {
    throw InvalidInput(fmt::format(
        "dynamics.excitation = \"{}\" is not known: use impulse, ramp, harmonic or free",
        c.excitation_name));
  }
  validate(c.excitation);
  for (const char* other : {"impulse", "ramp", "harmonic"}) {
    if (d->get(other) && c.excitation_name != other) {
      throw InvalidInput(fmt::format("dynamics.{} is given but the excitation is \"{}\"", other,
                                     c.excitation_name));
    }
  }
  if (const auto* t = subtable(*d, "free", W)) {
    if (c.excitation_name != "free")
      throw InvalidInput("dynamics.free is given but the excitation is not \"free\"");
    check_keys(*t, W + ".free", {"u0", "v0"});
    c.simulation.u0 = number(*t, "u0", W + ".free", 0.0);
    c.simulation.v0 = number(*t, "v0", W + ".free", 0.0);
  }

  if (root.get("joint")) {
    c.friction = joint_friction(c, base_dir, file_text, root, subtable(*d, "friction", W));
  } else {
    c.friction = parse_friction(subtable(*d, "friction", W), sc, c.friction_summary);
  }

  SimulationOptions& sim = c.simulation;
  sim.output_interval = 0.01;
  if (const auto* t = subtable(*d, "integrator", W)) {
    const std::string w = W + ".integrator";
    check_keys(*t, w,
               {"method", "rtol", "atol", "max_step", "initial_step", "min_step", "max_steps",
                "output_interval"});
    sim.integrator.method = parse_method(text(*t, "method", w, "dp54"));
    sim.integrator.rtol = number(*t, "rtol", w, 1e-6);
    if (const auto* a = t->get("atol")) {
      if (const auto* arr = a->as_array()) {
        sim.integrator.atol.clear();
        for (const auto& e : *arr) {
          auto x = e.value<double>();
          if (!x) throw InvalidInput(w + ".atol entries must be numbers");
          sim.integrator.atol.push_back(*x);
        }
      } else {
        sim.integrator.atol = {number(*t, "atol", w, 1e-7)};
      }
    }
    sim.integrator.max_step = number(*t, "max_step", w, 0.0);
    sim.integrator.initial_step = number(*t, "initial_step", w, 0.0);
    sim.integrator.min_step = number(*t, "min_step", w, 0.0);
    const double max_steps = number(*t, "max_steps", w, 5e7);
    if (!(max_steps >= 1 && max_steps <= 1e9))
      throw InvalidInput(w + ".max_steps must lie in [1, 1e9]");
    sim.integrator.max_steps = static_cast<std::size_t>(max_steps);
    sim.output_interval = number(*t, "output_interval", w, 0.01);
  }
  if (!(sim.output_interval > 0.0))
    throw InvalidInput("dynamics.integrator.output_interval must be > 0");
  sim.validate();
  sim.integrator.validate(2 + c.friction->internal_states() + 3);
  // Decays: exact extrema at located reversals for the logarithmic decrement.
  if (c.excitation_name == "impulse" || c.excitation_name == "free") sim.locate_reversals = true;

  if (const auto* t = subtable(*d, "analysis", W)) {
    const std::string w = W + ".analysis";
    check_keys(*t, w, {"f_min", "f_max", "bins", "stick_velocity", "loop_cycles", "decay_start"});
    CaseAnalysis& a = c.analysis;
    a.f_min = number(*t, "f_min", w, 0.0);
    a.f_max = number(*t, "f_max", w, 0.0);
    if (a.f_min < 0.0 || a.f_max < 0.0 || (a.f_max > 0.0 && a.f_max <= a.f_min)) {
      throw InvalidInput(fmt::format(
          "{}: f_min = {} and f_max = {} must satisfy 0 <= f_min < f_max", w, a.f_min, a.f_max));
    }
    const double bins = number(*t, "bins", w, 4000);
    if (!(bins >= 16 && bins <= 1e6)) throw InvalidInput(w + ".bins must lie in [16, 1e6]");
    a.bins = static_cast<std::size_t>(bins);
    a.stick_velocity = number(*t, "stick_velocity", w, 0.05);
    if (!(a.stick_velocity > 0.0)) throw InvalidInput(w + ".stick_velocity must be > 0");
    const double lc = number(*t, "loop_cycles", w, 5);
    if (!(lc >= 1 && lc <= 1e4)) throw InvalidInput(w + ".loop_cycles must lie in [1, 1e4]");
    a.loop_cycles = static_cast<int>(lc);
    a.decay_start = number(*t, "decay_start", w, -1.0);
  }
  return c;
}

DynamicsCase read_case_file(const std::string& path) {
  const core::CaseFileText f = core::read_case_file_text(path);
  return parse_case_text(f.text, path, f.base_dir);
}

}  // namespace asperity::dynamics
