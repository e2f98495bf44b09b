#pragma once
// Simple backbones: Cattaneo-Mindlin (one asperity), Jenkins (elastic-perfectly
// plastic), a scaled view of another backbone, and one from user functions.
#include <functional>
#include <memory>

#include "asperity/contact/mindlin.hpp"
#include "asperity/hysteresis/masing.hpp"

namespace asperity::hysteresis {

/// Cattaneo-Mindlin virgin curve of one sphere (B.15 solved for Q), saturating at
/// mu P beyond the slip displacement.
class MindlinBackbone final : public Backbone {
 public:
  explicit MindlinBackbone(const contact::MindlinContact& contact);
  [[nodiscard]] double force(double x) const override;
  [[nodiscard]] double displacement(double Q) const override;
  [[nodiscard]] double limit() const override;
  [[nodiscard]] double initial_stiffness() const override;
  [[nodiscard]] double stiffness(double x) const override;
  [[nodiscard]] double integral(double x) const override;

 private:
  contact::MindlinContact contact_;
};

/// Jenkins element: a spring k in series with a Coulomb slider F: Q_l = min(k x, F).
class JenkinsBackbone final : public Backbone {
 public:
  JenkinsBackbone(double stiffness, double slip_force);
  [[nodiscard]] double force(double x) const override;
  [[nodiscard]] double displacement(double Q) const override;
  [[nodiscard]] double limit() const override { return F_; }
  [[nodiscard]] double initial_stiffness() const override { return k_; }
  /// k below the slip displacement F/k, 0 from there on.
  [[nodiscard]] double stiffness(double x) const override { return k_ * x < F_ ? k_ : 0.0; }
  [[nodiscard]] double integral(double x) const override;

 private:
  double k_;
  double F_;
};

/// Q(x) = Q_scale * inner(x / x_scale): e.g. a normalized rough-flat backbone
/// (delta*, Q*) seen in SI units (x_scale = sigma, Q_scale = K H A0).
class ScaledBackbone final : public Backbone {
 public:
  ScaledBackbone(std::shared_ptr<const Backbone> inner, double x_scale, double Q_scale);
  [[nodiscard]] double force(double x) const override;
  [[nodiscard]] double displacement(double Q) const override;
  [[nodiscard]] double limit() const override;
  [[nodiscard]] double initial_stiffness() const override;
  [[nodiscard]] double stiffness(double x) const override {
    return Q_scale_ / x_scale_ * inner_->stiffness(x / x_scale_);
  }
  [[nodiscard]] double integral(double x) const override;
  [[nodiscard]] const Backbone& inner() const { return *inner_; }
  [[nodiscard]] double x_scale() const { return x_scale_; }
  [[nodiscard]] double Q_scale() const { return Q_scale_; }

 private:
  std::shared_ptr<const Backbone> inner_;
  double x_scale_;
  double Q_scale_;
};

/// A backbone from a function Q_l(x) (x >= 0), its limit and initial stiffness; the
/// inverse is found by root finding. For tests and user-defined laws.
class FunctionBackbone final : public Backbone {
 public:
  FunctionBackbone(std::function<double(double)> force, double limit, double initial_stiffness);
  [[nodiscard]] double force(double x) const override { return f_(x); }
  [[nodiscard]] double displacement(double Q) const override;
  [[nodiscard]] double limit() const override { return limit_; }
  [[nodiscard]] double initial_stiffness() const override { return k0_; }

 private:
  std::function<double(double)> f_;
  double limit_;
  double k0_;
};

}  // namespace asperity::hysteresis
