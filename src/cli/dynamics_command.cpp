// asperity dynamics: the single-DOF base-excited system of thesis chapter 7 with a
// friction model, from a TOML case file.
//
// Case file (every table optional except [dynamics]; unknown keys are errors):
//
//   [dynamics]
//   excitation = "impulse"     # impulse | ramp | harmonic | free
//   epsilon = 0.032            # c/sqrt(m k); or give mass, stiffness, damping with units
//   # mass = "10 kg"  stiffness = "1e5 N/m"  damping = "32 N*s/m"  amplitude = "1 mm"
//   duration = 300             # in tau = sqrt(k/m) t, or a time with units ("3 s")
//   [dynamics.impulse]   Omega = 31.4159 (rad per tau) or omega = "314 rad/s"... ; amplitude = 1
//   [dynamics.ramp]      alpha = 1, or velocity = "1 mm/s"
//   [dynamics.harmonic]  frequency = 1 (f~ = sqrt(m/k) f), or "10 Hz"; amplitude = 1
//   [dynamics.free]      u0 = 1, v0 = 0
//   [dynamics.friction]  model = "none|coulomb|dankowicz|jenkins|iwan|physics", and
//       coulomb: F_max, k_tan; dankowicz: F_max, delta; jenkins: F_max, stiffness;
//       iwan: F_S, K_T, chi, beta; physics: memory = "masing|reset_at_reversal" and
//         backbone = "rough_flat": asperity_model, E_star, G_star, H, nu, sigma, R, eta,
//                                  A0, P or P_tilde (= P/(k A)), mu_cfc (needs stiffness
//                                  and amplitude in [dynamics]); or
//         backbone = "mindlin": F_max, slip_displacement (a two-parameter stand-in)
//   [dynamics.integrator] method = "dp54|bs23", rtol, atol (number or per-state array),
//                         max_step, initial_step, min_step (collapse threshold),
//                         max_steps, output_interval
//   [dynamics.analysis]  f_min, f_max, bins, stick_velocity, loop_cycles, decay_start
//
// Numbers are non-dimensional (section 7.2); strings are quantities with units and need
// mass, stiffness and amplitude (the scales) in [dynamics].
//
// Instead of [dynamics.friction] parameters, a joint described as for `asperity
// predict` gives the physics-based law: the [joint] table (area, model, mu_cfc, zeta,
// slip_scaling, two [[joint.half]] with material and roughness or profiles), [load] with
// one preload (or bolts with one torque) and optionally [profiles]. They are read by
// joint::parse_case (same keys, same errors with file and line); the rough flat of
// the joint (RoughFlat::from_dimensional) at that preload gives the SI backbone, seen
// through the scales stiffness and amplitude of [dynamics]. [dynamics.friction] may then
// hold only model = "physics", backbone = "joint" and memory.
#include <fmt/format.h>

#include <toml++/toml.h>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <set>
#include <sstream>

#include "asperity/core/error.hpp"
#include "asperity/core/units.hpp"
#include "asperity/dynamics/analysis.hpp"
#include "asperity/dynamics/epb.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/predict.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace {

using namespace asperity::dynamics;
using core::Dimension;
namespace dim = core::dim;

struct DynamicsOptions {
  std::string case_file;
  std::string out_dir = ".";
  bool no_plots = false;
};

void check_keys(const toml::table& t, const std::string& where,
                const std::set<std::string>& allowed) {
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (!allowed.count(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      const auto line = k.source().begin.line > 0 ? k.source().begin.line : v.source().begin.line;
      const std::string at = line > 0 ? fmt::format(" at line {}", line) : std::string();
      throw InvalidInput(fmt::format("{}: unknown key \"{}\"{} (allowed: {})",
                                     where.empty() ? std::string("top level") : where, key, at,
                                     list));
    }
  }
}

const toml::table* subtable(const toml::table& t, const std::string& key,
                            const std::string& where) {
  const auto* n = t.get(key);
  if (!n) return nullptr;
  const auto* tt = n->as_table();
  if (!tt) throw InvalidInput(fmt::format("{}.{} must be a table", where, key));
  return tt;
}

