#pragma once
// Internal: a statistical sum over a measured summit-height density, whose kinks at the
// table's nodes split every piece between breaks.
#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <vector>

#include "asperity/surface/summit_heights.hpp"

namespace asperity::surface::detail {

/// The summit heights a sum at separation d* runs over, in u = z* - d*: [0, u_max], and a
/// measured table's nodes inside (ascending). A Gaussian (table null, spread s_a) is cut
/// where its density falls below exp(-tail_exponent) of its value at max(d*, 0); a table
/// ends at its highest summit.
struct HeightRange {
  double u_max = 0.0;
  std::vector<double> nodes;
};
inline HeightRange height_range(const SummitHeightTable* table, double d, double s_a,
                                double tail_exponent) {
  HeightRange r;
  if (table) {
    r.u_max = std::max(table->top() - d, 0.0);
    for (double z : table->nodes_between(d, table->top())) r.nodes.push_back(z - d);
  } else {
    const double z0 = std::max(d, 0.0);
    r.u_max = std::sqrt(z0 * z0 + 2.0 * tail_exponent * s_a * s_a) - d;
  }
  return r;
}

/// Inner pieces up to this wide (in sigma) take the fixed rule; wider ones (a coarse table)
/// the end rule.
inline constexpr double kFixedRuleWidth = 0.05;

/// Integral of g over each piece [breaks[i], breaks[i+1]] (breaks ascending), split at the
/// density's `nodes` (ascending) inside it: the inner pieces between two nodes (~0.01 wide
/// for a measured table, the integrand smooth on them) take a 10-point Gauss-Legendre rule
/// (up to kFixedRuleWidth),
/// the end pieces that touch a break (where the integrand may have a root singularity) and
/// their neighbours `end_rule(g, a, b)`, e.g. tanh-sinh.
template <class G, class EndRule>
double integrate_between_nodes(G g, EndRule end_rule, const std::vector<double>& breaks,
                               const std::vector<double>& nodes) {
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = breaks[i];
    const double b = breaks[i + 1];
    if (!(b > a)) continue;
    const auto first = std::upper_bound(nodes.begin(), nodes.end(), a);
    const auto last = std::lower_bound(nodes.begin(), nodes.end(), b);
    if (first >= last) {
      total += end_rule(g, a, b);
      continue;
    }
    total += end_rule(g, a, *first);
    for (auto it = first; it + 1 < last; ++it) {
      // The pieces next to the end pieces too take the end rule: a break may lie just
      // outside them (a root singularity at a distance far below their width).
      const bool next_to_end = it == first || it + 2 == last;
      total += !next_to_end && *(it + 1) - *it <= kFixedRuleWidth
                   ? boost::math::quadrature::gauss<double, 10>::integrate(g, *it, *(it + 1))
                   : end_rule(g, *it, *(it + 1));
    }
    total += end_rule(g, *(last - 1), b);
  }
  return total;
}

}  // namespace asperity::surface::detail
