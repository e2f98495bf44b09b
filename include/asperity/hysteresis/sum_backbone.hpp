#pragma once
// The backbone of elements in parallel under one common displacement: Q_l(x) = sum_i
// Q_l,i(x). Masing's rules are linear in the backbone (every branch is Q_r + s 2 Q_l(|x -
// x_r|/2), and the reversal and closing points depend on x alone), so Masing's rules on
// the sum equal the sum of each element's Masing response along the same displacement
// history: one Hysteresis over a SumBackbone replaces one per element. Used for the
// patches of a joint interface at their local pressures (joint/interface.hpp).
#include <memory>
#include <vector>

#include "asperity/hysteresis/backbone.hpp"

namespace asperity::hysteresis {

class SumBackbone final : public Backbone {
 public:
  /// At least one backbone; each is shared, not copied.
  explicit SumBackbone(std::vector<std::shared_ptr<const Backbone>> parts);
  [[nodiscard]] double force(double x) const override;
  /// Root of sum_i Q_l,i(x) = Q (bracketed, TOMS 748); InvalidInput for Q >= limit().
  [[nodiscard]] double displacement(double Q) const override;
  [[nodiscard]] double limit() const override { return limit_; }
  [[nodiscard]] double initial_stiffness() const override { return k0_; }
  [[nodiscard]] double integral(double x) const override;
  [[nodiscard]] const std::vector<std::shared_ptr<const Backbone>>& parts() const { return parts_; }

 private:
  std::vector<std::shared_ptr<const Backbone>> parts_;
  double limit_ = 0.0;
  double k0_ = 0.0;
};

}  // namespace asperity::hysteresis
