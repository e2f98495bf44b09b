// surface/rough_flat: the Greenwood-Williamson rough flat of chapter 4.
#include <nanobind/stl/optional.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>

#include <string>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/core/error.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "bindings.hpp"
#include "vectorize.hpp"

namespace asperity::python {

using namespace nb::literals;
using namespace asperity::surface;

namespace {

SlipScaling parse_scaling(const std::string& s) {
  if (s == "elastic") return SlipScaling::elastic;
  if (s == "own_law") return SlipScaling::own_law;
  throw InvalidInput("slip_scaling \"" + s +
                     "\" is unknown: allowed are elastic (Eq. 4.8) and own_law");
}

}  // namespace

void bind_rough_flat(nb::module_& m) {
  nb::class_<RoughFlatScales>(m, "RoughFlatScales", "SI scales of a dimensional rough flat.")
      .def_ro("sigma", &RoughFlatScales::sigma, "rms surface height [m] (length scale)")
      .def_ro("force", &RoughFlatScales::force, "K H A0 [N] (force scale)")
      .def_ro("A0", &RoughFlatScales::A0, "nominal area [m^2]")
      .def_ro("eta", &RoughFlatScales::eta, "asperity density [1/m^2]")
      .def_ro("R", &RoughFlatScales::R, "asperity radius [m]");

  nb::class_<RoughFlatBackbone, hysteresis::Backbone>(
      m, "RoughFlatBackbone",
      "Tabulated virgin loading curve Q*_l(delta*) of a rough flat at one separation, with a "
      "verified error bound (normalized units).")
      .def_prop_ro("d_star", &RoughFlatBackbone::d_star)
      .def_prop_ro("verified_error", &RoughFlatBackbone::verified_error,
                   "largest relative table error found at the interval midpoints")
      .def_prop_ro("intervals", &RoughFlatBackbone::intervals)
      .def_prop_ro("table_end", &RoughFlatBackbone::table_end);

  nb::class_<RoughFlat>(
      m, "RoughFlat",
      "Nominally flat rough contact: the asperity model summed over Gaussian heights "
      "(Eq. 4.1-4.14). Normalized: lengths over sigma_s, forces over K H A0.")
      .def(
          "__init__",
          [](RoughFlat* self, const std::string& model, double beta, double psi, double nu,
             double G_over_E, double mu_cfc, double zeta, const std::string& slip_scaling) {
            new (self) RoughFlat(RoughFlatParameters{.model = contact::parse_model_name(model),
                                                     .beta = beta,
                                                     .psi = psi,
                                                     .nu = nu,
                                                     .G_over_E = G_over_E,
                                                     .friction = {.mu_cfc = mu_cfc, .zeta = zeta},
                                                     .slip_scaling = parse_scaling(slip_scaling)});
          },
          "model"_a, "beta"_a, "psi"_a, "nu"_a, "G_over_E"_a, "mu_cfc"_a = 0.3, "zeta"_a = 0.48,
          "slip_scaling"_a = "elastic")
      .def_static(
          "from_dimensional",
          [](const contact::Material& a, const contact::Material& b, double sigma, double eta,
             double R, double A0, const std::string& model, double mu_cfc, double zeta,
             const std::string& slip_scaling) {
            return RoughFlat::from_dimensional(
                a, b, sigma, eta, R, A0, contact::parse_model_name(model),
                {.mu_cfc = mu_cfc, .zeta = zeta}, parse_scaling(slip_scaling));
          },
          "body1"_a, "body2"_a, "sigma"_a, "eta"_a, "R"_a, "A0"_a, "model"_a, "mu_cfc"_a = 0.3,
          "zeta"_a = 0.48, "slip_scaling"_a = "elastic",
          "From SI inputs: materials, combined roughness sigma [m], eta [1/m^2], R [m], area A0 "
          "[m^2]. psi uses sigma_a (SEED_NOTES.md).")
      .def_prop_ro("beta", [](const RoughFlat& f) { return f.parameters().beta; })
      .def_prop_ro("psi", [](const RoughFlat& f) { return f.parameters().psi; })
      .def_prop_ro("nu", [](const RoughFlat& f) { return f.parameters().nu; })
      .def_prop_ro("G_over_E", [](const RoughFlat& f) { return f.parameters().G_over_E; })
      .def_prop_ro(
          "model",
          [](const RoughFlat& f) { return std::string(contact::to_string(f.parameters().model)); })
      .def_prop_ro("scales", &RoughFlat::scales)
      .def_prop_ro("sigma_a_over_sigma", &RoughFlat::sigma_a_over_sigma)
      .def_prop_ro("omega_c_star", &RoughFlat::omega_c_star)
      .def(
          "normal_load_star",
          [](const RoughFlat& f, const ArrayLike& d) {
            return vectorize([&f](double v) { return f.normal_load_star(v); }, d);
          },
          "d_star"_a, "P* at separation d* (Eq. 4.4).")
      .def(
          "separation_star",
          [](const RoughFlat& f, const ArrayLike& P) {
            return vectorize([&f](double v) { return f.separation_star(v); }, P);
          },
          "P_star"_a, "Separation d* for a load P* (Eq. 4.4 inverted).")
      .def_prop_ro("max_load_star", &RoughFlat::max_load_star)
      .def(
          "static_friction_star",
          [](const RoughFlat& f, const ArrayLike& d) {
            return vectorize([&f](double v) { return f.static_friction_star(v); }, d);
          },
          "d_star"_a, "Q*_max at d* (Eq. 4.7).")
      .def(
          "contact_area_ratio",
          [](const RoughFlat& f, const ArrayLike& d) {
            return vectorize([&f](double v) { return f.contact_area_ratio(v); }, d);
          },
          "d_star"_a, "Real contact area over A0.")
      .def(
          "contact_fraction",
          [](const RoughFlat& f, const ArrayLike& d) {
            return vectorize([&f](double v) { return f.contact_fraction(v); }, d);
          },
          "d_star"_a, "Fraction of asperities in contact.")
      .def(
          "loading_force_star",
          [](const RoughFlat& f, const ArrayLike& x, const ArrayLike& d) {
            return vectorize([&f](double a, double b) { return f.loading_force_star(a, b); }, x, d);
          },
          "delta_star"_a, "d_star"_a, "Virgin loading Q*_l (Eq. 4.9-4.10, erratum) by quadrature.")
      .def(
          "unloading_force_star",
          [](const RoughFlat& f, const ArrayLike& x, const ArrayLike& xm, const ArrayLike& d) {
            return vectorize(
                [&f](double a, double b, double c) { return f.unloading_force_star(a, b, c); }, x,
                xm, d);
          },
          "delta_star"_a, "delta_max_star"_a, "d_star"_a,
          "Unloading (Eq. 4.11-4.12) by quadrature.")
      .def(
          "reloading_force_star",
          [](const RoughFlat& f, const ArrayLike& x, const ArrayLike& xm, const ArrayLike& d) {
            return vectorize(
                [&f](double a, double b, double c) { return f.reloading_force_star(a, b, c); }, x,
                xm, d);
          },
          "delta_star"_a, "delta_max_star"_a, "d_star"_a, "Reloading (Eq. 4.13).")
      .def(
          "energy_star",
          [](const RoughFlat& f, const ArrayLike& xm, const ArrayLike& d) {
            return vectorize([&f](double a, double b) { return f.energy_star(a, b); }, xm, d);
          },
          "delta_max_star"_a, "d_star"_a, "Energy per cycle over K H A0 sigma (Eq. 4.14).")
      .def(
          "stiffness_star",
          [](const RoughFlat& f, const ArrayLike& d) {
            return vectorize([&f](double v) { return f.stiffness_star(v); }, d);
          },
          "d_star"_a, "Tangential stiffness at a reversal over K H A0/sigma.")
      .def("backbone", &RoughFlat::backbone, "d_star"_a, "rel_tol"_a = 1e-9,
           "The tabulated backbone at separation d* (for Hysteresis).")
      .def("backbone_at_preload", &RoughFlat::backbone_at_preload, "P"_a, "rel_tol"_a = 1e-9,
           "The backbone in SI at preload P [N] (a flat from from_dimensional): Q_l [N] of "
           "delta [m], the tabulated backbone at the separation carrying P scaled by sigma_s "
           "and K H A0 (for Hysteresis).");
}

}  // namespace asperity::python
