// Joint case files (TOML) and the torque-preload relation of Eq. 5.2.
#include "asperity/joint/case.hpp"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/units.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/scan_set.hpp"

namespace asperity::joint {

namespace dim = core::dim;

double bolt_preload(double torque, double nut_factor, double diameter) {
  if (!(torque > 0.0) || !std::isfinite(torque)) {
    throw InvalidInput(fmt::format("bolt torque = {} N*m must be > 0", torque));
  }
  if (!(nut_factor > 0.0) || !std::isfinite(nut_factor)) {
    throw InvalidInput(
        fmt::format("nut factor = {} must be > 0 (0.2 for steel bolts)", nut_factor));
  }
  if (!(diameter > 0.0) || !std::isfinite(diameter)) {
    throw InvalidInput(fmt::format("bolt diameter = {} m must be > 0", diameter));
  }
  return torque / (nut_factor * diameter);  // Eq. 5.2: T = k F D
}

double Bolts::preload(double torque) const {
  return static_cast<double>(count) * bolt_preload(torque, nut_factor, diameter);
}

HalfRoughness half_roughness_from_files(const std::vector<std::string>& files,
                                        const ProfileSettings& settings) {
  if (files.empty()) throw InvalidInput("profiles: give the scan files");
  settings.filter.validate();
  std::vector<surface::ScanFile> scans;
  for (const auto& f : files) scans.push_back(surface::parse_scan_file(f));
  // The same function as `asperity roughness --surface` (scan_set.hpp).
  const auto r = surface::equivalent_isotropic_surface(scans, {.level = settings.level,
                                                               .filter = settings.filter,
                                                               .rule = settings.rule,
                                                               .text = {.dx = settings.dx}});
  HalfRoughness out;
  for (const auto& sc : scans) out.profiles.push_back(sc.path);
  out.moments = r.moments;
  for (const auto& sc : r.scans) {
    // "isotropic (one scan)" -> "isotropic", "x (max_slope)" -> "max_slope"
    const auto open = sc.direction.find('(');
    std::string d = sc.direction;
    if (sc.direction.starts_with("isotropic")) {
      d = "isotropic";
    } else if (open != std::string::npos) {
      d = sc.direction.substr(open + 1, sc.direction.size() - open - 2);
    }
    out.directions.push_back(d);
  }
  return out;
}

surface::SpectralMoments JointCase::combined_roughness() const {
  return surface::combine(halves[0].roughness.moments, halves[1].roughness.moments);
}

surface::RoughFlat JointCase::rough_flat() const {
  const auto c = combined_roughness();
  try {
    return surface::RoughFlat::from_dimensional(halves[0].material, halves[1].material, c.sigma(),
                                                c.eta(), c.R(), area, model, friction,
                                                slip_scaling);
  } catch (const InvalidInput& e) {
    // The combined roughness (or the materials) of both halves: name where they are.
    if (roughness_origin.empty()) throw;
    throw InvalidInput(
        fmt::format("{} (combined: sigma = {:.4g} um, eta = {:.4g} um^-2, R = "
                    "{:.4g} um): {}",
                    roughness_origin, c.sigma() * 1e6, c.eta() * 1e-12, c.R() * 1e6, e.what()));
  }
}

void JointCase::validate() const {
  if (!(area > 0.0) || !std::isfinite(area)) {
    throw InvalidInput(fmt::format("{}: joint.area = {} m^2 must be > 0", source, area));
  }
  if (preloads.empty()) throw InvalidInput(fmt::format("{}: no load case", source));
  for (double P : preloads) {
    if (!(P > 0.0) || !std::isfinite(P)) {
      throw InvalidInput(fmt::format("{}: preload = {} N must be > 0", source, P));
    }
  }
  for (double a : amplitudes) {
    if (!(a > 0.0) || !std::isfinite(a)) {
      throw InvalidInput(fmt::format("{}: amplitude = {:.6g} m must be > 0", source, a));
    }
  }
  for (double a : imposed) {
    if (!(a > 0.0) || !std::isfinite(a)) {
      throw InvalidInput(fmt::format("{}: imposed amplitude = {:.6g} m must be > 0", source, a));
    }
  }
  if (!(apparatus.pzt_stiffness > 0.0) || !(apparatus.load_cell_stiffness > 0.0) ||
      !std::isfinite(apparatus.compliance())) {
    throw InvalidInput(fmt::format("{}: the apparatus stiffnesses must be > 0", source));
  }
  for (std::size_t i = 0; i < 2; ++i) {
    halves[i].material.validate(fmt::format("joint.half[{}].material", i + 1));
    halves[i].roughness.moments.validate(fmt::format("joint.half[{}].roughness", i + 1));
  }
  if (halves[0].material.H <= 0.0 && halves[1].material.H <= 0.0) {
    throw InvalidInput(fmt::format("{}: give the hardness H of at least one half", source));
  }
}

namespace {

// Error context: the file and the line of a node.
class Reader {
 public:
  Reader(std::string source, std::string base_dir)
      : source_(std::move(source)), base_(std::move(base_dir)) {}

