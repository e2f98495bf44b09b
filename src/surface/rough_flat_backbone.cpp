// The tabulated backbone of a rough flat (see RoughFlatBackbone in rough_flat.hpp).
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "gw_fast_sum.hpp"
#include "rough_flat_tolerances.hpp"

namespace asperity::surface {

namespace {

hysteresis::BackboneTabulation tabulation(const RoughFlat& flat, double d_star, double rel_tol) {
  core::require_finite("separation d*", d_star);
  auto sum = std::make_shared<const detail::FastLoadingSum>(flat, d_star);
  hysteresis::BackboneTabulation in;
  in.limit = sum->static_friction();
  const auto origin = sum->at(0.0);
  in.initial_stiffness = origin.dQ;
  in.initial_curvature = origin.d2Q;
  if (!(in.limit > 0.0) || !(in.initial_stiffness > 0.0)) {
    throw InvalidInput(fmt::format(
        "the rough flat carries no friction force at d* = {} (Q*_max = {}): with the {} model "
        "every asperity in contact has yielded (mu = 0) or none is in contact",
        core::format_value(d_star), core::format_value(in.limit),
        contact::to_string(flat.parameters().model)));
  }
  // Table end: where the virgin curve has saturated at Q_max to detail::kSaturation (it reaches
  // Q_max exactly once every asperity slips fully: the same rule then sums the same terms).
  in.x_end = in.limit / in.initial_stiffness;
  for (int i = 0;; ++i) {
    if (1.0 - sum->at(in.x_end).Q / in.limit < detail::kSaturation) break;
    in.x_end *= 1.5;
    if (i > 200) throw NumericalError("rough-flat backbone: the loading curve does not saturate");
  }
  for (double x : sum->critical_displacements()) {
    if (x > 0.0 && x < in.x_end) in.knots.push_back(x);
  }
  in.sample = [sum](double x) {
    const auto q = sum->at(x);
    return hysteresis::BackboneSample{q.Q, q.dQ, q.d2Q};
  };
  in.rel_tol = rel_tol;
  return in;
}

}  // namespace

RoughFlatBackbone::RoughFlatBackbone(const RoughFlat& flat, double d_star, double rel_tol)
    : hysteresis::TabulatedBackbone(tabulation(flat, d_star, rel_tol)), d_star_(d_star) {}

}  // namespace asperity::surface