// Scales for quantities given with units.
struct Scales {
  std::optional<double> m, k, A;
  [[nodiscard]] bool complete() const { return m && k && A; }
};

// A value that is a plain number (non-dimensional) or a quantity string with units
// converted by `to_nondim` (which needs the scales).
std::optional<double> value(const toml::table& t, const std::string& key, const std::string& where,
                            Dimension d, const Scales& s,
                            const std::function<double(double, const Scales&)>& to_nondim) {
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

double number(const toml::table& t, const std::string& key, const std::string& where, double dflt) {
  const auto* n = t.get(key);
  if (!n) return dflt;
  if (auto x = n->value<double>(); x && (n->is_floating_point() || n->is_integer())) return *x;
  throw InvalidInput(fmt::format("{}.{} must be a number", where, key));
}

std::string text(const toml::table& t, const std::string& key, const std::string& where,
                 const std::string& dflt) {
  const auto* n = t.get(key);
  if (!n) return dflt;
  if (auto x = n->value<std::string>()) return *x;
  throw InvalidInput(fmt::format("{}.{} must be a string", where, key));
}

double time_scale(const Scales& s) {
  return std::sqrt(*s.m / *s.k);
}

struct Case {
  SystemParameters system;
  Excitation excitation;
  std::string excitation_name;
  std::unique_ptr<FrictionModel> friction;
  SimulationOptions sim;
  Scales scales;
  // analysis
  double f_min = 0.0, f_max = 0.0;
  std::size_t bins = 4000;
  double stick_velocity = 0.05;
  int loop_cycles = 5;
  double decay_start = -1.0;
  std::optional<Json> joint;  // the [joint]'s rough flat at its preload, for summary.json
};

hysteresis::MemoryRule memory_rule(const toml::table& t) {
  const std::string m = text(t, "memory", "dynamics.friction", "masing");
  if (m == "masing") return hysteresis::MemoryRule::masing;
  if (m == "reset_at_reversal" || m == "eq7.10") return hysteresis::MemoryRule::reset_at_reversal;
  throw InvalidInput(fmt::format(
      "dynamics.friction.memory = \"{}\": use \"masing\" or \"reset_at_reversal\" (Eq. 7.10)", m));
}

// ---- [joint] ---------------------------------------------------------------------------

// Adds the lines of the case file that hold any part of `n` (a node of the [dynamics]
// tree): the headers of its tables, its keys and its values.
void collect_lines(const toml::node& n, std::set<std::uint32_t>& lines) {
  auto add = [&lines](const toml::source_region& r) {
    if (r.begin.line == 0) return;
    for (auto l = r.begin.line; l <= std::max(r.begin.line, r.end.line); ++l) lines.insert(l);
  };
  if (const auto* t = n.as_table()) {
    // A [header] table: only its header line (its region may span other tables).
    if (t->is_inline()) {
      add(t->source());
    } else if (t->source().begin.line > 0) {
      lines.insert(t->source().begin.line);
    }
    for (const auto& [k, v] : *t) {
      add(k.source());
      collect_lines(v, lines);
    }
    return;
  }
  if (const auto* a = n.as_array()) {
    const bool headers =
        a->is_array_of_tables() && !a->empty() && !a->get(0)->as_table()->is_inline();
    if (!headers) add(a->source());  // [[header]] arrays: only their tables' headers
    for (const auto& e : *a) collect_lines(e, lines);
    return;
  }
  add(n.source());
}

// The case file with every line of its [dynamics] tree blanked: what remains is the
// joint part ([joint], [load], [profiles], comments) at its original line numbers, so
// that the joint reader's errors point into the user's file.
std::string joint_text(const std::string& text, const toml::node& dynamics) {
  std::set<std::uint32_t> lines;
  collect_lines(dynamics, lines);
  std::string out;
  out.reserve(text.size());
  std::uint32_t line = 1;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    if (!lines.count(line)) out.append(text, begin, end - begin);
    if (end == text.size()) break;
    out += '\n';
    begin = end + 1;
    ++line;
  }
  return out;
}

