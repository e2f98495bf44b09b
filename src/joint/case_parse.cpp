// Joint case files (TOML): read and validated into a JointCase ([interface] is read by
// case_interface.cpp).
#include <fmt/format.h>

#include <toml++/toml.h>
#include <algorithm>
#include <cstdint>
#include <string_view>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/units.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/surface/profile.hpp"
#include "asperity/surface/roughness.hpp"
#include "case_parse.hpp"

namespace asperity::joint {

namespace dim = core::dim;
using detail::parse_interface;
using detail::Reader;

namespace {

// The profile processing's messages suggest `asperity roughness` flags; in a case file
// the same settings are keys of [profiles].
std::string case_file_hint(std::string msg) {
  const std::pair<std::string_view, std::string_view> flags[] = {
      {"--end regression", "end = \"regression\" in [profiles]"},
      {"(--dx, e.g. 0.5um)", "(dx = \"0.5 um\" in [profiles])"},
      {"so --dx must not be given", "so [profiles] dx must not be given"},
      {"a shorter --lc", "a shorter lc in [profiles]"},
      {"a shorter lc (--lc)", "a shorter lc (lc in [profiles])"},
      {"a shorter ls (--ls)", "a shorter ls (ls in [profiles])"}};
  for (const auto& [flag, key] : flags) {
    for (auto at = msg.find(flag); at != std::string::npos; at = msg.find(flag, at + key.size()))
      msg.replace(at, flag.size(), key);
  }
  // "--lc 395um --ls 5um" (a cut-off pair that fits) -> lc = "395um", ls = "5um" in [profiles].
  for (const std::string_view key : {"lc", "ls"}) {
    const std::string flag = fmt::format("--{} ", key);
    for (auto at = msg.find(flag); at != std::string::npos; at = msg.find(flag, at + 1)) {
      const auto begin = at + flag.size();
      const auto end = std::min(msg.find_first_of(" ;", begin), msg.size());
      const std::string value = msg.substr(begin, end - begin);
      msg.replace(at, end - at,
                  fmt::format("{} = \"{}\"{}", key, value, key == "lc" ? "," : " in [profiles]"));
    }
  }
  return msg;
}

contact::Material parse_material(const Reader& r, const toml::node& n, const std::string& where) {
  const auto* t = n.as_table();
  if (!t)
    r.fail(&n, where,
           "must be a table { E = \"200 GPa\", nu = 0.24, G = \"80.7 GPa\", H = \"5.8 GPa\" }");
  r.check_keys(*t, where, {"E", "nu", "G", "H"});
  contact::Material m;
  m.E = r.positive(*t, "E", dim::pressure, where);
  m.nu = r.required(*t, "nu", dim::dimensionless, where);
  if (!(m.nu >= 0.0 && m.nu < 0.5))
    r.fail_value(t->get("nu"), where + ".nu", "must be in [0, 0.5)");
  m.G = r.optional_quantity(*t, "G", dim::pressure, where).value_or(0.0);
  if (t->get("G") && !(m.G > 0.0)) r.fail_value(t->get("G"), where + ".G", "must be > 0");
  m.H = r.optional_quantity(*t, "H", dim::pressure, where).value_or(0.0);
  if (t->get("H") && !(m.H > 0.0)) r.fail_value(t->get("H"), where + ".H", "must be > 0");
  // Hardness is about 3 times the yield stress (Tabor), which lies far below E: H/E runs
  // from about 1e-3 (lead) to 0.1 (diamond-like coatings).
  if (m.H > 0.0 && !(m.H < m.E)) {
    r.fail_value(t->get("H"), where + ".H",
                 fmt::format("must be below the Young's modulus E = {} Pa of the same material "
                             "(hardness is about 3 times the yield stress; H/E is 1e-3 to 0.1)",
                             core::format_value(m.E)));
  }
  return m;
}

// A [profiles] table, or a half's `processing` table (its keys override `base`, the case's
// [profiles], for that half only: the two surfaces are often measured differently).
ProfileSettings parse_profile_settings(const Reader& r, const toml::node& p, const std::string& w,
                                       ProfileSettings base) {
  const auto* t = p.as_table();
  if (!t) r.fail(&p, w, "must be a table");
  r.check_keys(*t, w, {"lc", "ls", "end", "truncation", "rule", "level", "dx"});
  try {
    if (const auto* n = t->get("lc")) {
      const auto s = n->value<std::string>();
      base.filter.lc = (s && *s == "none") ? 0.0 : r.quantity(*n, dim::length, w + ".lc");
    }
    if (const auto* n = t->get("ls")) {
      const auto s = n->value<std::string>();
      base.filter.ls = (s && *s == "none") ? 0.0 : r.quantity(*n, dim::length, w + ".ls");
    }
    if (t->get("end"))
      base.filter.end = surface::parse_end_effects(r.string(*t, "end", w, ""), w + ".end");
    if (const auto* n = t->get("dx")) {
      const double dx = r.quantity(*n, dim::length, w + ".dx");
      if (!(dx > 0.0) || !std::isfinite(dx)) r.fail_value(n, w + ".dx", "must be > 0");
      base.dx = dx;
    }
    if (const auto* n = t->get("truncation"))
      base.filter.truncation = r.quantity(*n, dim::dimensionless, w + ".truncation");
    base.filter.validate();
    if (t->get("rule"))
      base.rule = surface::parse_isotropic_rule(r.string(*t, "rule", w, ""), w + ".rule");
    if (t->get("level"))
      base.level = surface::parse_levelling(r.string(*t, "level", w, ""), w + ".level");
  } catch (const InvalidInput& e) {
    if (std::string_view(e.what()).starts_with(r.source())) throw;
    r.fail(&p, w, e.what());
  }
  return base;
}

HalfRoughness parse_roughness(const Reader& r, const toml::table& half, const std::string& where,
                              const ProfileSettings& settings) {
  const auto* rough = half.get("roughness");
  const auto* prof = half.get("profiles");
  if (rough && prof) r.fail(prof, where, "give either roughness or profiles, not both");
  if (!rough && !prof) {
    r.fail(&half, where,
           "missing roughness: give roughness = { sigma, eta, R } or profiles = [scan files]");
  }
  if (rough) {
    const std::string w = where + ".roughness";
    const auto* t = rough->as_table();
    if (!t)
      r.fail(rough, w,
             "must be a table { sigma = \"1.763 um\", eta = \"3.34e-4 um^-2\", R = \"40.76 um\" }");
    r.check_keys(*t, w, {"sigma", "eta", "R"});
    const double sigma = r.positive(*t, "sigma", dim::length, w);
    const double eta = r.positive(*t, "eta", dim::inverse_area, w);
    const double R = r.positive(*t, "R", dim::length, w);
    return {surface::SpectralMoments::from_parameters(sigma, eta, R), {}, {}};
  }
  const std::string w = where + ".profiles";
  const auto* a = prof->as_array();
  if (!a || a->empty()) {
    r.fail(prof, w,
           "must be an array of scan files, e.g. [\"pzt_max.csv\", \"pzt_min.csv\"] (tags "
           "FILE@max / FILE@min and one areal file as for `asperity roughness --surface`)");
  }
  std::vector<std::string> files;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto s = a->get(i)->value<std::string>();
    if (!s) r.fail(a->get(i), fmt::format("{}[{}]", w, i + 1), "must be a file name");
    // The tag is split off before the path is resolved against the case file's folder.
    std::string tag;
    for (std::string_view t : {"@max", "@min"}) {
      if (s->size() > t.size() && s->ends_with(t)) tag = std::string(t);
    }
    files.push_back(r.resolve(s->substr(0, s->size() - tag.size())) + tag);
  }
  try {
    return half_roughness_from_files(files, settings);
  } catch (const InvalidInput& e) {
    r.fail(prof, w, case_file_hint(e.what()));
  }
}

}  // namespace

