// vibration/: the thesis's rough flat as the 3-D contact law of a zero-thickness interface
// element (issue 20; include/asperity/vibration/rough_contact.hpp, docs/rough_contact.md).
// One RoughContactSurface (the rough flat and its tangential tables over the pressure) is
// shared by the elements of an interface; python/asperity/vibration.py (RoughContactSurface,
// RoughContact, rough_contact_on_interface) wraps these.
#include <nanobind/eigen/dense.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>

#include <fmt/format.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "asperity/vibration/rough_contact.hpp"
#include "bindings.hpp"
#include "summit_table.hpp"

namespace asperity::python {

using namespace nb::literals;
using namespace asperity::vibration;

namespace {

RoughInterfaceParameters interface_parameters(double E_star, double G_star, double H, double nu,
                                              std::optional<double> sigma_given, double R,
                                              double eta, const std::string& model,
                                              std::optional<double> mu_cfc, bool summit_sigma,
                                              const std::optional<Eigen::MatrixXd>& heights) {
  double sigma = 0.0;
  auto table = summit_table_from(heights, sigma_given, sigma, summit_sigma);
  RoughInterfaceParameters p{.E_star = E_star,
                             .G_star = G_star,
                             .H = H,
                             .nu = nu,
                             .sigma = sigma,
                             .R = R,
                             .eta = eta,
                             .model = contact::parse_model_name(model),
                             .friction = {},
                             .summit_sigma = summit_sigma,
                             .summit_heights = std::move(table)};
  if (mu_cfc) {
    core::require_positive("rough_contact.mu_cfc", *mu_cfc);
    p.friction.mu_cfc = *mu_cfc;
  }
  p.validate();
  return p;
}

// The largest pressure the rough flat represents (its load at d = -5 sigma_a) [Pa].
double flat_max_pressure(const RoughInterfaceParameters& p) {
  return surface::RoughFlat::from_combined(p.E_star, p.G_star, p.H, p.nu, p.sigma, p.R, p.eta,
                                           p.model, p.friction, p.summit_sigma, p.summit_heights)
             .max_load_star() *
         contact::hardness_factor(p.nu) * p.H;
}

}  // namespace

void bind_vibration_rough(nb::module_& vibration) {
  nb::class_<RoughContactSurface>(
      vibration, "RoughContactSurface",
      "An interface's rough flat per unit nominal area and its tangential tables over the "
      "normal pressure (log-spaced 2^(1/8) apart from p_low to p_high); shared by the "
      "interface's rough_contact elements. Use asperity.vibration.RoughContactSurface.")
      .def_prop_ro("p_low", &RoughContactSurface::p_low, "[Pa]")
      .def_prop_ro("p_high", &RoughContactSurface::p_high, "[Pa]")
      .def_prop_ro("pressure_scale", &RoughContactSurface::pressure_scale,
                   "K H [Pa]: pressures over it are the flat's P*")
      .def_prop_ro("sigma", &RoughContactSurface::sigma, "[m]")
      .def_prop_ro("tables", &RoughContactSurface::tables, "number of tangential tables over ln p")
      .def_prop_ro(
          "max_pressure",
          [](const RoughContactSurface& s) {
            return s.flat().max_load_star() * s.pressure_scale();
          },
          "[Pa]: the flat's load at d = -5 sigma_a, the largest it represents")
      .def(
          "separation_star",
          [](const RoughContactSurface& s, double pressure) {
            core::require_positive("pressure", pressure);
            return s.flat().separation_star(pressure / s.pressure_scale());
          },
          "pressure"_a, "d/sigma carrying the nominal pressure [Pa] (Eq. 4.4 inverted)");

  vibration.def(
      "rough_contact_surface",
      [](double E_star, double G_star, double H, double nu, std::optional<double> sigma, double R,
         double eta, const std::string& model, std::optional<double> mu_cfc, bool summit_sigma,
         double p_low, double p_high, const std::optional<Eigen::MatrixXd>& summit_heights) {
        const RoughInterfaceParameters p = interface_parameters(
            E_star, G_star, H, nu, sigma, R, eta, model, mu_cfc, summit_sigma, summit_heights);
        nb::gil_scoped_release release;
        return std::make_shared<RoughContactSurface>(p, p_low, p_high);
      },
      "E_star"_a, "G_star"_a, "H"_a, "nu"_a, "sigma"_a.none(), "R"_a, "eta"_a, "model"_a,
      "mu_cfc"_a.none(), "summit_sigma"_a, "p_low"_a, "p_high"_a,
      "summit_heights"_a.none() = nb::none(),
      "The rough surface of an interface (combined values, SI) with tables from p_low to "
      "p_high [Pa].");

  vibration.def(
      "rough_flat_max_pressure",
      [](double E_star, double G_star, double H, double nu, std::optional<double> sigma, double R,
         double eta, const std::string& model, std::optional<double> mu_cfc, bool summit_sigma,
         const std::optional<Eigen::MatrixXd>& summit_heights) {
        return flat_max_pressure(interface_parameters(E_star, G_star, H, nu, sigma, R, eta, model,
                                                      mu_cfc, summit_sigma, summit_heights));
      },
      "E_star"_a, "G_star"_a, "H"_a, "nu"_a, "sigma"_a.none(), "R"_a, "eta"_a, "model"_a,
      "mu_cfc"_a.none(), "summit_sigma"_a, "summit_heights"_a.none() = nb::none(),
      "The largest nominal pressure [Pa] the rough flat of these surfaces represents.");

  vibration.def(
      "rough_contact_element",
      [](std::shared_ptr<RoughContactSurface> surface, double area, double pressure,
         std::string name) {
        if (!surface) throw InvalidInput(fmt::format("{}: surface is None: give a surface", name));
        nb::gil_scoped_release release;
        return std::shared_ptr<const Element>(std::make_shared<RoughContactElement>(
            std::shared_ptr<const RoughContactSurface>(std::move(surface)), area, pressure,
            std::move(name)));
      },
      "surface"_a, "area"_a, "pressure"_a, "name"_a,
      "A zero-thickness element (directions t1, t2, n: closure) of area [m^2] at the prestress "
      "pressure [Pa] in [surface.p_low, surface.p_high].");
}

}  // namespace asperity::python