// The physics-based law of a joint described as for `asperity predict`: the joint's
// rough flat (RoughFlat::from_dimensional from the halves' materials and combined
// roughness, the area and the asperity model) at the [load]'s single preload, its SI
// backbone seen in the variables of section 7.2 through k and A.
std::unique_ptr<FrictionModel> joint_friction(const std::string& path, const std::string& file_text,
                                              const toml::table& root, const toml::table* friction,
                                              const Scales& s, std::optional<Json>& summary) {
  hysteresis::MemoryRule rule = hysteresis::MemoryRule::masing;
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
    rule = memory_rule(*friction);
  }
  if (!s.k || !s.A) {
    throw InvalidInput(
        "dynamics: the [joint] friction law needs the scales stiffness and amplitude in [dynamics] "
        "(forces are divided by k A, displacements by A)");
  }
  const auto dir = std::filesystem::path(path).parent_path();
  const joint::JointCase jc = joint::parse_case(joint_text(file_text, *root.get("dynamics")), path,
                                                dir.empty() ? "." : dir.string());
  // [load] is there: joint::parse_case requires it.
  const auto load_line = root.get("load")->source().begin.line;
  if (jc.preloads.size() != 1) {
    throw InvalidInput(
        fmt::format("{}:{}: load: `asperity dynamics` runs one preload; the [load] table gives {} "
                    "(a sweep): keep one",
                    path, load_line, jc.preloads.size()));
  }
  const double P = jc.preloads.front();
  const auto flat = jc.rough_flat();
  const joint::LoadPrediction lp = [&] {
    try {
      return joint::predict_load(flat, P, {});
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}:{}: load: {}", path, load_line, e.what()));
    }
  }();
  const double kA = *s.k * *s.A;
  Json j;
  j["name"] = jc.name;
  j["model"] = std::string(contact::to_string(jc.model));
  j["area"] = jc.area;
  j["preload"] = P;
  j["separation"] = lp.separation;
  j["Q_max"] = lp.Q_max;
  j["mu"] = lp.mu;
  j["stiffness"] = lp.stiffness;
  j["F_max_tilde"] = lp.Q_max / kA;
  j["stiffness_tilde"] = lp.stiffness / *s.k;
  summary = std::move(j);
  return make_physics_based(lp.backbone, *s.k, *s.A, rule);
}

// The physics-based (EPB) law of section 7.3 from Table 7.2-style inputs: combined
// E*, G*, hardness H and Poisson's ratio nu of the softer material, combined roughness
// (sigma, R, eta), nominal area A0 and normal load P (or P~ = P/(k A), the reading of
// Table 7.2's "P~ = 5" under which mu P~ = F~max = 1.5 with mu ~ 0.3); see
// dynamics/epb.hpp. Its SI backbone is seen in the variables of section 7.2 through k, A.
std::unique_ptr<FrictionModel> rough_flat_friction(const toml::table& t, const Scales& s,
                                                   hysteresis::MemoryRule rule) {
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
  const double nu = number(t, "nu", where, 0.3);
  double P = 0.0;
  if (t.get("P") && t.get("P_tilde")) throw InvalidInput(where + ": give P or P_tilde, not both");
  if (t.get("P")) {
    P = q("P", dim::force);
  } else {
    P = number(t, "P_tilde", where, 5.0) * *s.k * *s.A;
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
               .model = contact::parse_model_name(text(t, "asperity_model", where, "bke"))};
  if (t.get("mu_cfc")) c.friction.mu_cfc = number(t, "mu_cfc", where, 0.3);
  const auto si = epb_backbone(c);
  return make_physics_based(si, *s.k, *s.A, rule);
}

