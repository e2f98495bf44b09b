#include <algorithm>

#include <fmt/format.h>

#include "asperity/contact/material.hpp"
#include "asperity/core/error.hpp"
#include "asperity/vibration/rough_contact.hpp"

namespace asperity::vibration {

InterfaceRoughContact interface_rough_contact(const fem::ReducedModel& model,
                                              contact::ModelName asperity_model,
                                              const contact::FrictionParameters& friction,
                                              const std::string& name, const std::string& what) {
  if (!model.rough) {
    throw InvalidInput(fmt::format(
        "{}: the reduced model of {} has no rough interface ([rough_contact]: its surfaces and "
        "each element's prestress pressure)",
        what, model.source));
  }
  const fem::RoughInterfaceRecord& r = *model.rough;
  RoughInterfaceParameters rp{.E_star = r.E_star,
                              .G_star = r.G_star,
                              .H = r.H,
                              .nu = r.nu,
                              .sigma = r.sigma,
                              .R = r.R,
                              .eta = r.eta,
                              .model = asperity_model,
                              .friction = friction,
                              .summit_sigma = r.summit_sigma,
                              .summit_heights = r.summit_heights};
  // The elements in contact by the prestress's rule (at least one asperity expected in
  // contact, eta A Phi(d) >= 1): those its linearised modes stiffen.
  InterfaceRoughContact out;
  for (Eigen::Index e = 0; e < r.pressure.size(); ++e)
    if (r.in_contact[static_cast<std::size_t>(e)] && r.pressure[e] > 0.0)
      out.interface_elements.push_back(e);
  if (out.interface_elements.empty()) {
    throw InvalidInput(fmt::format(
        "{}: no interface element of {} is in contact at the rough prestress", what, model.source));
  }
  double p_min = r.pressure[out.interface_elements.front()], p_max = p_min;
  for (const Eigen::Index e : out.interface_elements) {
    p_min = std::min(p_min, r.pressure[e]);
    p_max = std::max(p_max, r.pressure[e]);
  }
  // One surface for the interface: tables from p_min/8 to 8 p_max (as a single element's,
  // docs/rough_contact.md), below the largest load the rough flat represents.
  const double p_flat_max =
      surface::RoughFlat::from_combined(rp.E_star, rp.G_star, rp.H, rp.nu, rp.sigma, rp.R, rp.eta,
                                        rp.model, rp.friction, rp.summit_sigma, rp.summit_heights)
          .max_load_star() *
      contact::hardness_factor(rp.nu) * rp.H;
  const auto surface = std::make_shared<const RoughContactSurface>(
      rp, p_min / 8.0, std::min(8.0 * p_max, 0.999 * p_flat_max));
  const Eigen::Index dofs = model.dofs();
  out.elements.reserve(out.interface_elements.size());
  for (const Eigen::Index e : out.interface_elements) {
    PlacedElement pe;
    pe.name = fmt::format("{} {}", name, e);
    pe.element = std::make_shared<RoughContactElement>(
        surface, model.elements[static_cast<std::size_t>(e)].area, r.pressure[e],
        fmt::format("{} (interface element {})", what, e));
    pe.T.resize(3, dofs);
    pe.T.row(0) = model.Q.row(3 * e);
    pe.T.row(1) = model.Q.row(3 * e + 1);
    pe.T.row(2) = -model.Q.row(3 * e + 2);
    out.elements.push_back(std::move(pe));
  }
  return out;
}

}  // namespace asperity::vibration
