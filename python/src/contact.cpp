// contact/: one asperity (thesis ch. 2-3, appendices A-B). Scalar C++ functions of
// interference, load or displacement are vectorized over numpy arrays (vectorize.hpp);
// law and model names are strings: normal laws "hertz", "ceb", "ke", "bke"; friction
// laws and models "cfc", "ceb", "ke", "bke".
#include <fmt/format.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/string_view.h>

#include <asperity/contact/asperity_model.hpp>
#include <asperity/contact/friction_law.hpp>
#include <asperity/contact/material.hpp>
#include <asperity/contact/mindlin.hpp>
#include <asperity/contact/normal_law.hpp>
#include <limits>
#include <string>

#include "bindings.hpp"
#include "vectorize.hpp"

namespace asperity::python {

namespace {

using namespace nb::literals;
using namespace contact;

std::string str(std::string_view s) {
  return std::string(s);
}

void bind_materials(nb::module_& m) {
  nb::class_<Material>(m, "Material",
                       "One body's elastic and plastic properties, SI units.\n\n"
                       "E: Young's modulus [Pa] > 0; nu: Poisson's ratio in [0, 0.5); "
                       "G: shear modulus [Pa], 0 = derive from E and nu as E/(2(1+nu)); "
                       "H: hardness [Pa], 0 = not given (the other body is the softer).")
      .def(
          "__init__",
          [](Material* self, double E, double nu, double G, double H) {
            new (self) Material{.E = E, .nu = nu, .G = G, .H = H};
            self->validate();
          },
          "E"_a, "nu"_a, "G"_a = 0.0, "H"_a = 0.0,
          "Validates on construction: raises InvalidInput naming the field.")
      .def_rw("E", &Material::E, "Young's modulus [Pa]")
      .def_rw("nu", &Material::nu, "Poisson's ratio")
      .def_rw("G", &Material::G, "shear modulus [Pa]; 0 = derive from E and nu")
      .def_rw("H", &Material::H, "hardness [Pa]; 0 = not given")
      .def(
          "validate", [](const Material& mat, const std::string& name) { mat.validate(name); },
          "name"_a = "material",
          "Raises InvalidInput naming `name`.field, its value and the allowed range.")
      .def("shear_modulus", &Material::shear_modulus, "G if given, else E/(2(1+nu)) [Pa].")
      .def("__repr__", [](const Material& mat) {
        return fmt::format("Material(E={:g}, nu={:g}, G={:g}, H={:g})", mat.E, mat.nu, mat.G,
                           mat.H);
      });

  m.def(
      "hardness_factor",
      [](const ArrayLike& nu) {
        return vectorize([](double v) { return hardness_factor(v); }, nu);
      },
      "nu"_a, "Hardness factor K = 0.454 + 0.41 nu (Chang et al., Eq. 3.5).");

  nb::class_<CriticalValues>(m, "CriticalValues",
                             "Critical values at the inception of plastic yield (Eq. 3.5 / B.9).")
      .def_ro("omega_c", &CriticalValues::omega_c, "critical interference [m]")
      .def_ro("a_c", &CriticalValues::a_c, "critical contact radius [m]")
      .def_ro("P_c", &CriticalValues::P_c, "critical normal load [N]")
      .def("__repr__", [](const CriticalValues& c) {
        return fmt::format("CriticalValues(omega_c={:g}, a_c={:g}, P_c={:g})", c.omega_c, c.a_c,
                           c.P_c);
      });

  nb::class_<ContactPair>(
      m, "ContactPair",
      "Combined properties of a sphere-on-flat (or sphere-on-sphere) contact, SI units:\n"
      "E* = 1/((1-nu1^2)/E1 + (1-nu2^2)/E2), G* = 1/((2-nu1)/G1 + (2-nu2)/G2),\n"
      "1/R = 1/R1 + 1/R2; H and nu of the softer material (Eq. 3.5, B.9).")
      .def(
          "__init__",
          [](ContactPair* self, double E_star, double G_star, double R, double H, double nu) {
            new (self) ContactPair{.E_star = E_star, .G_star = G_star, .R = R, .H = H, .nu = nu};
            self->validate();
          },
          nb::kw_only(), "E_star"_a, "G_star"_a, "R"_a, "H"_a, "nu"_a,
          "From already combined values; validates (InvalidInput names the field).")
      .def_static("combine", &ContactPair::combine, "body1"_a, "body2"_a, "R1"_a,
                  "R2"_a = std::numeric_limits<double>::infinity(),
                  "Combines two bodies of radii R1 and R2 [m] (R2 = inf for a flat). The "
                  "softer material is the one with the smaller H; H = 0 means harder.")
      .def_ro("E_star", &ContactPair::E_star, "combined Young's modulus [Pa]")
      .def_ro("G_star", &ContactPair::G_star, "combined shear modulus [Pa]")
      .def_ro("R", &ContactPair::R, "combined radius [m]")
      .def_ro("H", &ContactPair::H, "hardness of the softer material [Pa]")
      .def_ro("nu", &ContactPair::nu, "Poisson's ratio of the softer material")
      .def_prop_ro("K", &ContactPair::K, "hardness factor 0.454 + 0.41 nu")
      .def_prop_ro("critical", &ContactPair::critical,
                   "CriticalValues omega_c, a_c, P_c (Eq. 3.5 / B.9)")
      .def("validate", &ContactPair::validate)
      .def("__repr__", [](const ContactPair& p) {
        return fmt::format("ContactPair(E_star={:g}, G_star={:g}, R={:g}, H={:g}, nu={:g})",
                           p.E_star, p.G_star, p.R, p.H, p.nu);
      });
}

void bind_laws(nb::module_& m) {
  m.attr("normal_laws") = nb::make_tuple("hertz", "ceb", "ke", "bke");
  m.attr("friction_laws") = nb::make_tuple("cfc", "ceb", "ke", "bke");
  m.attr("models") = nb::make_tuple("cfc", "ceb", "ke", "bke");

  nb::class_<BkeConstants>(m, "BkeConstants",
                           "Constants of the Brizmer-Kligerman-Etsion fits (under Eq. 3.5 and "
                           "B.9); valid for nu in about (0.118, 0.5).")
      .def_static("for_poisson", &BkeConstants::for_poisson, "nu"_a,
                  "Raises InvalidInput when l_c <= 0 or delta_c <= 0.")
      .def_ro("l_c", &BkeConstants::l_c, "8.88 nu - 10.13 (nu^2 + 0.089)")
      .def_ro("delta_c", &BkeConstants::delta_c, "6.82 nu - 7.83 (nu^2 + 0.0586)")
      .def_ro("alpha", &BkeConstants::alpha, "0.174 + 0.08 nu")
      .def_ro("gamma", &BkeConstants::gamma, "0.25 + 0.125 nu")
      .def("__repr__", [](const BkeConstants& c) {
        return fmt::format("BkeConstants(l_c={:g}, delta_c={:g}, alpha={:g}, gamma={:g})", c.l_c,
                           c.delta_c, c.alpha, c.gamma);
      });

  m.def(
      "normal_load_star",
      [](const std::string& law, const ArrayLike& w, const ArrayLike& nu) {
        const NormalLaw l = parse_normal_law(law);
        return vectorize([l](double x, double v) { return normal_load_star(l, x, v); }, w, nu);
      },
      "law"_a, "w"_a, "nu"_a,
      "P/P_c at w = omega/omega_c >= 0: Hertz (B.1), CEB (B.2), KE (B.3, with the fourth "
      "branch 3/K w beyond w = 110), BKE (B.4). `law` is 'hertz', 'ceb', 'ke' or 'bke'; w and "
      "nu broadcast.");
  m.def(
      "contact_radius_star",
      [](const std::string& law, const ArrayLike& w, const ArrayLike& nu) {
        const NormalLaw l = parse_normal_law(law);
        return vectorize([l](double x, double v) { return contact_radius_star(l, x, v); }, w, nu);
      },
      "law"_a, "w"_a, "nu"_a, "a/a_c at w = omega/omega_c >= 0 (B.5-B.8).");
  m.def(
      "interference_star",
      [](const std::string& law, const ArrayLike& P_star, const ArrayLike& nu) {
        const NormalLaw l = parse_normal_law(law);
        return vectorize([l](double p, double v) { return interference_star(l, p, v); }, P_star,
                         nu);
      },
      "law"_a, "P_star"_a, "nu"_a,
      "Inverse of normal_load_star: w = omega/omega_c for a load P/P_c >= 0. A load inside "
      "a jump of CEB (w = 1) or KE (w = 1, 6, 110) returns the branch point.");

  nb::class_<FrictionParameters>(m, "FrictionParameters",
                                 "Parameters of the friction laws that are not in the pair.")
      .def(
          "__init__",
          [](FrictionParameters* self, double mu_cfc, double zeta) {
            new (self) FrictionParameters{.mu_cfc = mu_cfc, .zeta = zeta};
            self->validate();
          },
          "mu_cfc"_a = 0.3, "zeta"_a = 0.48,
          "mu_cfc: constant friction coefficient of CFC, s/H (B.10), > 0. zeta: CEB depth of "
          "first yield over contact radius, 0.48 for nu = 0.3 (under B.13).")
      .def_rw("mu_cfc", &FrictionParameters::mu_cfc)
      .def_rw("zeta", &FrictionParameters::zeta)
      .def("validate", &FrictionParameters::validate)
      .def("__repr__", [](const FrictionParameters& p) {
        return fmt::format("FrictionParameters(mu_cfc={:g}, zeta={:g})", p.mu_cfc, p.zeta);
      });

  m.def(
      "cfc_coefficient",
      [](const ArrayLike& s, const ArrayLike& H) {
        return vectorize([](double a, double b) { return cfc_coefficient(a, b); }, s, H);
      },
      "shear_strength"_a, "hardness"_a,
      "CFC friction coefficient mu = s/H of the softer material (B.10, Eq. 3.13).");
  m.def(
      "friction_coefficient",
      [](const std::string& law, const ArrayLike& w, const ArrayLike& nu,
         const FrictionParameters& params) {
        const FrictionLaw l = parse_friction_law(law);
        return vectorize(
            [l, &params](double x, double v) { return friction_coefficient(l, x, v, params); }, w,
            nu);
      },
      "law"_a, "w"_a, "nu"_a, "params"_a = FrictionParameters{},
      "Static friction coefficient at w = omega/omega_c: CFC (B.10), CEB (B.11; 0 for w >= 1), "
      "KE (B.12; 0 beyond w = 6.2), BKE (B.13, mu = 0.26 coth(0.27 (w/delta_c)^0.46)). w > 0 "
      "except for CFC.");
  m.def(
      "static_friction_star",
      [](const std::string& law, const ArrayLike& w, const ArrayLike& nu,
         const ArrayLike& normal_load_star, const FrictionParameters& params) {
        const FrictionLaw l = parse_friction_law(law);
        return vectorize(
            [l, &params](double x, double v, double p) {
              return static_friction_star(l, x, v, p, params);
            },
            w, nu, normal_load_star);
      },
      "law"_a, "w"_a, "nu"_a, "normal_load_star"_a, "params"_a = FrictionParameters{},
      "mu(w) P(w)/P_c: static friction force over P_c, 0 at w = 0 where mu diverges.");

  m.def(
      "normal_law_of",
      [](const std::string& model) {
        return str(to_string(normal_law_of(parse_model_name(model))));
      },
      "model"_a, "Normal law of a model: cfc -> hertz, the others their own.");
  m.def(
      "friction_law_of",
      [](const std::string& model) {
        return str(to_string(friction_law_of(parse_model_name(model))));
      },
      "model"_a, "Friction law of a model (same name).");

  nb::class_<AsperityLaws>(m, "AsperityLaws",
                           "A model's asperity laws in dimensionless form, validated once: "
                           "P/P_c, a/a_c and mu as functions of w = omega/omega_c.")
      .def(
          "__init__",
          [](AsperityLaws* self, const std::string& model, double nu,
             const FrictionParameters& params) {
            new (self) AsperityLaws(parse_model_name(model), nu, params);
          },
          "model"_a, "nu"_a, "params"_a = FrictionParameters{})
      .def_prop_ro("model", [](const AsperityLaws& l) { return str(to_string(l.model())); })
      .def_prop_ro("nu", &AsperityLaws::nu)
      .def_prop_ro("friction_parameters", &AsperityLaws::friction_parameters)
      .def(
          "load_star",
          [](const AsperityLaws& l, const ArrayLike& w) {
            return vectorize([&l](double x) { return l.load_star(x); }, w);
          },
          "w"_a, "P/P_c (B.1-B.4)")
      .def(
          "radius_star",
          [](const AsperityLaws& l, const ArrayLike& w) {
            return vectorize([&l](double x) { return l.radius_star(x); }, w);
          },
          "w"_a, "a/a_c (B.5-B.8)")
      .def(
          "mu",
          [](const AsperityLaws& l, const ArrayLike& w) {
            return vectorize([&l](double x) { return l.mu(x); }, w);
          },
          "w"_a, "friction coefficient (B.10-B.13)")
      .def(
          "interference_star",
          [](const AsperityLaws& l, const ArrayLike& P_star) {
            return vectorize([&l](double p) { return l.interference_star(p); }, P_star);
          },
          "P_star"_a, "inverse of load_star")
      .def(
          "break_points", [](const AsperityLaws& l) { return array_of(l.break_points()); },
          "Interferences w where the laws switch branch (kinks or jumps of P, a or mu): CEB 1; "
          "KE 1, 6, 6.2, 110; BKE delta_c; none for CFC.");
}

void bind_mindlin(nb::module_& m) {
  nb::module_ mm = m.def_submodule(
      "mindlin",
      "Cattaneo-Mindlin / Mindlin-Deresiewicz responses in the tilde variables of Appendix "
      "B.2: Q~ = Q/(mu P), delta~ = 16 G* a delta/(3 mu P). Gross slip starts at delta~ = 1. "
      "Every function is vectorized (arguments broadcast).");
  mm.def(
      "stick_displacement_tilde",
      [](const ArrayLike& Q) {
        return vectorize([](double q) { return mindlin::stick_displacement_tilde(q); }, Q);
      },
      "Q_tilde"_a, "Full stick, B.14: delta~ = 2/3 Q~.");
  mm.def(
      "loading_displacement_tilde",
      [](const ArrayLike& Q) {
        return vectorize([](double q) { return mindlin::loading_displacement_tilde(q); }, Q);
      },
      "Q_tilde"_a, "Partial slip, increasing Q, B.15: delta~ = 1 - (1 - Q~)^(2/3), Q~ in [0, 1].");
  mm.def(
      "loading_force_tilde",
      [](const ArrayLike& d) {
        return vectorize([](double x) { return mindlin::loading_force_tilde(x); }, d);
      },
      "delta_tilde"_a,
      "Inverse of B.15: Q~ = 1 - (1 - delta~)^(3/2) for delta~ in [0, 1), 1 beyond (gross "
      "slip); odd in delta~.");
  mm.def(
      "unloading_displacement_tilde",
      [](const ArrayLike& Q, const ArrayLike& Qm) {
        return vectorize(
            [](double q, double qm) { return mindlin::unloading_displacement_tilde(q, qm); }, Q,
            Qm);
      },
      "Q_tilde"_a, "Q_max_tilde"_a,
      "Unloading from Q~max, B.16: delta~ = 2 (1 - (Q~max - Q~)/2)^(2/3) - (1 - Q~max)^(2/3) - 1.");
  mm.def(
      "reloading_displacement_tilde",
      [](const ArrayLike& Q, const ArrayLike& Qm) {
        return vectorize(
            [](double q, double qm) { return mindlin::reloading_displacement_tilde(q, qm); }, Q,
            Qm);
      },
      "Q_tilde"_a, "Q_max_tilde"_a, "Reloading from -Q~max, B.17.");
  mm.def(
      "unloading_force_tilde",
      [](const ArrayLike& d, const ArrayLike& dm) {
        return vectorize([](double x, double xm) { return mindlin::unloading_force_tilde(x, xm); },
                         d, dm);
      },
      "delta_tilde"_a, "delta_max_tilde"_a,
      "Unloading force from a reversal at delta~max (B.16 solved for Q~; Masing's rule, also "
      "valid in gross slip): Q~ = Q~l(delta~max) - 2 Q~l((delta~max - delta~)/2).");
  mm.def(
      "reloading_force_tilde",
      [](const ArrayLike& d, const ArrayLike& dm) {
        return vectorize([](double x, double xm) { return mindlin::reloading_force_tilde(x, xm); },
                         d, dm);
      },
      "delta_tilde"_a, "delta_max_tilde"_a,
      "Reloading force from a reversal at -delta~max (B.17 solved for Q~).");
  mm.def(
      "energy_tilde",
      [](const ArrayLike& Qm) {
        return vectorize([](double q) { return mindlin::energy_tilde(q); }, Qm);
      },
      "Q_max_tilde"_a,
      "Energy per cycle over 9 (mu P)^2/(10 G* a), B.19: 1 - (1 - Q~)^(5/3) - 5Q~/6 (1 + (1 - "
      "Q~)^(2/3)), Q~max in [0, 1].");
  mm.def(
      "energy_tilde_small_amplitude",
      [](const ArrayLike& Qm) {
        return vectorize([](double q) { return mindlin::energy_tilde_small_amplitude(q); }, Qm);
      },
      "Q_max_tilde"_a, "Small-amplitude form of B.19, B.20: 5 Q~^3/162 (1 + 2 Q~/3).");
  mm.def(
      "energy_tilde_for_displacement",
      [](const ArrayLike& dm) {
        return vectorize([](double x) { return mindlin::energy_tilde_for_displacement(x); }, dm);
      },
      "delta_max_tilde"_a,
      "Energy per cycle (tilde units) for a displacement amplitude: B.19 for delta~max <= 1, "
      "1/6 + 5/6 (delta~max - 1) in gross slip.");
}

void bind_tangential(nb::module_& m) {
  nb::class_<FrettingLoop>(m, "FrettingLoop",
                           "Points of a fretting loop: virgin loading 0 -> delta_max, "
                           "unloading to -delta_max, reloading back to delta_max. Arrays are "
                           "read-only views.")
      .def_prop_ro(
          "delta", [](const FrettingLoop& l) { return view_of(l.delta); },
          nb::rv_policy::reference_internal, "tangential displacement [m]")
      .def_prop_ro(
          "Q", [](const FrettingLoop& l) { return view_of(l.Q); },
          nb::rv_policy::reference_internal, "tangential force [N]")
      .def_prop_ro(
          "branch", [](const FrettingLoop& l) { return view_of(l.branch); },
          nb::rv_policy::reference_internal, "0 loading, 1 unloading, 2 reloading")
      .def("__len__", [](const FrettingLoop& l) { return l.delta.size(); })
      .def("__repr__", [](const FrettingLoop& l) {
        return fmt::format("FrettingLoop({} points)", l.delta.size());
      });

  using MC = MindlinContact;
  nb::class_<MC>(m, "MindlinContact",
                 "Dimensional Cattaneo-Mindlin contact (Eq. 3.6-3.12, B.14-B.20): friction "
                 "coefficient mu, normal load P [N], combined shear modulus G* [Pa], contact "
                 "radius a [m].")
      .def(nb::init<double, double, double, double>(), "mu"_a, "P"_a, "G_star"_a, "a"_a,
           "mu >= 0, P >= 0, G* > 0, a > 0 (a = 0 only with P = 0); raises InvalidInput.")
      .def_prop_ro("mu", &MC::mu)
      .def_prop_ro("P", &MC::P, "[N]")
      .def_prop_ro("Q_max", &MC::Q_max, "static friction force mu P [N]")
      .def_prop_ro("stiffness", &MC::stiffness,
                   "tangential stiffness at Q = 0 and at every reversal, 8 G* a (Eq. 3.11) [N/m]")
      .def_prop_ro("slip_displacement", &MC::slip_displacement,
                   "displacement at the onset of gross slip, 3 mu P/(16 G* a) [m]")
      .def(
          "loading_force",
          [](const MC& c, const ArrayLike& delta) {
            return vectorize([&c](double d) { return c.loading_force(d); }, delta);
          },
          "delta"_a,
          "Virgin loading force for a displacement of either sign (Eq. 3.7 inverted) [N].")
      .def(
          "loading_displacement",
          [](const MC& c, const ArrayLike& Q) {
            return vectorize([&c](double q) { return c.loading_displacement(q); }, Q);
          },
          "Q"_a, "Virgin loading displacement for |Q| <= mu P (Eq. 3.7) [m].")
      .def(
          "unloading_force",
          [](const MC& c, const ArrayLike& delta, const ArrayLike& delta_max) {
            return vectorize([&c](double d, double dm) { return c.unloading_force(d, dm); }, delta,
                             delta_max);
          },
          "delta"_a, "delta_max"_a,
          "Unloading force at delta after a reversal at delta_max > 0 (Eq. 3.8 solved for Q; "
          "gross slip included) [N].")
      .def(
          "reloading_force",
          [](const MC& c, const ArrayLike& delta, const ArrayLike& delta_max) {
            return vectorize([&c](double d, double dm) { return c.reloading_force(d, dm); }, delta,
                             delta_max);
          },
          "delta"_a, "delta_max"_a,
          "Reloading force at delta after a reversal at -delta_max (Eq. 3.9) [N].")
      .def(
          "unloading_displacement",
          [](const MC& c, const ArrayLike& Q, const ArrayLike& Q_max) {
            return vectorize([&c](double q, double qm) { return c.unloading_displacement(q, qm); },
                             Q, Q_max);
          },
          "Q"_a, "Q_max"_a,
          "Unloading displacement after a reversal at Q_max <= mu P (Eq. 3.8, B.16) [m].")
      .def(
          "reloading_displacement",
          [](const MC& c, const ArrayLike& Q, const ArrayLike& Q_max) {
            return vectorize([&c](double q, double qm) { return c.reloading_displacement(q, qm); },
                             Q, Q_max);
          },
          "Q"_a, "Q_max"_a,
          "Reloading displacement after a reversal at -Q_max (Eq. 3.9, B.17) [m].")
      .def(
          "regime_for_displacement",
          [](const MC& c, const ArrayLike& delta_max) -> nb::object {
            // 1 for gross slip, 0 for partial slip, elementwise (with vectorize's checks
            // and broadcasting); then the names.
            const auto gross = vectorize(
                [&c](double d) {
                  return c.regime_for_displacement(d) == SlipRegime::gross_slip ? 1.0 : 0.0;
                },
                delta_max);
            const char* names[] = {"partial_slip", "gross_slip"};
            if (PyFloat_Check(gross.obj.ptr())) {
              return nb::str(names[nb::cast<double>(gross.obj) != 0.0 ? 1 : 0]);
            }
            nb::module_ np = nb::module_::import_("numpy");
            return np.attr("where")(gross.obj, names[1], names[0]);
          },
          "delta_max"_a,
          "'partial_slip' or 'gross_slip' for a displacement amplitude; for an array, a numpy "
          "array of these names of the same shape.")
      .def(
          "energy_per_cycle",
          [](const MC& c, const ArrayLike& delta_max) {
            return vectorize([&c](double d) { return c.energy_per_cycle(d); }, delta_max);
          },
          "delta_max"_a,
          "Energy dissipated per cycle of displacement amplitude delta_max (Eq. 3.12 / B.19; "
          "gross slip adds 4 mu P (delta_max - slip_displacement)) [J].")
      .def(
          "energy_per_cycle_for_force",
          [](const MC& c, const ArrayLike& Q_max) {
            return vectorize([&c](double q) { return c.energy_per_cycle_for_force(q); }, Q_max);
          },
          "Q_max"_a, "Energy per cycle for a force amplitude Q_max <= mu P (Eq. 3.12 / B.19) [J].")
      .def("loop", &MC::loop, "delta_max"_a, "points"_a = 101,
           "Loading, unloading and reloading branches with `points` per branch (>= 2).");
}

void bind_models(nb::module_& m) {
  using PSM = PartialSlipModel;
  nb::class_<PSM>(m, "PartialSlipModel",
                  "A sphere under a constant normal load with one of the four physics-based "
                  "partial slip models of section 3.3 (Fig. 3.5): 'cfc' (Hertz + constant mu), "
                  "'ceb', 'ke', 'bke' (own normal law + own friction law) fed into "
                  "Cattaneo-Mindlin.")
      .def_static(
          "from_load",
          [](const ContactPair& pair, const std::string& model, double P,
             const FrictionParameters& params, const std::string& interference) {
            return PSM::from_load(pair, parse_model_name(model), P, params,
                                  parse_interference_reading(interference));
          },
          "pair"_a, "model"_a, "P"_a, "params"_a = FrictionParameters{}, "interference"_a = "own",
          "From a normal load P [N] > 0, which stays as given. interference='own': the "
          "model's normal law gives omega and a (inside a jump of the CEB or KE load law the "
          "branch point); 'hertz': Hertz's omega and a for every model, the thesis's reading "
          "of Table 3.2.")
      .def_static(
          "from_interference_star",
          [](const ContactPair& pair, const std::string& model, double omega_star,
             const FrictionParameters& params, const std::string& interference) {
            return PSM::from_interference_star(pair, parse_model_name(model), omega_star, params,
                                               parse_interference_reading(interference));
          },
          "pair"_a, "model"_a, "omega_star"_a, "params"_a = FrictionParameters{},
          "interference"_a = "own",
          "From the dimensionless interference omega* = omega/omega_c > 0; P and a from the "
          "model's normal law (interference='own') or from Hertz's ('hertz').")
      .def_prop_ro("model", [](const PSM& p) { return std::string(to_string(p.model())); })
      .def_prop_ro(
          "interference", [](const PSM& p) { return std::string(to_string(p.reading())); },
          "'own' or 'hertz': whose normal law gave omega and a")
      .def_prop_ro("pair", &PSM::pair)
      .def_prop_ro("critical", &PSM::critical)
      .def_prop_ro("omega_star", &PSM::omega_star, "omega/omega_c")
      .def_prop_ro("omega", &PSM::omega, "interference [m]")
      .def_prop_ro("a", &PSM::a, "contact radius [m] (B.5-B.8)")
      .def_prop_ro("P", &PSM::P, "normal load [N]")
      .def_prop_ro("mu", &PSM::mu, "friction coefficient (B.10-B.13)")
      .def_prop_ro("Q_max", &PSM::Q_max, "static friction force mu P [N]")
      .def_prop_ro("K_T", &PSM::K_T, "tangential stiffness 8 G* a (Eq. 3.11) [N/m]")
      .def_prop_ro("contact", &PSM::contact, "the MindlinContact")
      .def_prop_ro("delta_scale", &PSM::delta_scale,
                   "3 P_c/(16 G* a_c) [m]: delta* = delta/delta_scale (section 3.3)")
      .def_prop_ro("energy_scale", &PSM::energy_scale,
                   "P_c^2/(G* a_c) [J]: Delta W* = Delta W/energy_scale (section 3.4)")
      .def(
          "energy_curve",
          [](const PSM& p, const ArrayLike& delta_max) {
            return vectorize([&p](double d) { return p.contact().energy_per_cycle(d); }, delta_max);
          },
          "delta_max"_a,
          "Energy per cycle [J] for each displacement amplitude (any shape; C++ energy_curve).")
      .def(
          "loop",
          [](const PSM& p, double delta_max, std::size_t points) {
            return p.contact().loop(delta_max, points);
          },
          "delta_max"_a, "points"_a = 101, "Shorthand for contact.loop(delta_max, points).")
      .def("__repr__", [](const PSM& p) {
        return fmt::format("PartialSlipModel(model='{}', omega_star={:.4g}, P={:.4g} N, mu={:.4g})",
                           to_string(p.model()), p.omega_star(), p.P(), p.mu());
      });
}

}  // namespace

void bind_contact(nb::module_& m) {
  bind_materials(m);
  bind_laws(m);
  bind_mindlin(m);
  bind_tangential(m);
  bind_models(m);
}

}  // namespace asperity::python