  [[noreturn]] void fail(const toml::node* n, const std::string& key,
                         const std::string& what) const {
    const auto line = n ? n->source().begin.line : 0U;
    if (line > 0) throw InvalidInput(fmt::format("{}:{}: {}: {}", source_, line, key, what));
    throw InvalidInput(fmt::format("{}: {}: {}", source_, key, what));
  }

  // "FILE:LINE: key" of a node.
  [[nodiscard]] std::string origin(const toml::node* n, const std::string& key) const {
    const auto line = n ? n->source().begin.line : 0U;
    if (line > 0) return fmt::format("{}:{}: {}", source_, line, key);
    return fmt::format("{}: {}", source_, key);
  }

  // The value as the user wrote it: "\"-1.2 lbf*in\"" or "0.24".
  static std::string text_of(const toml::node* n) {
    if (!n) return "";
    if (const auto s = n->value<std::string>()) return fmt::format("\"{}\"", *s);
    if (n->is_boolean()) return *n->value<bool>() ? "true" : "false";
    if (const auto v = n->value<double>()) return fmt::format("{}", *v);
    return "(a table or array)";
  }

  // "FILE:LINE: key = TEXT: what".
  [[noreturn]] void fail_value(const toml::node* n, const std::string& key,
                               const std::string& what) const {
    throw InvalidInput(fmt::format("{} = {}: {}", origin(n, key), text_of(n), what));
  }

  void check_keys(const toml::table& t, const std::string& where,
                  const std::set<std::string>& allowed) const {
    for (const auto& [k, v] : t) {
      const std::string key(k.str());
      if (!allowed.count(key)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        const std::string full = where.empty() ? key : where + "." + key;
        // The key's own position is the best line to report.
        const auto line = k.source().begin.line > 0 ? k.source().begin.line : v.source().begin.line;
        throw InvalidInput(fmt::format("{}:{}: {}: unknown key (allowed in [{}]: {})", source_,
                                       line, full, where.empty() ? "top level" : where, list));
      }
    }
  }

  const toml::table& table(const toml::table& parent, const std::string& key,
                           const std::string& where) const {
    const auto* n = parent.get(key);
    const std::string full = where.empty() ? key : where + "." + key;
    if (!n) fail(&parent, full, "missing (required table)");
    const auto* t = n->as_table();
    if (!t) fail(n, full, "must be a table");
    return *t;
  }

  // What to write instead of a string for a dimensionless key: the number it starts
  // with, if any, without quotes and without the unit.
  static std::string dimensionless_advice(const std::string& name, const std::string& text) {
    const auto first = text.find_first_not_of(" \t");
    const char* begin = text.data() + (first == std::string::npos ? text.size() : first);
    const char* end = text.data() + text.size();
    double x = 0.0;
    const auto [ptr, ec] = std::from_chars(begin, end, x);
    if (ec != std::errc() || !std::isfinite(x)) {
      return fmt::format(
          "{} is dimensionless: write a bare number without quotes or unit, e.g. {} = 0.3", name,
          name);
    }
    const std::string rest(ptr, end);
    if (rest.find_first_not_of(" \t") == std::string::npos) {
      return fmt::format("a dimensionless value is a bare number, not a string: write {} = {}",
                         name, std::string(begin, ptr));
    }
    return fmt::format(
        "{} is dimensionless and takes no unit: write {} = {} (no quotes, no \"{}\")", name, name,
        std::string(begin, ptr), rest.substr(rest.find_first_not_of(" \t")));
  }

