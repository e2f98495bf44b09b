#pragma once
// A measured distribution of summit heights for the Greenwood-Williamson sums of a rough
// flat: Eq. 4.4-4.14 with a tabulated density in place of Eq. 4.2's Gaussian phi(z).
#include <string>
#include <vector>

namespace asperity::surface {

/// Summit-height probability density, linear between tabulated heights and zero outside
/// them, standardized with the exact moments of that piecewise-linear density:
/// z* = (z - mean)/sd, phi*(z*) = sd phi(z) / Int phi dz (unit integral, mean 0, standard
/// deviation 1). A rough flat summing over it has sigma_a/sigma = 1 (summit_sigma), so
/// its length scale is `standard_deviation()` in the table's unit.
class SummitHeightTable {
 public:
  /// Heights z (any one length unit, strictly increasing) and the density, or histogram
  /// counts, at them (>= 0, any positive factor: normalized here). `what` names the table
  /// in messages. Throws InvalidInput when it is not a distribution: fewer than 3 points,
  /// a size mismatch, a value that is not finite, heights that do not increase, a negative
  /// density, or nothing above zero.
  SummitHeightTable(const std::vector<double>& z, const std::vector<double>& density,
                    const std::string& what);

  /// Mean and standard deviation of the heights in the input's unit.
  [[nodiscard]] double mean() const { return mean_; }
  [[nodiscard]] double standard_deviation() const { return sd_; }
  /// The standardized nodes z*_k and phi*(z*_k).
  [[nodiscard]] const std::vector<double>& z_star() const { return z_; }
  [[nodiscard]] const std::vector<double>& density_star() const { return p_; }
  /// phi*(z*): linear between nodes, 0 outside [z*_0, z*_last].
  [[nodiscard]] double density(double z_star) const;
  /// Fraction of the summits above z*: Int_{z*}^inf phi* dz* (exact for the linear pieces).
  [[nodiscard]] double survival(double z_star) const;
  /// The highest and lowest tabulated heights z* (the density's support: runs of zero
  /// density at the table's ends are dropped but for one zero node).
  [[nodiscard]] double top() const { return z_.back(); }
  [[nodiscard]] double bottom() const { return z_.front(); }
  /// Nodes strictly inside (lo, hi) in z*, ascending: where phi* has kinks.
  [[nodiscard]] std::vector<double> nodes_between(double lo, double hi) const;

 private:
  std::vector<double> z_, p_;
  std::vector<double> above_;  // survival at each node
  double mean_ = 0.0, sd_ = 0.0;
};

/// A summit-height table from a CSV file (core/csv.hpp's format; `asperity roughness
/// --summits` writes one): the columns height (with a length unit in the header, e.g.
/// "height[m]") and density, or count (any positive factor: normalized). Throws InvalidInput
/// naming the file for a missing column and for a table that is not a distribution.
[[nodiscard]] SummitHeightTable read_summit_height_table(const std::string& path);

}  // namespace asperity::surface
