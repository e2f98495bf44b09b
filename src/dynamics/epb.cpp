#include "asperity/dynamics/epb.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "asperity/contact/material.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/surface/rough_flat.hpp"

namespace asperity::dynamics {

void EpbContact::validate() const {
  core::require_positive("E_star", E_star);
  core::require_positive("G_star", G_star);
  core::require_positive("H", H);
  core::require_in_half_open("nu", nu, 0.0, 0.5);
  core::require_positive("sigma", sigma);
  core::require_positive("R", R);
  core::require_positive("eta", eta);
  core::require_positive("A0 (nominal contact area)", A0);
  core::require_positive("P (normal load)", P);
  const double beta = sigma * R * eta;
  if (!(beta > 0.01928)) {
    throw InvalidInput(
        fmt::format("beta = sigma R eta = {:.4g} must exceed 0.01928 (the asperity-height spread "
                    "sqrt(1 - 3.717e-4/beta^2) is real only above it)",
                    beta));
  }
  friction.validate();
}

EpbContact table_7_2_rough() {
  return {};
}

EpbContact table_7_2_smooth() {
  EpbContact c;
  c.sigma = 0.85e-6;
  c.R = 24.8e-6;
  c.eta = 1.5e9;
  return c;
}

std::shared_ptr<const hysteresis::Backbone> epb_backbone(const EpbContact& c) {
  c.validate();
  const double K = contact::hardness_factor(c.nu);
  const auto flat = surface::RoughFlat::from_combined(c.E_star, c.G_star, c.H, c.nu, c.sigma, c.R,
                                                      c.eta, c.model, c.friction);
  const double force_scale = K * c.H * c.A0;
  const double d_star = flat.separation_star(c.P / force_scale);
  return std::make_shared<hysteresis::ScaledBackbone>(flat.backbone(d_star), c.sigma, force_scale);
}

}  // namespace asperity::dynamics
