// The tabulated backbone of a rough flat in patches (see patched_flat.hpp).
#include "asperity/surface/patched_flat.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "gw_fast_sum.hpp"
#include "rough_flat_tolerances.hpp"

namespace asperity::surface {

namespace {

// Patches whose d* agree to this (relative) share one sum.
constexpr double kSameSeparation = 1e-12;

struct Group {
  double weight = 0.0;
  double d_star = 0.0;
  std::shared_ptr<const detail::FastLoadingSum> sum;
  double Q_max = 0.0;  // unweighted
  double k0 = 0.0;
  double x_end = 0.0;
};

}  // namespace

struct PatchedRoughFlatBackbone::Built {
  hysteresis::BackboneTabulation tab;
  std::vector<FlatPatchResponse> responses;
  std::size_t distinct = 0;
};

PatchedRoughFlatBackbone::PatchedRoughFlatBackbone(const RoughFlat& flat,
                                                   const std::vector<FlatPatch>& patches,
                                                   double rel_tol, double series_compliance_star)
    : PatchedRoughFlatBackbone(build(flat, patches, rel_tol, series_compliance_star), patches) {}

PatchedRoughFlatBackbone::PatchedRoughFlatBackbone(Built&& b, const std::vector<FlatPatch>& patches)
    : hysteresis::TabulatedBackbone(b.tab),
      patches_(patches),
      responses_(std::move(b.responses)),
      distinct_(b.distinct) {}

PatchedRoughFlatBackbone::Built PatchedRoughFlatBackbone::build(
    const RoughFlat& flat, const std::vector<FlatPatch>& patches, double rel_tol,
    double series_compliance_star) {
  const double C = series_compliance_star;
  if (!(C >= 0.0) || !std::isfinite(C)) {
    throw InvalidInput(fmt::format("series compliance C* = {} must be >= 0", C));
  }
  if (patches.empty()) throw InvalidInput("patched rough flat: no patch");
  std::vector<Group> groups;
  std::vector<std::size_t> group_of(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto& p = patches[i];
    if (!(p.weight > 0.0) || !std::isfinite(p.weight)) {
      throw InvalidInput(fmt::format("patch {}: area share = {} must be > 0", i + 1, p.weight));
    }
    core::require_finite("separation d*", p.d_star);
    std::size_t g = 0;
    while (g < groups.size() && !(std::abs(groups[g].d_star - p.d_star) <=
                                  kSameSeparation * std::max(1.0, std::abs(p.d_star))))
      ++g;
    if (g == groups.size()) groups.push_back({0.0, p.d_star, nullptr, 0.0, 0.0, 0.0});
    groups[g].weight += p.weight;
    group_of[i] = g;
  }
  Built out;
  out.distinct = groups.size();
  auto& in = out.tab;
  for (auto& g : groups) {
    g.sum = std::make_shared<const detail::FastLoadingSum>(flat, g.d_star);
    g.Q_max = g.sum->static_friction();
    g.k0 = g.sum->at(0.0).dQ;
    if (!(g.Q_max > 0.0) || !(g.k0 > 0.0)) {
      throw InvalidInput(fmt::format(
          "a patch at d* = {} carries no friction force (Q*_max = {}): with the {} model every "
          "asperity in contact has yielded (mu = 0) or none is in contact",
          core::format_value(g.d_star), core::format_value(g.Q_max),
          contact::to_string(flat.parameters().model)));
    }
    // The patch's own end (as RoughFlatBackbone): Q_l = Q_max to detail::kSaturation beyond.
    g.x_end = g.Q_max / g.k0;
    for (int i = 0;; ++i) {
      if (1.0 - g.sum->at(g.x_end).Q / g.Q_max < detail::kSaturation) break;
      g.x_end *= 1.5;
      if (i > 200) throw NumericalError("patched backbone: a patch's loading does not saturate");
    }
    in.limit += g.weight * g.Q_max;
    in.initial_stiffness += g.weight * g.k0;
    in.initial_curvature += g.weight * g.sum->at(0.0).d2Q;
    in.x_end = std::max(in.x_end, g.x_end);
  }
  for (const auto& g : groups) {
    for (double x : g.sum->critical_displacements()) {
      if (x > 0.0 && x < in.x_end) in.knots.push_back(x);
    }
    // Where a patch saturates, the sum's curvature may change abruptly.
    if (g.x_end < in.x_end) in.knots.push_back(g.x_end);
  }
  std::sort(in.knots.begin(), in.knots.end());
  in.knots.erase(std::unique(in.knots.begin(), in.knots.end()), in.knots.end());
  if (groups.size() == 1) {
    // One sum: exactly RoughFlatBackbone's samples (scaled by the weight).
    const auto g = groups.front();
    in.sample = [g](double x) {
      const auto q = g.sum->at(x);
      return hysteresis::BackboneSample{g.weight * q.Q, g.weight * q.dQ, g.weight * q.d2Q};
    };
  } else {
    in.sample = [groups](double x) {
      hysteresis::BackboneSample s;
      for (const auto& g : groups) {
        const auto q = g.sum->at(x);
        s.Q += g.weight * q.Q;
        s.dQ += g.weight * q.dQ;
        s.d2Q += g.weight * q.d2Q;
      }
      return s;
    };
  }
  in.rel_tol = rel_tol;
  in.max_intervals = 1u << 16;
  if (C > 0.0) {
    // The interface in series with a linear spring: sample at x* by solving
    // x*_i + C* Q*_l(x*_i) = x* (monotone in x*_i; Newton steps kept inside a shrinking
    // bracket [0, x*], first guess x*/(1 + C* k0)).
    const auto interface = in.sample;
    const double k0 = in.initial_stiffness;
    in.sample = [interface, C, k0](double x) {
      double lo = 0.0, hi = x, xi = x / (1.0 + C * k0);
      hysteresis::BackboneSample q = interface(xi);
      for (int it = 0; it < 200; ++it) {
        const double h = xi + C * q.Q - x;
        if (h > 0.0) {
          hi = xi;
        } else {
          lo = xi;
        }
        if (std::abs(h) <= 1e-15 * x || hi - lo <= 1e-15 * x) break;
        double next = xi - h / (1.0 + C * q.dQ);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        xi = next;
        q = interface(xi);
      }
      const double s = 1.0 + C * q.dQ;
      return hysteresis::BackboneSample{q.Q, q.dQ / s, q.d2Q / (s * s * s)};
    };
    for (double& k : in.knots) k += C * interface(k).Q;
    for (auto& g : groups) g.x_end += C * interface(g.x_end).Q;
    in.x_end += C * in.limit;
    in.initial_curvature /= std::pow(1.0 + C * k0, 3);
    in.initial_stiffness = k0 / (1.0 + C * k0);
  }
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto& g = groups[group_of[i]];
    out.responses.push_back({patches[i].weight * g.Q_max, patches[i].weight * g.k0, g.x_end});
  }
  return out;
}

}  // namespace asperity::surface