std::unique_ptr<FrictionModel> parse_friction(const toml::table* t, const Scales& s) {
  const std::string where = "dynamics.friction";
  if (!t) return std::make_unique<NoFriction>();
  const std::string model = text(*t, "model", where, "none");
  auto force = [&](const std::string& key) {
    return value(*t, key, where, dim::force, s,
                 [](double f, const Scales& sc) { return f / (*sc.k * *sc.A); });
  };
  auto length = [&](const std::string& key) {
    return value(*t, key, where, dim::length, s,
                 [](double x, const Scales& sc) { return x / *sc.A; });
  };
  auto stiff = [&](const std::string& key) {
    return value(*t, key, where, dim::stiffness, s,
                 [](double x, const Scales& sc) { return x / *sc.k; });
  };
  auto need = [&](const std::optional<double>& v, const std::string& key) {
    if (!v) throw InvalidInput(fmt::format("{}: model \"{}\" needs {}", where, model, key));
    return *v;
  };
  auto memory = [&] { return memory_rule(*t); };
  if (model == "none") {
    check_keys(*t, where, {"model"});
    return std::make_unique<NoFriction>();
  }
  if (model == "coulomb") {
    check_keys(*t, where, {"model", "F_max", "k_tan"});
    const auto k_tan =
        value(*t, "k_tan", where, Dimension{-1, 0, 1}, s,
              [](double x, const Scales& sc) { return x * *sc.A * std::sqrt(*sc.k / *sc.m); });
    return std::make_unique<RegularizedCoulomb>(RegularizedCoulombParameters{
        .F_max = need(force("F_max"), "F_max"), .k_tan = need(k_tan, "k_tan")});
  }
  if (model == "dankowicz") {
    check_keys(*t, where, {"model", "F_max", "delta"});
    return std::make_unique<Dankowicz>(DankowiczParameters{
        .F_max = need(force("F_max"), "F_max"), .delta = need(length("delta"), "delta")});
  }
  if (model == "jenkins") {
    check_keys(*t, where, {"model", "F_max", "stiffness"});
    return make_jenkins(need(stiff("stiffness"), "stiffness"), need(force("F_max"), "F_max"));
  }
  if (model == "iwan") {
    check_keys(*t, where, {"model", "F_S", "K_T", "chi", "beta"});
    return make_segalman_iwan({.F_S = need(force("F_S"), "F_S"),
                               .K_T = need(stiff("K_T"), "K_T"),
                               .chi = number(*t, "chi", where, -0.5),
                               .beta = number(*t, "beta", where, 0.1)});
  }
  if (model == "physics") {
    const std::string bb = text(*t, "backbone", where, "mindlin");
    if (bb == "rough_flat") return rough_flat_friction(*t, s, memory());
    if (bb == "joint") {
      throw InvalidInput(fmt::format(
          "{}.backbone = \"joint\" needs a [joint] table (and [load]) as for `asperity predict`",
          where));
    }
    if (bb != "mindlin") {
      throw InvalidInput(fmt::format(
          "{}.backbone = \"{}\": use \"rough_flat\", \"mindlin\" or \"joint\"", where, bb));
    }
    // A Cattaneo-Mindlin-shaped saturating backbone (the CFC limit of the rough flat:
    // Q = F_max (1 - (1 - x/s)^{3/2}) up to the slip displacement s) through Masing's
    // rules: a quick stand-in with two parameters.
    check_keys(*t, where, {"model", "backbone", "F_max", "slip_displacement", "memory"});
    const double F = need(force("F_max"), "F_max");
    const double sd = need(length("slip_displacement"), "slip_displacement");
    if (!(F > 0.0 && sd > 0.0)) {
      throw InvalidInput(fmt::format("{}: F_max and slip_displacement must be > 0", where));
    }
    auto backbone = std::make_shared<hysteresis::FunctionBackbone>(
        [F, sd](double x) { return x >= sd ? F : F * (1.0 - std::pow(1.0 - x / sd, 1.5)); }, F,
        1.5 * F / sd);
    return std::make_unique<HysteresisFriction>(backbone, memory(), "physics");
  }
  throw InvalidInput(fmt::format(
      "{}.model = \"{}\" is not known: use none, coulomb, dankowicz, jenkins, iwan or physics",
      where, model));
}

