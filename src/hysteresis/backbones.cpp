#include "asperity/hysteresis/backbones.hpp"

#include <fmt/format.h>

#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::hysteresis {

namespace {

[[noreturn]] void beyond_limit(double Q, double limit) {
  throw InvalidInput(
      fmt::format("tangential force {} reaches the static friction limit {}: the contact slides",
                  core::format_value(Q), core::format_value(limit)));
}

}  // namespace

MindlinBackbone::MindlinBackbone(const contact::MindlinContact& contact) : contact_(contact) {
  if (!(contact.Q_max() > 0.0)) {
    throw InvalidInput("a Mindlin backbone needs a friction force mu P > 0");
  }
}

double MindlinBackbone::force(double x) const {
  return contact_.loading_force(x);
}

double MindlinBackbone::displacement(double Q) const {
  if (Q >= contact_.Q_max()) beyond_limit(Q, contact_.Q_max());
  return contact_.loading_displacement(Q);
}

double MindlinBackbone::limit() const {
  return contact_.Q_max();
}
double MindlinBackbone::initial_stiffness() const {
  return contact_.stiffness();
}

double MindlinBackbone::stiffness(double x) const {
  core::require_non_negative("x", x);
  // d/dx of mu P (1 - (1 - x/s)^{3/2}) (B.15 solved for Q).
  const double s = contact_.slip_displacement();
  if (x >= s) return 0.0;
  return 1.5 * contact_.Q_max() / s * std::sqrt(1.0 - x / s);
}

double MindlinBackbone::integral(double x) const {
  core::require_non_negative("x", x);
  // Int_0^x mu P (1 - (1 - t/s)^{3/2}) dt = mu P (x - 2 s/5 (1 - (1 - x/s)^{5/2})) for
  // x <= s, and the plateau mu P (x - s) beyond.
  const double s = contact_.slip_displacement();
  const double F = contact_.Q_max();
  if (x <= s) return F * (x - 0.4 * s * (1.0 - std::pow(1.0 - x / s, 2.5)));
  return F * (0.6 * s + (x - s));
}

JenkinsBackbone::JenkinsBackbone(double stiffness, double slip_force)
    : k_(stiffness), F_(slip_force) {
  core::require_positive("Jenkins stiffness", stiffness);
  core::require_positive("Jenkins slip force", slip_force);
}

double JenkinsBackbone::force(double x) const {
  return std::min(k_ * x, F_);
}

double JenkinsBackbone::displacement(double Q) const {
  if (Q >= F_) beyond_limit(Q, F_);
  return Q / k_;
}

double JenkinsBackbone::integral(double x) const {
  const double xs = F_ / k_;
  if (x <= xs) return 0.5 * k_ * x * x;
  return 0.5 * F_ * xs + F_ * (x - xs);
}

ScaledBackbone::ScaledBackbone(std::shared_ptr<const Backbone> inner, double x_scale,
                               double Q_scale)
    : inner_(std::move(inner)), x_scale_(x_scale), Q_scale_(Q_scale) {
  if (!inner_) throw InvalidInput("ScaledBackbone needs a backbone");
  core::require_positive("x_scale", x_scale);
  core::require_positive("Q_scale", Q_scale);
}

double ScaledBackbone::force(double x) const {
  return Q_scale_ * inner_->force(x / x_scale_);
}
double ScaledBackbone::displacement(double Q) const {
  return x_scale_ * inner_->displacement(Q / Q_scale_);
}
double ScaledBackbone::limit() const {
  return Q_scale_ * inner_->limit();
}
double ScaledBackbone::initial_stiffness() const {
  return Q_scale_ / x_scale_ * inner_->initial_stiffness();
}
double ScaledBackbone::integral(double x) const {
  return Q_scale_ * x_scale_ * inner_->integral(x / x_scale_);
}

FunctionBackbone::FunctionBackbone(std::function<double(double)> force, double limit,
                                   double initial_stiffness)
    : f_(std::move(force)), limit_(limit), k0_(initial_stiffness) {
  if (!f_) throw InvalidInput("FunctionBackbone needs a function");
  core::require_positive("backbone limit", limit);
  core::require_positive("backbone initial stiffness", initial_stiffness);
}

double FunctionBackbone::displacement(double Q) const {
  core::require_non_negative("force", Q);
  if (Q >= limit_) beyond_limit(Q, limit_);
  if (Q == 0.0) return 0.0;
  double hi = Q / k0_;
  int n = 0;
  while (f_(hi) < Q) {
    hi *= 2.0;
    if (++n > 1100) throw NumericalError("FunctionBackbone: no displacement reaches the force");
  }
  return core::find_root([&](double x) { return f_(x) - Q; }, 0.0, hi, "backbone inverse", 60);
}

}  // namespace asperity::hysteresis
