#include "asperity/fem/structure.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <numeric>

#include "../core/toml_case.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/units.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/fem/gap_map.hpp"
#include "asperity/fem/mesh_io.hpp"

namespace asperity::fem {
namespace tc = core::toml_case;
namespace {

constexpr core::Dimension density{-3, 1, 0};
constexpr core::Dimension pressure_per_length{-2, 1, -2};

struct Reader {
  std::string path;
  double unit = 1.0;  // geometry numbers -> m

  [[noreturn]] void fail(const std::string& where, const std::string& what,
                         const toml::node* n) const {
    throw InvalidInput(fmt::format("{}: {}: {}{}", path, where, what, n ? tc::at_line(*n) : ""));
  }
  // A quantity as text with units, or a bare number in `bare_unit` (0: text required).
  double quantity(const toml::table& t, const std::string& key, const std::string& where,
                  core::Dimension dim, double bare_unit,
                  std::optional<double> dflt = std::nullopt) const {
    const auto* n = t.get(key);
    if (!n) {
      if (dflt) return *dflt;
      fail(where, fmt::format("`{}` is missing", key), nullptr);
    }
    if (const auto s = n->value<std::string>()) {
      try {
        return core::parse_quantity(*s, dim, key);
      } catch (const InvalidInput& e) {
        fail(where, e.what(), n);
      }
    }
    if (bare_unit > 0 && (n->is_floating_point() || n->is_integer())) {
      const double v = *n->value<double>();
      if (!std::isfinite(v)) fail(where, fmt::format("`{}` must be finite", key), n);
      return v * bare_unit;
    }
    fail(where,
         fmt::format("`{}` must be {}", key,
                     bare_unit > 0 ? "a number (geometry unit) or a quantity with units"
                                   : "a quantity with units, e.g. \"200 GPa\""),
         n);
  }
  Eigen::Vector3d point(const toml::table& t, const std::string& key,
                        const std::string& where) const {
    const auto* n = t.get(key);
    const auto* a = n ? n->as_array() : nullptr;
    if (!a || a->size() != 3)
      fail(where, fmt::format("`{}` must be an array of 3 numbers", key), n);
    Eigen::Vector3d p;
    for (std::size_t i = 0; i < 3; ++i) {
      const auto v = (*a)[i].value<double>();
      if (!v || !std::isfinite(*v))
        fail(where, fmt::format("`{}` must be an array of 3 finite numbers", key), n);
      p[static_cast<Eigen::Index>(i)] = *v * unit;
    }
    return p;
  }
  std::string text(const toml::table& t, const std::string& key, const std::string& where,
                   std::optional<std::string> dflt = std::nullopt) const {
    const auto* n = t.get(key);
    if (!n) {
      if (dflt) return *dflt;
      fail(where, fmt::format("`{}` is missing", key), nullptr);
    }
    const auto s = n->value<std::string>();
    if (!s) fail(where, fmt::format("`{}` must be a string", key), n);
    return *s;
  }
  int integer(const toml::table& t, const std::string& key, const std::string& where,
              int dflt) const {
    const auto* n = t.get(key);
    if (!n) return dflt;
    const auto v = n->value<std::int64_t>();
    if (!n->is_integer() || !v || *v < -1000000 || *v > 1000000)
      fail(where, fmt::format("`{}` must be an integer", key), n);
    return static_cast<int>(*v);
  }
  const toml::array* tables(const toml::table& t, const std::string& key) const {
    const auto* n = t.get(key);
    if (!n) return nullptr;
    const auto* a = n->as_array();
    if (!a || !a->is_array_of_tables())
      fail("top level", fmt::format("`{}` must be an array of tables ([[{}]])", key, key), n);
    return a;
  }
  Primitive primitive(const toml::table& t, const std::string& where) const {
    tc::check_keys(t, where, {"box", "cylinder", "prism"});
    if (t.size() != 1) fail(where, "give exactly one of box, cylinder, prism", nullptr);
    if (const auto* b = tc::subtable(t, "box", where)) {
      tc::check_keys(*b, where + ".box", {"corner", "size"});
      return Box{point(*b, "corner", where + ".box"), point(*b, "size", where + ".box")};
    }
    if (const auto* c = tc::subtable(t, "cylinder", where)) {
      tc::check_keys(*c, where + ".cylinder", {"base", "axis", "radius"});
      return Cylinder{point(*c, "base", where + ".cylinder"),
                      point(*c, "axis", where + ".cylinder"),
                      quantity(*c, "radius", where + ".cylinder", core::dim::length, unit)};
    }
    const auto* p = tc::subtable(t, "prism", where);
    tc::check_keys(*p, where + ".prism", {"polygon", "extrusion"});
    const auto* poly = p->get("polygon") ? p->get("polygon")->as_array() : nullptr;
    if (!poly)
      fail(where + ".prism", "`polygon` must be an array of points [[x, y, z], ...]",
           p->get("polygon"));
    Prism prism;
    for (std::size_t i = 0; i < poly->size(); ++i) {
      toml::table holder;
      holder.insert("p", *(*poly)[i].as_array());
      if (!(*poly)[i].as_array()) fail(where + ".prism", "`polygon` must hold points [x, y, z]", p);
      prism.polygon.push_back(
          point(holder, "p", fmt::format("{}.prism.polygon[{}]", where, i + 1)));
    }
    prism.extrusion = point(*p, "extrusion", where + ".prism");
    return prism;
  }
};

// The steps of a run: announced to options.progress, timed (wall) with the peak memory after.
class StepLog {
 public:
  StepLog(std::vector<StepCost>& costs, const StructureOptions& options)
      : costs_(costs), options_(options) {}
  void starting(const std::string& what) const {
    if (options_.progress) options_.progress(what);
  }
  void done(const char* name) {
    const auto now = std::chrono::steady_clock::now();
    costs_.push_back(
        {name, std::chrono::duration<double>(now - clock_).count(), peak_resident_memory_mib()});
    clock_ = now;
  }