Case parse_case(const std::string& path) {
  std::string file_text;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InvalidInput(fmt::format("{}: cannot open the case file", path));
    std::ostringstream ss;
    ss << in.rdbuf();
    file_text = ss.str();
  }
  toml::table root;
  try {
    root = toml::parse(file_text, path);
  } catch (const toml::parse_error& e) {
    throw InvalidInput(
        fmt::format("{}: {} (line {})", path, e.description(), e.source().begin.line));
  }
  check_keys(root, path, {"dynamics", "joint", "load", "profiles"});
  if (!root.get("joint")) {
    for (const char* k : {"load", "profiles"}) {
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
  Case c;
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
                              [](double t, const Scales& s) { return t / time_scale(s); });
  c.sim.duration = duration.value_or(100.0);

  c.excitation_name = text(*d, "excitation", W, "impulse");
  const Scales& sc = c.scales;
  if (c.excitation_name == "impulse") {
    ImpulseExcitation e;
    if (const auto* t = subtable(*d, "impulse", W)) {
      check_keys(*t, W + ".impulse", {"Omega", "amplitude"});
      e.Omega =
          value(*t, "Omega", W + ".impulse", dim::frequency, sc, [](double w, const Scales& s) {
            return w * time_scale(s);
          }).value_or(e.Omega);
      e.amplitude = number(*t, "amplitude", W + ".impulse", 1.0);
    }
    c.excitation = e;
  } else if (c.excitation_name == "ramp") {
    RampExcitation e;
    if (const auto* t = subtable(*d, "ramp", W)) {
      check_keys(*t, W + ".ramp", {"alpha"});
      e.alpha = value(*t, "alpha", W + ".ramp", dim::velocity, sc, [](double b, const Scales& s) {
                  return b * time_scale(s) / *s.A;
                }).value_or(1.0);
    }
    c.excitation = e;
  } else if (c.excitation_name == "harmonic") {
    HarmonicExcitation e;
    if (const auto* t = subtable(*d, "harmonic", W)) {
      check_keys(*t, W + ".harmonic", {"frequency", "amplitude"});
      e.frequency = value(*t, "frequency", W + ".harmonic", dim::frequency, sc,
                          [](double f, const Scales& s) { return f * time_scale(s); })
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
    c.sim.u0 = number(*t, "u0", W + ".free", 0.0);
    c.sim.v0 = number(*t, "v0", W + ".free", 0.0);
  }

  if (root.get("joint")) {
    c.friction = joint_friction(path, file_text, root, subtable(*d, "friction", W), sc, c.joint);
  } else {
    c.friction = parse_friction(subtable(*d, "friction", W), sc);
  }

  c.sim.output_interval = 0.01;
  if (const auto* t = subtable(*d, "integrator", W)) {
    const std::string w = W + ".integrator";
    check_keys(*t, w,
               {"method", "rtol", "atol", "max_step", "initial_step", "min_step", "max_steps",
                "output_interval"});
    c.sim.integrator.method = parse_method(text(*t, "method", w, "dp54"));
    c.sim.integrator.rtol = number(*t, "rtol", w, 1e-6);
    if (const auto* a = t->get("atol")) {
      if (const auto* arr = a->as_array()) {
        c.sim.integrator.atol.clear();
        for (const auto& e : *arr) {
          auto x = e.value<double>();
          if (!x) throw InvalidInput(w + ".atol entries must be numbers");
          c.sim.integrator.atol.push_back(*x);
        }
      } else {
        c.sim.integrator.atol = {number(*t, "atol", w, 1e-7)};
      }
    }
    c.sim.integrator.max_step = number(*t, "max_step", w, 0.0);
    c.sim.integrator.initial_step = number(*t, "initial_step", w, 0.0);
    c.sim.integrator.min_step = number(*t, "min_step", w, 0.0);
    const double max_steps = number(*t, "max_steps", w, 5e7);
    if (!(max_steps >= 1 && max_steps <= 1e9))
      throw InvalidInput(w + ".max_steps must lie in [1, 1e9]");
    c.sim.integrator.max_steps = static_cast<std::size_t>(max_steps);
    c.sim.output_interval = number(*t, "output_interval", w, 0.01);
  }
  if (!(c.sim.output_interval > 0.0))
    throw InvalidInput("dynamics.integrator.output_interval must be > 0");
  c.sim.validate();
  c.sim.integrator.validate(2 + c.friction->internal_states() + 3);

  if (const auto* t = subtable(*d, "analysis", W)) {
    const std::string w = W + ".analysis";
    check_keys(*t, w, {"f_min", "f_max", "bins", "stick_velocity", "loop_cycles", "decay_start"});
    c.f_min = number(*t, "f_min", w, 0.0);
    c.f_max = number(*t, "f_max", w, 0.0);
    const double bins = number(*t, "bins", w, 4000);
    if (!(bins >= 16 && bins <= 1e6)) throw InvalidInput(w + ".bins must lie in [16, 1e6]");
    c.bins = static_cast<std::size_t>(bins);
    c.stick_velocity = number(*t, "stick_velocity", w, 0.05);
    if (!(c.stick_velocity > 0.0)) throw InvalidInput(w + ".stick_velocity must be > 0");
    const double lc = number(*t, "loop_cycles", w, 5);
    if (!(lc >= 1 && lc <= 1e4)) throw InvalidInput(w + ".loop_cycles must lie in [1, 1e4]");
    c.loop_cycles = static_cast<int>(lc);
    c.decay_start = number(*t, "decay_start", w, -1.0);
  }
  return c;
}

Json or_null(const std::optional<double>& v) {
  return v ? Json(*v) : Json(nullptr);
}

void run_dynamics(const DynamicsOptions& o, std::string& out) {
  const Case c = parse_case(o.case_file);
  std::error_code ec;
  std::filesystem::create_directories(o.out_dir, ec);
  if (ec)
    throw InvalidInput(
        fmt::format("cannot create the output directory \"{}\": {}", o.out_dir, ec.message()));

  SimulationOptions sim = c.sim;
  const bool decays = c.excitation_name == "impulse" || c.excitation_name == "free";
  if (decays) sim.locate_reversals = true;  // exact extrema for the logarithmic decrement
  const Trajectory tr = simulate(c.system, c.excitation, *c.friction, sim);

  Json j;
  j["case"] = o.case_file;
  j["excitation"] = c.excitation_name;
  j["friction_model"] = tr.friction_model;
  j["epsilon"] = c.system.epsilon;
  j["method"] = to_string(c.sim.integrator.method);
  j["rtol"] = c.sim.integrator.rtol;
  j["duration"] = c.sim.duration;

  // Modal frequency and half-power damping from the spectrum of the displacement.
  std::optional<double> modal_f, modal_z;
  std::optional<Spectrum> spectrum;
  std::string spectrum_note;
  const double dt = sim.output_interval;
  const double tau0 = std::holds_alternative<ImpulseExcitation>(c.excitation)
                          ? std::numbers::pi / std::get<ImpulseExcitation>(c.excitation).Omega
                          : 0.0;
  if (decays) {
    try {
      const Periodogram p(uniform_samples(tr, dt), dt);
      const double f_max = c.f_max > 0.0 ? c.f_max : std::min(0.5 / dt, 10.0);
      const double f_min = c.f_min > 0.0 ? c.f_min : 2.0 / c.sim.duration;
      spectrum = power_spectrum(p, f_min, f_max, c.bins);
      const auto m = modal_estimate(p, f_min, f_max, c.bins);
      modal_f = m.frequency;
      modal_z = m.damping_ratio;
      j["modal_half_power"] = {
          {"f_low", m.f_low}, {"f_high", m.f_high}, {"peak_power", m.peak_power}};
    } catch (const NumericalError& e) {
      spectrum_note = e.what();  // an overdamped response has no modal peak: report null
    }
  }
  j["modal_frequency"] = or_null(modal_f);
  j["modal_damping"] = or_null(modal_z);
  if (!spectrum_note.empty()) j["modal_note"] = spectrum_note;
  if (c.scales.m && c.scales.k && modal_f)
    j["modal_frequency_hz"] = *modal_f / time_scale(c.scales);

  if (c.joint) j["joint"] = *c.joint;
  j["energy_balance_error"] = tr.energy_balance_error();
  j["energy"] = {{"work_base", tr.work_base.back()},
                 {"dissipated_damper", tr.dissipated_damper.back()},
                 {"work_friction", tr.work_friction.back()},
                 {"mechanical_energy_change", tr.energy.back() - tr.energy.front()}};
  if (c.scales.k && c.scales.A) j["energy_scale_J"] = *c.scales.k * *c.scales.A * *c.scales.A;
  j["steps"] = tr.stats.steps;
  j["rejected_steps"] = tr.stats.rejected_steps;
  j["rhs_evaluations"] = tr.stats.rhs_evaluations;
  j["force_evaluations"] = tr.force_evaluations;
  j["events"] = tr.stats.events;

  if (decays) {
    const auto decay = free_decay(tr, c.decay_start >= 0.0 ? c.decay_start : tau0);
    Json jd = Json::array();
    for (const auto& p : decay) {
      jd.push_back({{"tau", p.tau},
                    {"amplitude", p.amplitude},
                    {"frequency", p.frequency},
                    {"damping_ratio", p.damping_ratio}});
    }
    j["free_decay"] = {{"method", "logarithmic decrement over full cycles of successive swings"},
                       {"cycles", jd}};
  }
  if (const auto* r = std::get_if<RampExcitation>(&c.excitation)) {
    const double thr = c.stick_velocity * std::abs(r->alpha);
    const auto iv = stick_slip_intervals(tr, thr);
    Json ji = Json::array();
    for (const auto& i : iv)
      ji.push_back({{"begin", i.begin}, {"end", i.end}, {"state", i.stick ? "stick" : "slip"}});
    j["stick_slip"] = {{"velocity_threshold", thr}, {"intervals", ji}};
    j["first_slip"] = iv.size() > 1 && iv[0].stick ? Json(iv[0].end) : Json(nullptr);
  }
  if (const auto* h = std::get_if<HarmonicExcitation>(&c.excitation)) {
    const double period = 1.0 / h->frequency;
    if (c.sim.duration >= (c.loop_cycles + 1) * period) {
      const auto loop = steady_loop(tr, period, c.loop_cycles);
      j["steady_loop"] = {{"cycles", c.loop_cycles},
                          {"energy_per_cycle", loop.energy_per_cycle},
                          {"displacement_amplitude", loop.displacement_amplitude},
                          {"force_amplitude", loop.force_amplitude},
                          {"mean_displacement", loop.mean_displacement}};
    }
  }

  const std::filesystem::path dir(o.out_dir);
  {
    std::string csv = "tau,u,v,y,friction,work_base,dissipated_damper,work_friction,energy,event\n";
    csv.reserve(tr.size() * 120);
    for (std::size_t i = 0; i < tr.size(); ++i) {
      csv += fmt::format(
          "{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{}\n", tr.tau[i],
          tr.u[i], tr.v[i], tr.y[i], tr.friction[i], tr.work_base[i], tr.dissipated_damper[i],
          tr.work_friction[i], tr.energy[i], tr.is_event[i] ? 1 : 0);
    }
    write_file_atomically((dir / "timeseries.csv").string(), csv);
  }
  if (spectrum) {
    std::string csv = "frequency,power\n";
    for (std::size_t i = 0; i < spectrum->frequency.size(); ++i) {
      csv += fmt::format("{:.10g},{:.10g}\n", spectrum->frequency[i], spectrum->power[i]);
    }
    write_file_atomically((dir / "spectrum.csv").string(), csv);
  }
  write_file_atomically((dir / "summary.json").string(), j.dump(2) + "\n");

  std::vector<std::string> plots;
  if (!o.no_plots) {
    const std::string label =
        fmt::format("{} friction, {} excitation", tr.friction_model, c.excitation_name);
    // Thin the series for plotting (gnuplot reads text).
    const std::size_t stride = std::max<std::size_t>(1, tr.size() / 20000);
    auto series = [&](const std::string& title, const std::vector<double>& x,
                      const std::vector<double>& y, double t_from) {
      Series s{.title = title};
      for (std::size_t i = 0; i < tr.size(); i += stride) {
        if (tr.tau[i] < t_from) continue;
        s.x.push_back(x[i]);
        s.y.push_back(y[i]);
      }
      return s;
    };
    PlotSpec resp{
        .title = "Response (Fig. 7.5 style): " + label, .xlabel = "tau", .ylabel = "u = x/A"};
    resp.series.push_back(series("mass u", tr.tau, tr.u, 0.0));
    if (c.excitation_name != "free") resp.series.push_back(series("base y", tr.tau, tr.y, 0.0));
    plot_png((dir / "response.png").string(), resp);
    plots.push_back("response.png");
    // Phase portrait and friction loop: the steady part for harmonic input (Fig. 7.6-7.7).
    double from = 0.0;
    if (const auto* h = std::get_if<HarmonicExcitation>(&c.excitation)) {
      from = std::max(0.0, c.sim.duration - c.loop_cycles / h->frequency);
    }
    PlotSpec phase{.title = "Phase portrait (Fig. 7.6a-b / 7.7a-b style): " + label,
                   .xlabel = "u",
                   .ylabel = "u'"};
    phase.series.push_back(series("mass", tr.u, tr.v, from));
    plot_png((dir / "phase.png").string(), phase);
    plots.push_back("phase.png");
    if (tr.friction_model != "none") {
      PlotSpec loop{
          .title = "Friction force vs displacement (Fig. 7.6c-d / 7.7c-d style): " + label,
          .xlabel = "u",
          .ylabel = "F_s = f_s/(k A)"};
      loop.series.push_back(series("friction", tr.u, tr.friction, from));
      plot_png((dir / "friction_loop.png").string(), loop);
      plots.push_back("friction_loop.png");
    }
    if (spectrum) {
      PlotSpec sp{.title = "Power spectrum of u (Fig. 7.3-7.4 style): " + label,
                  .xlabel = "frequency [cycles per unit tau]",
                  .ylabel = "power",
                  .logy = true};
      Series s{.title = tr.friction_model};
      for (std::size_t i = 0; i < spectrum->frequency.size(); ++i) {
        if (spectrum->power[i] > 0.0) {
          s.x.push_back(spectrum->frequency[i]);
          s.y.push_back(spectrum->power[i]);
        }
      }
      sp.series.push_back(std::move(s));
      plot_png((dir / "spectrum.png").string(), sp);
      plots.push_back("spectrum.png");
    }
  }

  out += fmt::format(
      "{}: {} friction, {} excitation, eps = {:.4g}, {} steps ({} rejected), {} force evaluations, "
      "{} reversals\n",
      o.case_file, tr.friction_model, c.excitation_name, c.system.epsilon, tr.stats.steps,
      tr.stats.rejected_steps, tr.force_evaluations, tr.stats.events);
  if (c.joint) {
    const Json& jj = *c.joint;
    out += fmt::format(
        "joint: preload {:.6g} N, mu = Q_max/P = {:.4g}, Q_max {:.6g} N, tangential stiffness "
        "{:.4g} N/m (F~max = {:.4g}, k_t/k = {:.4g})\n",
        jj["preload"].get<double>(), jj["mu"].get<double>(), jj["Q_max"].get<double>(),
        jj["stiffness"].get<double>(), jj["F_max_tilde"].get<double>(),
        jj["stiffness_tilde"].get<double>());
  }
  if (modal_f)
    out += fmt::format("modal frequency {:.5g} (cycles per unit tau), half-power damping {:.4g}\n",
                       *modal_f, *modal_z);
  out += fmt::format("energy balance error {:.3g} of the input work\n", tr.energy_balance_error());
  out += fmt::format("wrote {}/summary.json, timeseries.csv{}", o.out_dir,
                     spectrum ? ", spectrum.csv" : "");
  for (const auto& p : plots) out += ", " + p;
  out += "\n";
}

}  // namespace

void add_dynamics_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<DynamicsOptions>();
  auto* cmd = app.add_subcommand(
      "dynamics",
      "Single-DOF base-excited system with friction (thesis ch. 7): impulse, ramp or harmonic "
      "base motion, with regularized Coulomb, Dankowicz, Jenkins, Iwan or physics-based friction "
      "(from rough-flat parameters, or from a [joint] and [load] as for `asperity predict`). "
      "Writes summary.json, timeseries.csv, spectrum.csv and PNG plots.");
  cmd->add_option(
         "case", o->case_file,
         "TOML case file with a [dynamics] table (and optionally [joint], [load], [profiles])")
      ->required();
  cmd->add_option("--out", o->out_dir, "output directory (created if missing)")->default_str(".");
  cmd->add_flag("--no-plots", o->no_plots, "skip the PNG plots (no gnuplot needed)");
  cmd->callback([o, &action] {
    action = [o] { return run_guarded([o](std::string& out) { run_dynamics(*o, out); }); };
  });
}

}  // namespace asperity::cli