  // A quantity: a string with units, or a bare number for dimensionless ones.
  double quantity(const toml::node& n, core::Dimension d, const std::string& key) const {
    if (const auto s = n.value<std::string>(); s && d == dim::dimensionless) {
      // One spelling for dimensionless values: a bare number (nu = 0.24), without a unit.
      fail_value(&n, key, dimensionless_advice(key.substr(key.rfind('.') + 1), *s));
    }
    try {
      if (n.is_floating_point() || n.is_integer()) {
        const double x = *n.value<double>();
        if (d == dim::dimensionless) return x;
        return core::parse_quantity(fmt::format("{}", x), d, key);  // names the missing unit
      }
      if (const auto s = n.value<std::string>()) return core::parse_quantity(*s, d, key);
    } catch (const InvalidInput& e) {
      // parse_quantity's message names the key already.
      const std::string msg = e.what();
      if (msg.starts_with(key))
        throw InvalidInput(fmt::format("{}:{}: {}", source_, n.source().begin.line, msg));
      fail(&n, key, msg);
    }
    fail(&n, key,
         d == dim::dimensionless ? "must be a number"
                                 : fmt::format("must be a quantity string with units of {}, e.g. "
                                               "\"{}\"",
                                               core::dimension_name(d), example(d)));
  }

  std::optional<double> optional_quantity(const toml::table& t, const std::string& key,
                                          core::Dimension d, const std::string& where) const {
    const auto* n = t.get(key);
    if (!n) return std::nullopt;
    return quantity(*n, d, where + "." + key);
  }

  double required(const toml::table& t, const std::string& key, core::Dimension d,
                  const std::string& where) const {
    const auto v = optional_quantity(t, key, d, where);
    if (!v) fail(&t, where + "." + key, "missing");
    return *v;
  }

  double positive(const toml::table& t, const std::string& key, core::Dimension d,
                  const std::string& where) const {
    const double v = required(t, key, d, where);
    if (!(v > 0.0) || !std::isfinite(v)) fail_value(t.get(key), where + "." + key, "must be > 0");
    return v;
  }

  std::vector<double> quantity_list(const toml::node& n, core::Dimension d, const std::string& key,
                                    bool must_be_positive) const {
    const auto* a = n.as_array();
    if (!a) fail(&n, key, "must be an array, e.g. [\"1 um\", \"2 um\"]");
    if (a->empty()) fail(&n, key, "must not be empty");
    std::vector<double> out;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string k = fmt::format("{}[{}]", key, i + 1);
      const double v = quantity(*a->get(i), d, k);
      if (must_be_positive && (!(v > 0.0) || !std::isfinite(v))) {
        fail_value(a->get(i), k, "must be > 0");
      }
      out.push_back(v);
    }
    return out;
  }

  std::string string(const toml::table& t, const std::string& key, const std::string& where,
                     const std::string& dflt) const {
    const auto* n = t.get(key);
    if (!n) return dflt;
    if (const auto s = n->value<std::string>()) return *s;
    fail(n, where + "." + key, "must be a string");
  }