 private:
  std::vector<StepCost>& costs_;
  const StructureOptions& options_;
  std::chrono::steady_clock::time_point clock_ = std::chrono::steady_clock::now();
};

}  // namespace

double peak_resident_memory_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

StructureCase read_structure_case(const std::string& path) {
  const auto file = core::read_case_file_text(path);
  const toml::table doc = tc::parse(file.text, path);
  Reader r{path};
  StructureCase c;
  c.path = path;
  tc::check_keys(doc, "",
                 {"name", "geometry", "mesh", "material", "body", "interface", "bolt", "output",
                  "reduction", "rough_contact", "fretting"});
  c.name = r.text(doc, "name", "top level", std::filesystem::path(path).stem().string());
  const auto* geo = tc::subtable(doc, "geometry", "top level");
  const auto* mesh = tc::subtable(doc, "mesh", "top level");
  if (geo) {
    tc::check_keys(*geo, "[geometry]", {"unit", "size", "interface_size", "hole_size"});
    r.unit = core::parse_quantity("1 " + r.text(*geo, "unit", "[geometry]", "m"), core::dim::length,
                                  "unit");
    c.geometry.size.global = r.quantity(*geo, "size", "[geometry]", core::dim::length, r.unit);
    c.geometry.size.interface = r.quantity(*geo, "interface_size", "[geometry]", core::dim::length,
                                           r.unit, c.geometry.size.global);
    c.geometry.size.hole = r.quantity(*geo, "hole_size", "[geometry]", core::dim::length, r.unit,
                                      c.geometry.size.interface);
  }
  if (mesh) {
    tc::check_keys(*mesh, "[mesh]", {"file", "unit"});
    c.mesh_file = (std::filesystem::path(file.base_dir) / r.text(*mesh, "file", "[mesh]")).string();
    r.unit = core::parse_quantity("1 " + r.text(*mesh, "unit", "[mesh]", "m"), core::dim::length,
                                  "unit");
    c.mesh_unit = r.unit;
  }
  if (!geo == !mesh)
    r.fail("top level",
           "give either [geometry] (with [[body]] add/cut, meshed by gmsh) or [mesh] file",
           nullptr);

  std::map<std::string, IsotropicMaterial> materials;
  std::map<std::string, std::pair<double, double>> bolt_material;  // E, nu (and rho below)
  std::map<std::string, double> material_rho;
  if (const auto* mats = r.tables(doc, "material"))
    for (std::size_t i = 0; i < mats->size(); ++i) {
      const auto& m = *(*mats)[i].as_table();
      const std::string where = fmt::format("[[material]] {}", i + 1);
      tc::check_keys(m, where, {"name", "E", "nu", "rho"});
      IsotropicMaterial mat{r.quantity(m, "E", where, core::dim::pressure, 0),
                            tc::number(m, "nu", where, 0.3),
                            r.quantity(m, "rho", where, density, 0)};
      const auto name = r.text(m, "name", where);
      try {
        mat.validate();
      } catch (const InvalidInput& e) {
        r.fail(where + " \"" + name + "\"", e.what(), &m);
      }
      materials[name] = mat;
    }
  auto material = [&](const std::string& name, const std::string& where, const toml::node* n) {
    const auto it = materials.find(name);
    if (it == materials.end()) r.fail(where, fmt::format("no [[material]] named \"{}\"", name), n);
    return it->second;
  };
  const auto* bodies = r.tables(doc, "body");
  if (!bodies || bodies->empty()) r.fail("top level", "no [[body]]", nullptr);
  for (std::size_t i = 0; i < bodies->size(); ++i) {
    const auto& b = *(*bodies)[i].as_table();
    const std::string where = fmt::format("[[body]] {}", i + 1);
    tc::check_keys(b, where,
                   geo ? std::set<std::string>{"name", "material", "add", "cut"}
                       : std::set<std::string>{"name", "material"});
    Body body;
    body.name = r.text(b, "name", where);
    c.body_names.push_back(body.name);
    c.body_materials.push_back(material(r.text(b, "material", where), where, b.get("material")));
    if (geo) {
      for (const char* key : {"add", "cut"}) {
        const auto* list = b.get(key) ? b.get(key)->as_array() : nullptr;
        if (!list) {
          if (std::string(key) == "add")
            r.fail(where, "`add` must list the body's solids", nullptr);
          continue;
        }
        for (std::size_t k = 0; k < list->size(); ++k) {
          const auto* pt = (*list)[k].as_table();
          const std::string w = fmt::format("{} \"{}\" {}[{}]", where, body.name, key, k + 1);
          if (!pt)
            r.fail(w, "must be a table {box = {...}} or {cylinder = ...} or {prism = ...}", list);
          (std::string(key) == "add" ? body.add : body.cut).push_back(r.primitive(*pt, w));
        }
      }
      c.geometry.bodies.push_back(std::move(body));
    }
  }
  if (const auto* itfs = r.tables(doc, "interface"))
    for (std::size_t i = 0; i < itfs->size(); ++i) {
      const auto& t = *(*itfs)[i].as_table();
      const std::string where = fmt::format("[[interface]] {}", i + 1);
      tc::check_keys(
          t, where,
          {"name", "bodies", "normal", "patches", "normal_stiffness", "tangential_stiffness"});
      StructureInterface si;
      si.spec.name = r.text(t, "name", where, fmt::format("interface_{}", i + 1));
      const auto* bl = t.get("bodies") ? t.get("bodies")->as_array() : nullptr;
      if (!bl || bl->size() != 2 || !(*bl)[0].value<std::string>() ||
          !(*bl)[1].value<std::string>())
        r.fail(where, "`bodies` must name two bodies, [\"A\", \"B\"]", t.get("bodies"));
      si.spec.body_a = *(*bl)[0].value<std::string>();
      si.spec.body_b = *(*bl)[1].value<std::string>();
      if (t.get("normal")) {
        const double keep = r.unit;
        r.unit = 1.0;
        si.spec.normal = r.point(t, "normal", where);
        r.unit = keep;
      }
      si.spec.patches = r.integer(t, "patches", where, 0);
      si.normal_stiffness = r.quantity(t, "normal_stiffness", where, pressure_per_length, 0);
      si.tangential_stiffness =
          r.quantity(t, "tangential_stiffness", where, pressure_per_length, 0, si.normal_stiffness);
      for (const auto& [key, v] : {std::pair{"normal_stiffness", si.normal_stiffness},
                                   std::pair{"tangential_stiffness", si.tangential_stiffness}})
        if (!(v > 0))
          r.fail(where, fmt::format("`{}` = {} Pa/m: give a value > 0", key, v), t.get(key));
      try {
        si.spec.validate();
      } catch (const InvalidInput& e) {
        r.fail(where, e.what(), &t);
      }
      c.interfaces.push_back(si);
    }
  if (const auto* rc = tc::subtable(doc, "rough_contact", "top level")) {
    const std::string where = "[rough_contact]";
    tc::check_keys(
        *rc, where,
        {"hardness", "sigma", "sigma_summits", "R", "eta", "surface_data", "asperity_model",
         "gap_map", "gap_variable", "gap_origin", "summit_distribution", "summit_heights"});
    RoughContactCase& rough = c.rough;
    rough.given = true;
    rough.hardness = r.quantity(*rc, "hardness", where, core::dim::pressure, 0);
    if (rc->get("surface_data") && rc->get("summit_heights"))
      r.fail(where,
             "give `surface_data` (a measured surface file) or `summit_heights` (a summit-height "
             "table), not both",
             rc->get("summit_heights"));
    // Which distribution a measured table is summed as (default: the table itself).
    const auto table_or_gaussian = [&] {
      const std::string shape = r.text(*rc, "summit_distribution", where, "table");
      if (shape == "gaussian") {
        rough.heights = nullptr;
      } else if (shape != "table") {
        r.fail(where,
               fmt::format("`summit_distribution` = \"{}\": allowed are \"table\" (the measured "
                           "density, the default) and \"gaussian\" (a Gaussian of its standard "
                           "deviation)",
                           shape),
               rc->get("summit_distribution"));
      }
      rough.summit_sigma = true;
    };
    if (rc->get("summit_heights")) {
      // A summit-height table (`asperity roughness --summits` writes one): columns height
      // (a length unit) and density (or count: any positive factor). Its standard deviation
      // is the length scale; R and eta are given.
      for (const char* key : {"sigma", "sigma_summits"})
        if (rc->get(key))
          r.fail(where,
                 fmt::format("give `{}` or `summit_heights` (whose standard deviation is the "
                             "summits' sigma), not both",
                             key),
                 rc->get(key));
      rough.summit_heights_file =
          (std::filesystem::path(file.base_dir) / r.text(*rc, "summit_heights", where)).string();
      try {
        rough.heights = std::make_shared<const surface::SummitHeightTable>(
            surface::read_summit_height_table(rough.summit_heights_file));
      } catch (const InvalidInput& e) {
        r.fail(where, e.what(), rc->get("summit_heights"));
      }
      rough.sigma = rough.heights->standard_deviation();
      table_or_gaussian();
      rough.R = r.quantity(*rc, "R", where, core::dim::length, 0);
      rough.eta = r.quantity(*rc, "eta", where, core::dim::inverse_area, 0);
    } else if (rc->get("surface_data")) {
      // A measured surface (the published BRB layout): Re [m], area_density [1/m^2] and the
      // summit-height density pzinterp over normzinterp (fractions of z_max): its standard
      // deviation is sigma_a.
      for (const char* key : {"sigma", "sigma_summits", "R", "eta"})
        if (rc->get(key))
          r.fail(where, fmt::format("give `{}` or `surface_data`, not both", key), rc->get(key));
      rough.surface_data =
          (std::filesystem::path(file.base_dir) / r.text(*rc, "surface_data", where)).string();
      const auto scalar = [&](const char* name) {
        const Eigen::MatrixXd v = read_mat_matrix(rough.surface_data, name);
        if (v.size() != 1 || !(v(0) > 0) || !std::isfinite(v(0)))
          r.fail(where,
                 fmt::format("\"{}\": {} must be one finite value > 0", rough.surface_data, name),
                 rc->get("surface_data"));
        return v(0);
      };
      rough.R = scalar("Re");
      rough.eta = scalar("area_density");
      const double z_max = scalar("z_max");
      const Eigen::MatrixXd z = read_mat_matrix(rough.surface_data, "normzinterp");
      const Eigen::MatrixXd pz = read_mat_matrix(rough.surface_data, "pzinterp");
      if (z.size() != pz.size() || z.size() < 3 || !z.allFinite() || !pz.allFinite() ||
          pz.minCoeff() < 0)
        r.fail(where,
               fmt::format("\"{}\": normzinterp and pzinterp must be equal-length finite tables "
                           "(3 or more points) with a density >= 0",
                           rough.surface_data),
               rc->get("surface_data"));
      double I = 0;  // the density's integral (trapezoidal: it is linear between nodes)
      for (Eigen::Index k = 0; k + 1 < z.size(); ++k) {
        const double h = z(k + 1) - z(k);
        if (!(h > 0))
          r.fail(where, fmt::format("\"{}\": normzinterp must increase", rough.surface_data),
                 rc->get("surface_data"));
        I += 0.5 * h * (pz(k) + pz(k + 1));
      }
      if (!(I > 0) || std::abs(I - 1.0) > 1e-3)
        r.fail(where,
               fmt::format("\"{}\": pzinterp integrates to {} over normzinterp; a probability "
                           "density integrates to 1",
                           rough.surface_data, I),
               rc->get("surface_data"));
      std::vector<double> z_m(static_cast<std::size_t>(z.size())), p(z_m.size());
      for (Eigen::Index k = 0; k < z.size(); ++k) {
        z_m[static_cast<std::size_t>(k)] = z.reshaped()(k) * z_max;
        p[static_cast<std::size_t>(k)] = pz.reshaped()(k);
      }
      try {
        rough.heights = std::make_shared<const surface::SummitHeightTable>(
            z_m, p, fmt::format("pzinterp over normzinterp of \"{}\"", rough.surface_data));
      } catch (const InvalidInput& e) {
        r.fail(where, e.what(), rc->get("surface_data"));
      }
      rough.sigma = rough.heights->standard_deviation();
      table_or_gaussian();
    } else {
      if (rc->get("summit_distribution"))
        r.fail(where,
               "`summit_distribution` needs a measured table: give `surface_data` or "
               "`summit_heights`",
               rc->get("summit_distribution"));
      if (rc->get("sigma") && rc->get("sigma_summits"))
        r.fail(where, "give `sigma` (surface heights) or `sigma_summits`, not both", rc);
      rough.summit_sigma = rc->get("sigma_summits") != nullptr;
      rough.sigma = r.quantity(*rc, rough.summit_sigma ? "sigma_summits" : "sigma", where,
                               core::dim::length, 0);
      rough.R = r.quantity(*rc, "R", where, core::dim::length, 0);
      rough.eta = r.quantity(*rc, "eta", where, core::dim::inverse_area, 0);
    }
    for (const auto& [key, v] :
         {std::pair{"hardness", rough.hardness}, std::pair{"sigma", rough.sigma},
          std::pair{"R", rough.R}, std::pair{"eta", rough.eta}})
      if (!(v > 0)) r.fail(where, fmt::format("`{}` = {}: give a value > 0", key, v), rc->get(key));
    try {
      rough.model = contact::parse_model_name(r.text(*rc, "asperity_model", where, "bke"));
    } catch (const InvalidInput& e) {
      r.fail(where, e.what(), rc->get("asperity_model"));
    }
    if (rc->get("gap_map")) {
      rough.gap_map =
          (std::filesystem::path(file.base_dir) / r.text(*rc, "gap_map", where)).string();
      rough.gap_variable = r.text(*rc, "gap_variable", where, "mesoscale_xygap");
      if (rc->get("gap_origin")) rough.gap_origin = r.point(*rc, "gap_origin", where);
      try {
        rough.gap = read_gap_map(rough.gap_map, rough.gap_variable);
      } catch (const InvalidInput& e) {
        r.fail(where, e.what(), rc->get("gap_map"));
      }
    } else if (rc->get("gap_origin") || rc->get("gap_variable")) {
      r.fail(where, "`gap_origin` and `gap_variable` need a `gap_map`", rc);
    }
  }
  if (const auto* bolts = r.tables(doc, "bolt"))
    for (std::size_t i = 0; i < bolts->size(); ++i) {
      const auto& t = *(*bolts)[i].as_table();
      const std::string where = fmt::format("[[bolt]] {}", i + 1);
      tc::check_keys(t, where,
                     {"name", "head", "nut", "shank_diameter", "hole_diameter", "washer_diameter",
                      "material", "head_mass", "preload"});
      BoltSpec b;
      b.name = r.text(t, "name", where, fmt::format("bolt_{}", i + 1));
      b.head = r.point(t, "head", where);
      b.nut = r.point(t, "nut", where);
      b.shank_diameter = r.quantity(t, "shank_diameter", where, core::dim::length, r.unit);
      b.hole_diameter = r.quantity(t, "hole_diameter", where, core::dim::length, r.unit);
      b.washer_diameter = r.quantity(t, "washer_diameter", where, core::dim::length, r.unit);
      const auto m = material(r.text(t, "material", where), where, t.get("material"));
      b.E = m.E, b.nu = m.nu, b.rho = m.rho;
      b.head_mass = r.quantity(t, "head_mass", where, core::dim::mass, 0, 0.0);
      b.preload = r.quantity(t, "preload", where, core::dim::force, 0);
      try {
        b.validate();
      } catch (const InvalidInput& e) {
        r.fail(where, e.what(), &t);
      }
      c.bolts.push_back(b);
    }
  if (const auto* outs = r.tables(doc, "output"))
    for (std::size_t i = 0; i < outs->size(); ++i) {
      const auto& t = *(*outs)[i].as_table();
      const std::string where = fmt::format("[[output]] {}", i + 1);
      tc::check_keys(t, where, {"name", "point"});
      c.outputs.push_back({r.text(t, "name", where), r.point(t, "point", where)});
    }
  if (const auto* red = tc::subtable(doc, "reduction", "top level")) {
    tc::check_keys(*red, "[reduction]", {"fixed_interface_modes", "modes"});
    c.reduction.fixed_interface_modes = r.integer(*red, "fixed_interface_modes", "[reduction]", 40);
    c.modes = r.integer(*red, "modes", "[reduction]", 10);
    if (c.modes < 1 || c.modes > 1000)
      r.fail("[reduction]", fmt::format("`modes` = {}: give 1 to 1000", c.modes),
             red->get("modes"));
    try {
      c.reduction.validate();
    } catch (const InvalidInput& e) {
      r.fail("[reduction]", e.what(), red);
    }
  }
  if (const auto* fr = tc::subtable(doc, "fretting", "top level")) {
    const std::string where = "[fretting]";
    tc::check_keys(*fr, where,
                   {"held", "driven", "direction", "drive_stiffness", "tip_amplitudes",
                    "total_preloads", "harmonics", "time_points"});
    auto& f = c.fretting;
    f.given = true;
    const auto grip = [&](const char* key) {
      const auto* g = tc::subtable(*fr, key, where);
      if (!g) r.fail(where, fmt::format("`{}` is missing: {{ body, point, normal }}", key), fr);
      const std::string w = fmt::format("[fretting].{}", key);
      tc::check_keys(*g, w, {"body", "point", "normal"});
      Grip out{r.text(*g, "body", w), r.point(*g, "point", w), r.point(*g, "normal", w)};
      return out;
    };
    f.fixture.held = grip("held");
    f.fixture.driven = grip("driven");
    if (fr->get("direction")) f.fixture.direction = r.point(*fr, "direction", where);
    f.fixture.drive_stiffness = r.quantity(*fr, "drive_stiffness", where, core::dim::stiffness, 0);
    try {
      f.fixture.validate();
    } catch (const InvalidInput& e) {
      r.fail(where, e.what(), fr);
    }
    const auto quantities = [&](const char* key, core::Dimension dim, bool required) {
      std::vector<double> v;
      const auto* n = fr->get(key);
      if (!n) {
        if (required) r.fail(where, fmt::format("`{}` is missing", key), fr);
        return v;
      }
      const auto* a = n->as_array();
      if (!a || a->empty() || a->size() > 200)
        r.fail(where, fmt::format("`{}` must be an array of 1 to 200 quantities with units", key),
               n);
      for (std::size_t i = 0; i < a->size(); ++i) {
        const auto t = (*a)[i].value<std::string>();
        if (!t) r.fail(where, fmt::format("`{}`[{}] must be a quantity with units", key, i + 1), n);
        double x = 0.0;
        try {
          x = core::parse_quantity(*t, dim, key);
        } catch (const InvalidInput& e) {
          r.fail(where, e.what(), n);
        }
        if (!(x > 0.0) || (!v.empty() && !(x > v.back())))
          r.fail(
              where,
              fmt::format("`{}`[{}] = \"{}\": give values > 0 in ascending order", key, i + 1, *t),
              n);
        v.push_back(x);
      }
      return v;
    };
    f.tip_amplitudes = quantities("tip_amplitudes", core::dim::length, true);
    if (f.tip_amplitudes.back() >= 1e-3)
      r.fail(where,
             fmt::format("`tip_amplitudes` up to {} m: fretting amplitudes are below 1 mm",
                         core::format_value(f.tip_amplitudes.back())),
             fr->get("tip_amplitudes"));
    f.total_preloads = quantities("total_preloads", core::dim::force, false);
    f.harmonics = r.integer(*fr, "harmonics", where, f.harmonics);
    if (f.harmonics < 1 || f.harmonics > 64)
      r.fail(where, fmt::format("`harmonics` = {}: give 1 to 64", f.harmonics),
             fr->get("harmonics"));
    const int nt = r.integer(*fr, "time_points", where, static_cast<int>(f.time_points));
    if (nt < 2 * f.harmonics + 2 || nt % 2 != 0 || nt > 65536)
      r.fail(where,
             fmt::format("`time_points` = {}: give an even number from 2 harmonics + 2 = {} to "
                         "65536",
                         nt, 2 * f.harmonics + 2),
             fr->get("time_points"));
    f.time_points = static_cast<std::size_t>(nt);
    if (!c.rough.given)
      r.fail(where,
             "the fretting apparatus needs the rough interface: add [rough_contact] (the thesis's "
             "physics is the contact law of every interface element)",
             fr);
  }
  if (geo) {
    try {
      c.geometry.validate();
    } catch (const InvalidInput& e) {
      r.fail("[[body]]", e.what(), nullptr);
    }
  }
  return c;
}

AssembledStructure assemble_structure(const StructureCase& c, const StructureOptions& options) {
  AssembledStructure res;
  StepLog log(res.costs, options);
  const auto starting = [&](const std::string& what) { log.starting(what); };
  const auto step = [&](const char* name) { log.done(name); };
  starting(c.mesh_file.empty() ? "meshing with gmsh" : "reading " + c.mesh_file);
  if (c.mesh_file.empty()) {
    res.mesh = mesh_geometry(c.geometry, options.meshing);
  } else {
    const auto ext = std::filesystem::path(c.mesh_file).extension().string();
    if (ext == ".msh")
      res.mesh = read_gmsh(c.mesh_file);
    else if (ext == ".inp")
      res.mesh = read_abaqus_inp(c.mesh_file);
    else
      throw InvalidInput(fmt::format(
          "{}: [mesh] file \"{}\": give a gmsh .msh or an Abaqus .inp file", c.path, c.mesh_file));
    res.mesh.nodes *= c.mesh_unit;
  }
  step("mesh");
  res.mesh.validate();
  // One material per mesh body, by name.
  std::vector<IsotropicMaterial> per_body;
  for (const auto& b : res.mesh.bodies) {
    const auto it = std::find(c.body_names.begin(), c.body_names.end(), b);
    if (it == c.body_names.end())
      throw InvalidInput(
          fmt::format("{}: the mesh has a body \"{}\" that no [[body]] names", c.path, b));
    per_body.push_back(c.body_materials[static_cast<std::size_t>(it - c.body_names.begin())]);
  }
  res.shared_nodes_split = split_shared_nodes(res.mesh);
  const auto faces = boundary_faces(res.mesh);
  starting(fmt::format("assembling ({} nodes, {} elements)", res.mesh.node_count(),
                       res.mesh.element_count()));
  auto km = assemble(res.mesh, per_body);
  for (const double m : body_masses(res.mesh, per_body)) res.total_mass += m;
  step("assembly");
  const Eigen::Index dofs = 3 * res.mesh.node_count();
  for (const auto& spec : c.bolts) {
    res.bolts.push_back(place_bolt(res.mesh, faces, spec));
    km.K += bolt_stiffness(res.bolts.back(), dofs);
    km.M += bolt_mass(res.bolts.back(), dofs);
    res.bolt_load_total += spec.preload;
  }
  for (const auto& si : c.interfaces)
    res.interfaces.push_back(build_interface(res.mesh, faces, si.spec));
  step("bolts and interfaces");
  res.K = std::move(km.K);
  res.M = std::move(km.M);
  return res;
}

RoughPrestress apply_rough_contact(const StructureCase& c, ReducedModel& m,
                                   const Eigen::VectorXd& gap) {
  if (!c.rough.given || c.interfaces.empty())
    throw InvalidInput(
        fmt::format("{}: the rough interface needs [rough_contact] and an "
                    "[[interface]]",
                    c.path));
  // The first interface's bodies give E*, G* and nu (one rough surface for all).
  const auto material_of = [&](const std::string& body) {
    const auto it = std::find(c.body_names.begin(), c.body_names.end(), body);
    const IsotropicMaterial& mat =
        c.body_materials[static_cast<std::size_t>(it - c.body_names.begin())];
    return contact::Material{.E = mat.E, .nu = mat.nu, .G = 0.0, .H = c.rough.hardness};
  };
  const auto ma = material_of(c.interfaces.front().spec.body_a);
  const auto mb = material_of(c.interfaces.front().spec.body_b);
  const auto flat =
      c.rough.summit_sigma
          ? surface::RoughFlat::from_summit_heights(ma, mb, c.rough.sigma, c.rough.eta, c.rough.R,
                                                    1.0, c.rough.model, {}, c.rough.heights)
          : surface::RoughFlat::from_dimensional(ma, mb, c.rough.sigma, c.rough.eta, c.rough.R, 1.0,
                                                 c.rough.model);
  const RoughSurfaceScales scales{
      .sigma = c.rough.sigma, .pressure_scale = flat.scales()->force, .eta = c.rough.eta};
  RoughPrestress rough = rough_prestress(m, flat, scales, gap);
  const auto& pair = flat.scales()->pair;
  m.rough = RoughInterfaceRecord{.E_star = pair.E_star,
                                 .G_star = pair.G_star,
                                 .H = pair.H,
                                 .nu = pair.nu,
                                 .sigma = c.rough.sigma,
                                 .R = c.rough.R,
                                 .eta = c.rough.eta,
                                 .summit_sigma = c.rough.summit_sigma,
                                 .summit_heights = c.rough.heights,
                                 .model = std::string(contact::to_string(c.rough.model)),
                                 .pressure = rough.pressure,
                                 .in_contact = rough.in_contact};
  return rough;
}

StructureResult run_structure(const StructureCase& c, const StructureOptions& options) {
  StructureResult res;
  AssembledStructure km = assemble_structure(c, options);
  res.mesh = std::move(km.mesh);
  res.shared_nodes_split = km.shared_nodes_split;
  res.interfaces = std::move(km.interfaces);
  res.bolts = std::move(km.bolts);
  res.bolt_load_total = km.bolt_load_total;
  res.total_mass = km.total_mass;
  res.costs = std::move(km.costs);
  StepLog log(res.costs, options);
  const auto starting = [&](const std::string& what) { log.starting(what); };
  const auto step = [&](const char* name) { log.done(name); };
  const Eigen::Index dofs = 3 * res.mesh.node_count();
  starting(fmt::format(
      "reducing ({} DOFs to {} interface DOFs and {} tied modes)", dofs,
      3 * std::accumulate(res.interfaces.begin(), res.interfaces.end(), std::size_t{0},
                          [](std::size_t a, const Interface& i) { return a + i.patches.size(); }),
      c.reduction.fixed_interface_modes));
  std::vector<Eigen::VectorXd> bolt_loads;
  for (const auto& b : res.bolts) bolt_loads.push_back(-Eigen::VectorXd(b.elongation));
  res.reduction =
      craig_bampton(km.K, km.M, res.mesh.nodes, res.interfaces, c.reduction, bolt_loads);
  step("reduction");

  // The reduced model: x = [g (3 per element, local frame); eta].
  auto& m = res.model;
  m.source = "asperity structure " + c.path;
  m.M = res.reduction.M;
  m.K = res.reduction.K;
  const Eigen::Index n = m.M.rows(), ng = res.reduction.interface_dofs;
  m.Q = Eigen::MatrixXd::Zero(ng, n);
  m.Q.leftCols(ng).setIdentity();
  m.T = Eigen::MatrixXd::Zero(n, ng);
  for (const auto& itf : res.interfaces)
    for (const auto& p : itf.patches) {
      const auto e = static_cast<Eigen::Index>(m.elements.size());
      for (int k = 0; k < 3; ++k) m.T(3 * e + k, 3 * e + k) = p.area;
      m.elements.push_back({itf.name, p.area, p.centroid, p.frame});
    }
  const auto nb = static_cast<Eigen::Index>(res.bolts.size());
  m.bolt_load.resize(n, nb);
  m.bolt_elongation.resize(nb, n);
  m.bolt_axial_stiffness.resize(nb);
  m.bolt_preload.resize(nb);
  for (Eigen::Index b = 0; b < nb; ++b) {
    const auto& bolt = res.bolts[static_cast<std::size_t>(b)];
    m.bolt_elongation.row(b) = res.reduction.reduce_row(bolt.elongation);
    m.bolt_load.col(b) = -m.bolt_elongation.row(b).transpose();  // unit tension pulls head to nut
    m.bolt_axial_stiffness[b] = bolt.axial_stiffness;
    m.bolt_preload[b] = bolt.spec.preload;
    m.bolt_names.push_back(bolt.spec.name);
  }
  m.recovery.resize(3 * static_cast<Eigen::Index>(c.outputs.size()), n);
  m.output_points.resize(static_cast<Eigen::Index>(c.outputs.size()), 3);
  for (std::size_t o = 0; o < c.outputs.size(); ++o) {
    Eigen::Index nearest = 0;
    (res.mesh.nodes.colwise() - c.outputs[o].point).colwise().squaredNorm().minCoeff(&nearest);
    const auto row = static_cast<Eigen::Index>(3 * o);
    for (int k = 0; k < 3; ++k) {
      Eigen::SparseVector<double> e(dofs);
      e.insert(3 * nearest + k) = 1.0;
      m.recovery.row(row + k) = res.reduction.reduce_row(e);
    }
    m.output_points.row(static_cast<Eigen::Index>(o)) = res.mesh.nodes.col(nearest).transpose();
    m.output_names.push_back(c.outputs[o].name);
  }
  m.fixed_interface_modes = c.reduction.fixed_interface_modes;
  m.validate();

  starting("prestress and linear modes");
  // Linear analyses at the bolt preload.
  const Eigen::VectorXd open = Eigen::VectorXd::Zero(ng);
  res.analyses.push_back({"open", reduced_linear_modes(m, open, c.modes, "open interface")});
  double kn = 0.0;
  Eigen::VectorXd kn_e = Eigen::VectorXd::Zero(ng), kt_e = Eigen::VectorXd::Zero(ng);
  {
    Eigen::Index e = 0;
    for (std::size_t i = 0; i < res.interfaces.size(); ++i)
      for (std::size_t p = 0; p < res.interfaces[i].patches.size(); ++p, ++e) {
        kn_e[3 * e + 2] = c.interfaces[i].normal_stiffness;
        kt_e[3 * e] = kt_e[3 * e + 1] = c.interfaces[i].tangential_stiffness;
      }
    kn = c.interfaces.empty() ? 0.0 : c.interfaces.front().normal_stiffness;
  }
  if (!c.interfaces.empty()) {
    res.prestress = linear_prestress(m, kn);
    for (Eigen::Index e = 0; e < static_cast<Eigen::Index>(m.elements.size()); ++e)
      if (!res.prestress.in_contact[static_cast<std::size_t>(e)])
        kn_e[3 * e + 2] = kt_e[3 * e] = kt_e[3 * e + 1] = 0;
    res.analyses.push_back(
        {"frictionless", reduced_linear_modes(m, kn_e, c.modes, "frictionless contact")});
    res.analyses.push_back(
        {"stuck", reduced_linear_modes(m, kn_e + kt_e, c.modes, "stuck interface")});
  }
  step("prestress and linear modes");
  if (c.rough.given && !c.interfaces.empty()) {
    starting("rough prestress and linear modes");
    if (c.rough.gap) res.gap = gap_at_elements(*c.rough.gap, m, c.rough.gap_origin);
    res.rough = apply_rough_contact(c, m, res.gap);
    Eigen::VectorXd k = Eigen::VectorXd::Zero(ng);
    for (Eigen::Index e = 0; e < static_cast<Eigen::Index>(m.elements.size()); ++e)
      if (res.rough->in_contact[static_cast<std::size_t>(e)]) {
        k[3 * e] = k[3 * e + 1] = res.rough->tangential_stiffness[e];
        k[3 * e + 2] = res.rough->normal_stiffness[e];
      }
    res.analyses.push_back(
        {"rough", reduced_linear_modes(m, k, c.modes, "rough interface at the prestress")});
    step("rough prestress and linear modes");
  }
  return res;
}

}  // namespace asperity::fem
