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

/// Visits the pieces of [a, b] split at the density's `nodes` (ascending) inside it, left to
/// right: end(x0, x1) for the two pieces that touch a or b and for their neighbours (a break
/// may lie just outside those: a root singularity at a distance far below their width),
/// inner(x0, x1) for the pieces between two nodes farther in.
template <class End, class Inner>
void split_at_nodes(double a, double b, const std::vector<double>& nodes, End end, Inner inner) {
  const auto first = std::upper_bound(nodes.begin(), nodes.end(), a);
  const auto last = std::lower_bound(nodes.begin(), nodes.end(), b);
  if (first >= last) {
    end(a, b);
    return;
  }
  end(a, *first);
  for (auto it = first; it + 1 < last; ++it) {
    if (it == first || it + 2 == last) {
      end(*it, *(it + 1));
    } else {
      inner(*it, *(it + 1));
    }
  }
  end(*(last - 1), b);
}

/// Integral of g over each piece [breaks[i], breaks[i+1]] (breaks ascending), split at the
/// density's `nodes` by split_at_nodes: the inner pieces (~0.01 wide for a measured table,
/// the integrand smooth on them) take a 10-point Gauss-Legendre rule (up to
/// kFixedRuleWidth), the others `end_rule(g, a, b)`, e.g. tanh-sinh.
template <class G, class EndRule>
double integrate_between_nodes(G g, EndRule end_rule, const std::vector<double>& breaks,
                               const std::vector<double>& nodes) {
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = breaks[i];
    const double b = breaks[i + 1];
    if (!(b > a)) continue;
    split_at_nodes(
        a, b, nodes, [&](double x0, double x1) { total += end_rule(g, x0, x1); },
        [&](double x0, double x1) {
          total += x1 - x0 <= kFixedRuleWidth
                       ? boost::math::quadrature::gauss<double, 10>::integrate(g, x0, x1)
                       : end_rule(g, x0, x1);
        });
  }
  return total;
}

}  // namespace asperity::surface::detail
