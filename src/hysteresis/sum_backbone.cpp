// Backbones in parallel (see sum_backbone.hpp).
#include "asperity/hysteresis/sum_backbone.hpp"

#include <fmt/format.h>

#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::hysteresis {

SumBackbone::SumBackbone(std::vector<std::shared_ptr<const Backbone>> parts)
    : parts_(std::move(parts)) {
  if (parts_.empty()) throw InvalidInput("SumBackbone needs at least one backbone");
  for (const auto& p : parts_) {
    if (!p) throw InvalidInput("SumBackbone: a backbone is missing (null)");
    limit_ += p->limit();
    k0_ += p->initial_stiffness();
  }
}

double SumBackbone::force(double x) const {
  double Q = 0.0;
  for (const auto& p : parts_) Q += p->force(x);
  return Q;
}

double SumBackbone::integral(double x) const {
  double I = 0.0;
  for (const auto& p : parts_) I += p->integral(x);
  return I;
}

double SumBackbone::displacement(double Q) const {
  core::require_non_negative("force", Q);
  if (Q >= limit_) {
    throw InvalidInput(fmt::format(
        "force = {:.6g} reaches the static limit {:.6g} of the backbone: the contact slides", Q,
        limit_));
  }
  if (Q == 0.0) return 0.0;
  // Each part reaches its share no later than its own displacement of the same force
  // fraction; the largest x over the parts at which part i carries Q/limit of its limit
  // brackets the root.
  double hi = 0.0;
  for (const auto& p : parts_) hi = std::max(hi, p->displacement(Q / limit_ * p->limit()));
  if (force(hi) <= Q) return hi;
  return core::find_root([&](double x) { return force(x) - Q; }, 0.0, hi, "backbone inverse", 60);
}

}  // namespace asperity::hysteresis