JointCase parse_case(std::string_view text, const std::string& source,
                     const std::string& base_dir) {
  const Reader r(source, base_dir);
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw InvalidInput(fmt::format("{}:{}: TOML syntax error: {}", source, e.source().begin.line,
                                   e.description()));
  }
  r.check_keys(root, "", {"joint", "load", "excitation", "profiles", "reference", "interface"});

  JointCase c;
  c.source = source;
  const auto& joint = r.table(root, "joint", "");
  r.check_keys(joint, "joint", {"name", "area", "model", "mu_cfc", "zeta", "slip_scaling", "half"});
  c.name = r.string(joint, "name", "joint", "");
  c.area = r.positive(joint, "area", dim::area, "joint");
  {
    const std::string m = r.string(joint, "model", "joint", "bke");
    try {
      c.model = contact::parse_model_name(m);
    } catch (const InvalidInput& e) {
      r.fail(joint.get("model"), "joint.model", e.what());
    }
  }
  if (const auto mu = r.optional_quantity(joint, "mu_cfc", dim::dimensionless, "joint")) {
    if (!(*mu > 0.0)) r.fail_value(joint.get("mu_cfc"), "joint.mu_cfc", "must be > 0");
    c.friction.mu_cfc = *mu;
  } else if (c.model == contact::ModelName::cfc) {
    r.fail(&joint, "joint.mu_cfc",
           "missing: the cfc model needs the constant friction coefficient");
  }
  if (const auto z = r.optional_quantity(joint, "zeta", dim::dimensionless, "joint"))
    c.friction.zeta = *z;
  {
    const std::string s = r.string(joint, "slip_scaling", "joint", "elastic");
    if (s == "elastic") {
      c.slip_scaling = surface::SlipScaling::elastic;
    } else if (s == "own_law") {
      c.slip_scaling = surface::SlipScaling::own_law;
    } else {
      r.fail(joint.get("slip_scaling"), "joint.slip_scaling",
             fmt::format("\"{}\": use elastic or own_law", s));
    }
  }

  // Profile processing settings (used only by halves given as scans).
  if (const auto* p = root.get("profiles"))
    c.profile_settings = parse_profile_settings(r, *p, "profiles", c.profile_settings);

  const auto* halves = joint.get("half");
  if (!halves)
    r.fail(&joint, "joint.half", "missing: give two [[joint.half]] tables (the two joint halves)");
  const auto* arr = halves->as_array();
  if (!arr || !arr->is_array_of_tables())
    r.fail(halves, "joint.half", "must be [[joint.half]] tables");
  if (arr->size() != 2) {
    r.fail(halves, "joint.half",
           fmt::format("found {} [[joint.half]] table{}; a joint has two (one per half)",
                       arr->size(), arr->size() == 1 ? "" : "s"));
  }
  c.roughness_origin = r.origin(arr->get(0), "joint.half[1-2].roughness");
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string w = fmt::format("joint.half[{}]", i + 1);
    const auto& h = *arr->get(i)->as_table();
    r.check_keys(h, w, {"name", "material", "roughness", "profiles", "processing"});
    const auto* mat = h.get("material");
    if (!mat) r.fail(&h, w + ".material", "missing");
    c.halves[i].material = parse_material(r, *mat, w + ".material");
    c.halves[i].profile_settings = c.profile_settings;
    if (const auto* pn = h.get("processing")) {
      if (!h.get("profiles")) {
        r.fail(pn, w + ".processing",
               "is used only with profiles = [scan files] (this half's roughness is given as "
               "parameters)");
      }
      c.halves[i].profile_settings =
          parse_profile_settings(r, *pn, w + ".processing", c.profile_settings);
    }
    c.halves[i].roughness = parse_roughness(r, h, w, c.halves[i].profile_settings);
  }
  if (c.halves[0].material.H <= 0.0 && c.halves[1].material.H <= 0.0) {
    r.fail(halves, "joint.half[].material.H", "give the hardness H of at least one half");
  }

  if (const auto* in = root.get("interface")) parse_interface(r, *in, c);
  const bool map_as_given =
      c.interface.pressure == PressureKind::map && !c.interface.map.scale_to_preload;
  if (map_as_given) {
    if (root.get("load")) {
      r.fail(root.get("load"), "load",
             "interface.scale_to_preload = false: the map's own integral is the load; remove "
             "[load] or set scale_to_preload = true");
    }
    c.interface.validate(c.area);
    const double P = map_total_force(c.interface, c.area);
    if (!(P > 0.0)) r.fail(root.get("interface"), "interface.map", "the map carries no force");
    c.preloads = {P};
    c.preload_origin = {r.origin(root.get("interface"), "interface.map (used as given)")};
  }
  // Load: exactly one of preload, preloads, bolts.
  const toml::table no_load;
  const auto& load = map_as_given ? no_load : r.table(root, "load", "");
  r.check_keys(load, "load", {"preload", "preloads", "bolts"});
  const int given =
      (load.get("preload") ? 1 : 0) + (load.get("preloads") ? 1 : 0) + (load.get("bolts") ? 1 : 0);
  if (map_as_given) {
    // the load came from the map
  } else if (given != 1) {
    r.fail(&load, "load",
           "give exactly one of preload = \"526 N\", preloads = [...] or bolts = { ... }");
  }
  if (map_as_given) {
    // done above
  } else if (const auto* n = load.get("preload")) {
    const double P = r.quantity(*n, dim::force, "load.preload");
    if (!(P > 0.0) || !std::isfinite(P)) r.fail_value(n, "load.preload", "must be > 0");
    c.preloads = {P};
    c.preload_origin = {r.origin(n, "load.preload = " + Reader::text_of(n))};
  } else if (const auto* n2 = load.get("preloads")) {
    c.preloads = r.quantity_list(*n2, dim::force, "load.preloads", true);
    for (std::size_t i = 0; i < c.preloads.size(); ++i) {
      const auto* e = n2->as_array()->get(i);
      c.preload_origin.push_back(
          r.origin(e, fmt::format("load.preloads[{}] = {}", i + 1, Reader::text_of(e))));
    }
  } else {
    const auto* bn = load.get("bolts");
    const auto* b = bn->as_table();
    if (!b)
      r.fail(bn, "load.bolts",
             "must be a table { count = 2, torque = \"0.1525 N*m\", nut_factor = 0.2, diameter = "
             "\"2.9 mm\" }");
    r.check_keys(
        *b, "load.bolts",
        {"count", "torque", "torques", "total_torque", "total_torques", "nut_factor", "diameter"});
    Bolts bolts;
    if (const auto* cn = b->get("count")) {
      const auto v = cn->value<int64_t>();
      if (!cn->is_integer() || !v || *v < 1 || *v > 1000)
        r.fail_value(cn, "load.bolts.count", "must be a whole number from 1 to 1000");
      bolts.count = static_cast<int>(*v);
    }
    bolts.nut_factor =
        r.optional_quantity(*b, "nut_factor", dim::dimensionless, "load.bolts").value_or(0.2);
    // Shigley's Mechanical Engineering Design, Table 8-15: k = 0.1 (lubricated) to 0.3 (dry).
    if (!(bolts.nut_factor > 0.0 && bolts.nut_factor <= 1.0))
      r.fail_value(b->get("nut_factor"), "load.bolts.nut_factor",
                   "must lie in (0, 1]: the nut factor k of T = k F D (Eq. 5.2) is about 0.1 "
                   "(lubricated) to 0.3 (dry), 0.2 for steel bolts");
    bolts.diameter = r.positive(*b, "diameter", dim::length, "load.bolts");
    const int nt = (b->get("torque") ? 1 : 0) + (b->get("torques") ? 1 : 0) +
                   (b->get("total_torque") ? 1 : 0) + (b->get("total_torques") ? 1 : 0);
    if (nt != 1) {
      r.fail(b, "load.bolts",
             "give exactly one of torque, torques (per bolt), total_torque or total_torques (all "
             "bolts)");
    }
    const bool total = b->get("total_torque") || b->get("total_torques");
    for (const char* key : {"torque", "total_torque"}) {
      if (const auto* tn = b->get(key)) {
        const double T = r.quantity(*tn, dim::energy, std::string("load.bolts.") + key);
        if (!(T > 0.0) || !std::isfinite(T))
          r.fail_value(tn, std::string("load.bolts.") + key, "must be > 0");
        bolts.torques = {T};
        c.preload_origin = {
            r.origin(tn, fmt::format("load.bolts.{} = {}", key, Reader::text_of(tn)))};
      }
    }
    for (const char* key : {"torques", "total_torques"}) {
      if (const auto* tn = b->get(key)) {
        bolts.torques = r.quantity_list(*tn, dim::energy, std::string("load.bolts.") + key, true);
        for (std::size_t i = 0; i < bolts.torques.size(); ++i) {
          const auto* e = tn->as_array()->get(i);
          c.preload_origin.push_back(
              r.origin(e, fmt::format("load.bolts.{}[{}] = {}", key, i + 1, Reader::text_of(e))));
        }
      }
    }
    if (total) {
      for (double& T : bolts.torques) T /= static_cast<double>(bolts.count);
    }
    for (double T : bolts.torques) c.preloads.push_back(bolts.preload(T));
    c.bolts = bolts;
  }

  if (const auto* en = root.get("excitation")) {
    const auto* e = en->as_table();
    if (!e) r.fail(en, "excitation", "must be a table");
    r.check_keys(*e, "excitation", {"amplitudes", "imposed", "apparatus"});
    if (const auto* a = e->get("amplitudes"))
      c.amplitudes = r.quantity_list(*a, dim::length, "excitation.amplitudes", true);
    if (const auto* a = e->get("imposed"))
      c.imposed = r.quantity_list(*a, dim::length, "excitation.imposed", true);
    if (!e->get("amplitudes") && !e->get("imposed")) {
      r.fail(en, "excitation",
             "give amplitudes = [\"0.5 um\", ...] (of the joint) and/or imposed = [\"6.75 um\", "
             "...] (at the PZT tip, through the apparatus); or leave out [excitation]");
    }
    if (const auto* ap = e->get("apparatus")) {
      const auto* t = ap->as_table();
      if (!t)
        r.fail(ap, "excitation.apparatus",
               "must be a table { pzt_stiffness = \"38 N/um\", load_cell_stiffness = \"1462 "
               "N/um\" }");
      r.check_keys(*t, "excitation.apparatus", {"pzt_stiffness", "load_cell_stiffness"});
      if (t->get("pzt_stiffness"))
        c.apparatus.pzt_stiffness =
            r.positive(*t, "pzt_stiffness", dim::stiffness, "excitation.apparatus");
      if (t->get("load_cell_stiffness"))
        c.apparatus.load_cell_stiffness =
            r.positive(*t, "load_cell_stiffness", dim::stiffness, "excitation.apparatus");
      if (!e->get("imposed"))
        r.fail(ap, "excitation.apparatus",
               "is used only with imposed amplitudes (imposed = [...])");
    }
  }
  if (const auto* rn = root.get("reference")) {
    const auto* t = rn->as_table();
    if (!t) r.fail(rn, "reference", "must be a table");
    r.check_keys(*t, "reference", {"source", "preloads", "mu"});
    const auto* pn = t->get("preloads");
    const auto* mn = t->get("mu");
    if (!pn || !mn)
      r.fail(rn, "reference", "needs preloads = [\"234 N\", ...] and mu = [0.354, ...]");
    ReferenceMu ref;
    ref.source = r.string(*t, "source", "reference", "reference");
    ref.preloads = r.quantity_list(*pn, dim::force, "reference.preloads", true);
    ref.mu = r.quantity_list(*mn, dim::dimensionless, "reference.mu", true);
    if (ref.mu.size() != ref.preloads.size()) {
      r.fail(mn, "reference.mu",
             fmt::format("has {} values for {} preloads: give one mu per preload", ref.mu.size(),
                         ref.preloads.size()));
    }
    c.reference = std::move(ref);
  }
  std::sort(c.amplitudes.begin(), c.amplitudes.end());
  std::sort(c.imposed.begin(), c.imposed.end());
  if (c.interface.pressure == PressureKind::bolted && c.bolts &&
      static_cast<int>(c.interface.bolts.positions.size()) != c.bolts->count) {
    r.fail(root.get("interface"), "interface.bolts.positions",
           fmt::format("{} positions given for load.bolts.count = {}: give one per bolt",
                       c.interface.bolts.positions.size(), c.bolts->count));
  }
  try {
    c.interface.validate(c.area);
  } catch (const InvalidInput& e) {
    if (std::string_view(e.what()).starts_with(source)) throw;
    r.fail(root.get("interface"), "interface", e.what());
  }
  c.validate();
  return c;
}

JointCase read_case_file(const std::string& path) {
  const core::CaseFileText f = core::read_case_file_text(path);
  return parse_case(f.text, path, f.base_dir);
}

}  // namespace asperity::joint