  [[nodiscard]] std::string resolve(const std::string& p) const {
    const std::filesystem::path path(p);
    return path.is_absolute() ? p
                              : (std::filesystem::path(base_) / path).lexically_normal().string();
  }

  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  static const char* example(core::Dimension d) {
    if (d == dim::length) return "2.9 mm";
    if (d == dim::area) return "170 mm^2";
    if (d == dim::pressure) return "200 GPa";
    if (d == dim::force) return "526 N";
    if (d == dim::energy) return "0.305 N*m";
    if (d == dim::stiffness) return "38 N/um";
    if (d == dim::inverse_area) return "3.34e-4 um^-2";
    return "1";
  }
  std::string source_;
  std::string base_;
};

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
  return m;
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

void parse_interface(const Reader& r, const toml::node& node, JointCase& c) {
  const auto* t = node.as_table();
  if (!t) r.fail(&node, "interface", "must be a table");
  r.check_keys(
      *t, "interface",
      {"pressure", "size", "patches", "map", "scale_to_preload", "bolts", "halves", "tangential"});
  auto& s = c.interface;
  s.origin = r.origin(&node, "interface");
  const std::string kind = r.string(*t, "pressure", "interface", "uniform");
  if (kind == "uniform") {
    s.pressure = PressureKind::uniform;
  } else if (kind == "map") {
    s.pressure = PressureKind::map;
  } else if (kind == "bolted") {
    s.pressure = PressureKind::bolted;
  } else {
    r.fail_value(t->get("pressure"), "interface.pressure",
                 "use \"uniform\" (the default), \"map\" (with map = \"FILE.csv\") or "
                 "\"bolted\" (with [interface.bolts])");
  }
  if (const auto* n = t->get("size")) {
    const auto v = r.quantity_list(*n, dim::length, "interface.size", true);
    if (v.size() != 2)
      r.fail(n, "interface.size", "give two lengths [Lx, Ly], e.g. [\"17 mm\", \"10 mm\"]");
    s.outline = std::array<double, 2>{v[0], v[1]};
  }
  if (const auto* n = t->get("patches")) {
    const auto* a = n->as_array();
    if (!a || a->size() != 2)
      r.fail(n, "interface.patches", "give two whole numbers [nx, ny], e.g. [8, 5]");
    for (std::size_t i = 0; i < 2; ++i) {
      const toml::node* e = a->get(i);
      const auto v = e ? e->value<int64_t>() : std::nullopt;
      if (!e || !e->is_integer() || !v || *v < 1 || *v > 1000)
        r.fail_value(e, fmt::format("interface.patches[{}]", i + 1),
                     "must be a whole number in [1, 1000]");
      s.patches[i] = static_cast<int>(*v);
    }
  }
  const auto* mapn = t->get("map");
  if (s.pressure == PressureKind::map) {
    if (!mapn)
      r.fail(&node, "interface.map", "missing: pressure = \"map\" needs map = \"FILE.csv\"");
    const auto f = mapn->value<std::string>();
    if (!f) r.fail(mapn, "interface.map", "must be a file name");
    s.map.file = r.resolve(*f);
    try {
      const auto table = core::read_csv_table(s.map.file);
      const auto col = [&](const char* name, core::Dimension d) {
        const auto* cl = table.find(name);
        if (!cl) {
          throw InvalidInput(
              fmt::format("{}: no column {} (the map needs columns x, y, p with units, e.g. "
                          "x[mm],y[mm],p[MPa])",
                          s.map.file, name));
        }
        return table.si_values(*cl, d);
      };
      s.map.x = col("x", dim::length);
      s.map.y = col("y", dim::length);
      s.map.p = col("p", dim::pressure);
      s.map.build_index();
    } catch (const InvalidInput& e) {
      r.fail(mapn, "interface.map", e.what());
    }
    if (const auto* sn = t->get("scale_to_preload")) {
      const auto b = sn->value<bool>();
      if (!b || !sn->is_boolean())
        r.fail(sn, "interface.scale_to_preload", "must be true or false");
      s.map.scale_to_preload = *b;
    }
  } else {
    if (mapn) r.fail(mapn, "interface.map", "is used only with pressure = \"map\"");
    if (t->get("scale_to_preload"))
      r.fail(t->get("scale_to_preload"), "interface.scale_to_preload",
             "is used only with pressure = \"map\"");
  }
  {
    // The tangential law at the asperity scale: Cattaneo-Mindlin only (see docs/joints.md
    // for why the Odfalk-Vingsbo law of Eq. 3.10 is refused).
    const std::string law = r.string(*t, "tangential", "interface", "mindlin");
    if (law == "odfalk_vingsbo") {
      r.fail_value(t->get("tangential"), "interface.tangential",
                   "the Odfalk-Vingsbo elastic-plastic law (Eq. 3.10) needs the fretting yield "
                   "point Q_ty and the hardening coefficient k_p, which the thesis says are "
                   "obtained experimentally (section 3.3); asperity has no physics-based value for "
                   "them and does not fit any: use \"mindlin\"");
    } else if (law != "mindlin") {
      r.fail_value(t->get("tangential"), "interface.tangential",
                   "use \"mindlin\" (Cattaneo-Mindlin partial slip, the default)");
    }
  }
  if (const auto* hn = t->get("halves")) {
    const auto* h = hn->as_table();
    if (!h) r.fail(hn, "interface.halves", "must be a table { length, thickness, width }");
    const std::string w = "interface.halves";
    r.check_keys(*h, w, {"length", "thickness", "width"});
    HalvesGeometry g;
    for (const char* key : {"length", "thickness"}) {
      const auto* n = h->get(key);
      if (!n) r.fail(hn, w + "." + key, "missing: give two lengths [half 1, half 2]");
      const auto v = r.quantity_list(*n, dim::length, w + "." + key, true);
      if (v.size() != 2) r.fail(n, w + "." + key, "give two lengths [half 1, half 2]");
      (std::string(key) == "length" ? g.length : g.thickness) = {v[0], v[1]};
    }
    g.width = r.positive(*h, "width", dim::length, w);
    s.halves = g;
  }
  const auto* bn = t->get("bolts");
  if (s.pressure == PressureKind::bolted) {
    if (!bn) {
      r.fail(&node, "interface.bolts",
             "missing: pressure = \"bolted\" needs [interface.bolts] with positions, "
             "head_diameter, hole_diameter, thickness");
    }
    const auto* b = bn->as_table();
    if (!b) r.fail(bn, "interface.bolts", "must be a table");
    const std::string w = "interface.bolts";
    r.check_keys(*b, w,
                 {"positions", "head_diameter", "hole_diameter", "thickness", "cone_half_angle"});
    const auto* pn = b->get("positions");
    if (!pn || !pn->as_array() || pn->as_array()->empty())
      r.fail(pn ? pn : bn, w + ".positions",
             "give the bolt axes, e.g. [[\"4.25 mm\", \"5 mm\"], [\"12.75 mm\", \"5 mm\"]]");
    for (std::size_t i = 0; i < pn->as_array()->size(); ++i) {
      const auto* e = pn->as_array()->get(i);
      if (!e) r.fail(pn, w + ".positions", "give [x, y] per bolt");
      const auto v =
          r.quantity_list(*e, dim::length, fmt::format("{}.positions[{}]", w, i + 1), false);
      if (v.size() != 2) r.fail(e, fmt::format("{}.positions[{}]", w, i + 1), "give [x, y]");
      s.bolts.positions.push_back({v[0], v[1]});
    }
    s.bolts.head_diameter = r.positive(*b, "head_diameter", dim::length, w);
    s.bolts.hole_diameter = r.positive(*b, "hole_diameter", dim::length, w);
    const auto* tn = b->get("thickness");
    if (!tn)
      r.fail(bn, w + ".thickness",
             "missing: the two halves' thicknesses [t1 (under the head), t2]");
    const auto th = r.quantity_list(*tn, dim::length, w + ".thickness", true);
    if (th.size() != 2) r.fail(tn, w + ".thickness", "give two thicknesses [t1, t2]");
    s.bolts.thickness = {th[0], th[1]};
    if (const auto a = r.optional_quantity(*b, "cone_half_angle", dim::dimensionless, w)) {
      if (!(*a > 0.0 && *a < 90.0))
        r.fail_value(b->get("cone_half_angle"), w + ".cone_half_angle",
                     "must be in (0, 90) degrees");
      s.bolts.cone_half_angle_deg = *a;
    }
  } else if (bn) {
    r.fail(bn, "interface.bolts", "is used only with pressure = \"bolted\"");
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
  if (const auto* p = root.get("profiles")) {
    const auto* t = p->as_table();
    if (!t) r.fail(p, "profiles", "must be a table");
    r.check_keys(*t, "profiles", {"lc", "ls", "end", "truncation", "rule", "level", "dx"});
    try {
      if (const auto* n = t->get("lc")) {
        const auto s = n->value<std::string>();
        c.profile_settings.filter.lc =
            (s && *s == "none") ? 0.0 : r.quantity(*n, dim::length, "profiles.lc");
      }
      if (const auto* n = t->get("ls")) {
        const auto s = n->value<std::string>();
        c.profile_settings.filter.ls =
            (s && *s == "none") ? 0.0 : r.quantity(*n, dim::length, "profiles.ls");
      }
      if (t->get("end")) {
        c.profile_settings.filter.end =
            surface::parse_end_effects(r.string(*t, "end", "profiles", ""), "profiles.end");
      }
      if (const auto* n = t->get("dx")) {
        const double dx = r.quantity(*n, dim::length, "profiles.dx");
        if (!(dx > 0.0) || !std::isfinite(dx)) r.fail_value(n, "profiles.dx", "must be > 0");
        c.profile_settings.dx = dx;
      }
      if (const auto* n = t->get("truncation")) {
        c.profile_settings.filter.truncation =
            r.quantity(*n, dim::dimensionless, "profiles.truncation");
      }
      c.profile_settings.filter.validate();
      if (t->get("rule")) {
        c.profile_settings.rule =
            surface::parse_isotropic_rule(r.string(*t, "rule", "profiles", ""), "profiles.rule");
      }
      if (t->get("level")) {
        c.profile_settings.level =
            surface::parse_levelling(r.string(*t, "level", "profiles", ""), "profiles.level");
      }
    } catch (const InvalidInput& e) {
      if (std::string_view(e.what()).starts_with(source)) throw;
      r.fail(p, "profiles", e.what());
    }
  }

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
    r.check_keys(h, w, {"name", "material", "roughness", "profiles"});
    const auto* mat = h.get("material");
    if (!mat) r.fail(&h, w + ".material", "missing");
    c.halves[i].material = parse_material(r, *mat, w + ".material");
    c.halves[i].roughness = parse_roughness(r, h, w, c.profile_settings);
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
    if (!(bolts.nut_factor > 0.0))
      r.fail_value(b->get("nut_factor"), "load.bolts.nut_factor",
                   "must be > 0 (0.2 for steel bolts, Eq. 5.2)");
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
