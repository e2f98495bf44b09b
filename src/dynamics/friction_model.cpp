#include "asperity/dynamics/friction_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/hysteresis/backbones.hpp"

namespace asperity::dynamics {

std::unique_ptr<FrictionModel> NoFriction::clone() const {
  return std::make_unique<NoFriction>(*this);
}

void RegularizedCoulombParameters::validate() const {
  core::require_positive("coulomb F_max", F_max);
  core::require_positive("coulomb k_tan", k_tan);
}

RegularizedCoulomb::RegularizedCoulomb(RegularizedCoulombParameters p) : p_(p) {
  p_.validate();
}

std::unique_ptr<FrictionModel> RegularizedCoulomb::clone() const {
  return std::make_unique<RegularizedCoulomb>(*this);
}

double RegularizedCoulomb::force(double, double v, std::span<const double>) const {
  return p_.F_max * std::tanh(p_.k_tan * v);  // Eq. 7.3
}

void DankowiczParameters::validate() const {
  core::require_positive("dankowicz F_max", F_max);
  core::require_positive("dankowicz delta", delta);
}

Dankowicz::Dankowicz(DankowiczParameters p) : p_(p) {
  p_.validate();
}

std::unique_ptr<FrictionModel> Dankowicz::clone() const {
  return std::make_unique<Dankowicz>(*this);
}

double Dankowicz::force(double, double, std::span<const double> z) const {
  return p_.F_max * z[0] / p_.delta;  // Eq. 7.7
}

void Dankowicz::internal_rates(double, double v, std::span<const double> z,
                               std::span<double> dz) const {
  // Eq. 7.6: zeta' = u' (1 - zeta/delta sgn u') = u' - |u'| zeta/delta.
  dz[0] = v - std::abs(v) * (z[0] / p_.delta);
}

HysteresisFriction::HysteresisFriction(std::shared_ptr<const hysteresis::Backbone> backbone,
                                       hysteresis::MemoryRule rule, std::string name)
    : h_(std::move(backbone), rule), name_(std::move(name)) {}

std::unique_ptr<FrictionModel> HysteresisFriction::clone() const {
  return std::make_unique<HysteresisFriction>(*this);
}

double HysteresisFriction::force(double u, double, std::span<const double>) const {
  return h_.force(u);
}

void HysteresisFriction::commit_reversal(double u) {
  h_.commit_reversal(u);
}

std::unique_ptr<FrictionModel> make_jenkins(double stiffness, double F_max) {
  return std::make_unique<HysteresisFriction>(
      std::make_shared<hysteresis::JenkinsBackbone>(stiffness, F_max),
      hysteresis::MemoryRule::masing, "jenkins");
}

void SegalmanIwanParameters::validate() const {
  core::require_positive("iwan F_S", F_S);
  core::require_positive("iwan K_T", K_T);
  if (!(chi > -1.0 && chi <= 0.0)) {
    throw InvalidInput(fmt::format("iwan chi = {} is not allowed: it must lie in (-1, 0]",
                                   core::format_value(chi)));
  }
  core::require_non_negative("iwan beta", beta);
}

SegalmanBackbone::SegalmanBackbone(SegalmanIwanParameters p) : p_(p) {
  p_.validate();
  const double c = p_.chi;
  const double g = p_.beta + (c + 1.0) / (c + 2.0);
  phi_max_ = p_.F_S * (1.0 + p_.beta) / (p_.K_T * g);
  R_ = p_.F_S * (c + 1.0) / (std::pow(phi_max_, c + 2.0) * g);
  S_ = p_.F_S / phi_max_ * p_.beta / g;
}

double SegalmanBackbone::force(double x) const {
  if (x <= 0.0) return 0.0;
  if (x >= phi_max_) return p_.F_S;
  const double c = p_.chi;
  // Elements with phi < x have slipped (carry R phi^chi * phi); the rest carry x each.
  return R_ * std::pow(x, c + 2.0) / (c + 2.0) +
         x * (R_ * (std::pow(phi_max_, c + 1.0) - std::pow(x, c + 1.0)) / (c + 1.0) + S_);
}

double SegalmanBackbone::stiffness(double x) const {
  core::require_non_negative("x", x);
  if (x >= phi_max_) return 0.0;
  // d/dx of force(): the elements not yet slipped, R (phi_max^{chi+1} - x^{chi+1})/(chi+1) + S.
  const double c = p_.chi;
  return R_ * (std::pow(phi_max_, c + 1.0) - std::pow(x, c + 1.0)) / (c + 1.0) + S_;
}

double SegalmanBackbone::displacement(double Q) const {
  core::require_non_negative("force", Q);
  if (Q >= p_.F_S) {
    throw InvalidInput(
        fmt::format("tangential force {} reaches the Iwan macro-slip force {}: the joint slides",
                    core::format_value(Q), core::format_value(p_.F_S)));
  }
  if (Q == 0.0) return 0.0;
  return core::find_root([&](double x) { return force(x) - Q; }, 0.0, phi_max_,
                         "Iwan backbone inverse", 60);
}

double SegalmanBackbone::integral(double x) const {
  core::require_non_negative("x", x);
  const double c = p_.chi;
  const double xm = std::min(x, phi_max_);
  // Int_0^x of R t^{c+2}/(c+2) + t (R phi^{c+1}/(c+1) + S) - R t^{c+2}/(c+1) dt.
  const double a = R_ / (c + 2.0) - R_ / (c + 1.0);
  const double lin = R_ * std::pow(phi_max_, c + 1.0) / (c + 1.0) + S_;
  double I = a * std::pow(xm, c + 3.0) / (c + 3.0) + 0.5 * lin * xm * xm;
  if (x > phi_max_) I += p_.F_S * (x - phi_max_);
  return I;
}

std::unique_ptr<FrictionModel> make_segalman_iwan(SegalmanIwanParameters p) {
  return std::make_unique<HysteresisFriction>(std::make_shared<SegalmanBackbone>(p),
                                              hysteresis::MemoryRule::masing, "iwan");
}

std::unique_ptr<FrictionModel> make_physics_based(
    std::shared_ptr<const hysteresis::Backbone> backbone_si, double k, double A,
    hysteresis::MemoryRule rule) {
  core::require_positive("structural stiffness k", k);
  core::require_positive("reference amplitude A", A);
  // F_s(u) = Q(A u)/(k A): ScaledBackbone computes Q_scale * inner(x / x_scale).
  auto scaled =
      std::make_shared<hysteresis::ScaledBackbone>(std::move(backbone_si), 1.0 / A, 1.0 / (k * A));
  return std::make_unique<HysteresisFriction>(std::move(scaled), rule, "physics");
}

}  // namespace asperity::dynamics
