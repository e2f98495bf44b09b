// The [interface] table of a joint case file (asperity/joint/interface.hpp): the pressure
// field (uniform, a map, or the bolts' pressure cones of [interface.bolts]), the outline
// and its patches, the halves' geometry and the tangential law.
#include <fmt/format.h>

#include <toml++/toml.h>
#include <array>
#include <cstdint>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/units.hpp"
#include "case_parse.hpp"

namespace asperity::joint::detail {

void parse_interface(const Reader& r, const toml::node& node, JointCase& c) {
  const auto* t = node.as_table();
  if (!t) r.fail(&node, "interface", "must be a table");
  r.check_keys(*t, "interface",
               {"pressure", "size", "patches", "map", "scale_to_preload", "bolts", "halves",
                "tangential", "fretting_yield_point", "hardening_coefficient"});
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
    // The tangential law: Cattaneo-Mindlin (Masing on the rough flat's backbone), or, opt-in,
    // the Odfalk-Vingsbo parallelogram of plastic slip in series with it (Eq. 3.10), whose
    // two parameters only a measurement gives (docs/joints.md).
    const std::string law = r.string(*t, "tangential", "interface", "mindlin");
    const auto* qn = t->get("fretting_yield_point");
    const auto* kn = t->get("hardening_coefficient");
    if (law == "odfalk_vingsbo") {
      if (!qn || !kn) {
        r.fail(t->get("tangential"),
               !qn ? "interface.fretting_yield_point" : "interface.hardening_coefficient",
               "missing: the Odfalk-Vingsbo law (Eq. 3.10) needs the fretting yield point Q_ty "
               "and the hardening coefficient k_p, which the thesis says are obtained "
               "experimentally and could not be generalized (section 3.3); asperity has no "
               "physics-based value for them and fits none: give both from fretting loops "
               "measured on this joint, e.g. fretting_yield_point = \"20 N\", "
               "hardening_coefficient = \"5 N/um\" (or use tangential = \"mindlin\")");
      }
      s.odfalk_vingsbo = hysteresis::OdfalkVingsboParameters{
          .fretting_yield_point = r.positive(*t, "fretting_yield_point", dim::force, "interface"),
          .hardening_coefficient =
              r.positive(*t, "hardening_coefficient", dim::stiffness, "interface")};
    } else if (law == "mindlin") {
      for (const auto* n : {qn, kn}) {
        if (n) {
          r.fail(n, n == qn ? "interface.fretting_yield_point" : "interface.hardening_coefficient",
                 "is used only with tangential = \"odfalk_vingsbo\"");
        }
      }
    } else {
      r.fail_value(t->get("tangential"), "interface.tangential",
                   "use \"mindlin\" (Cattaneo-Mindlin partial slip, the default) or "
                   "\"odfalk_vingsbo\" (Eq. 3.10, with measured fretting_yield_point and "
                   "hardening_coefficient)");
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

}  // namespace asperity::joint::detail
