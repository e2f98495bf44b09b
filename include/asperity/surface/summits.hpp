#pragma once
// Summits of a measured areal map, identified on the map itself: the summit-height
// distribution, summit density and tip radius that Greenwood and Williamson (1966) read
// off their surfaces, where chapter 5 derives them from spectral moments (Eq. 5.1).
// All quantities in SI units.
#include <cstddef>
#include <vector>

#include "asperity/surface/profile.hpp"
#include "asperity/surface/summit_heights.hpp"

namespace asperity::surface {

/// One summit: a grid point higher than its eight neighbours.
struct Summit {
  double x = 0.0;  ///< [m]
  double y = 0.0;  ///< [m]
  double z = 0.0;  ///< height above the map's reference plane z = 0 [m]
  /// Mean curvature -(z_xx + z_yy)/2 by central second differences along x and y
  /// (> 0 at a summit) [1/m]; the tip radius is its inverse.
  double curvature = 0.0;
};

/// The summits of a map and their statistics.
struct SummitSet {
  std::vector<Summit> summits;  ///< in raster order (x fastest)
  double area = 0.0;            ///< of the interior searched, (nx - 2)(ny - 2) dx dy [m^2]
  std::size_t points = 0;       ///< interior points searched, (nx - 2)(ny - 2)

  /// Summits per unit area, count / area [1/m^2] (the eta of Eq. 4.4).
  [[nodiscard]] double density() const;
  /// Mean and standard deviation (divisor n) of the summit heights [m].
  [[nodiscard]] double mean_height() const;
  [[nodiscard]] double height_standard_deviation() const;
  /// Tip radius 1 / <curvature> [m]: the radius of chapter 5's R = 0.375 sqrt(pi/m4), which is
  /// the inverse of the summits' mean curvature (Nayak 1971).
  [[nodiscard]] double radius() const;
};

/// Summits of a complete map (every point valid, nx, ny >= 3; normally the S-L surface of
/// scale_limited_surface()): interior points strictly higher than each of their eight
/// neighbours, where a neighbour of equal height earlier in raster order (x fastest) counts
/// as higher and one later does not, so that a flat pair of points is one summit, not zero
/// or two. Edge points (without eight neighbours) are not searched. Throws InvalidInput for
/// a map with invalid points, fewer than 3 x 3 points, or no summit at all.
///
/// The eight-neighbour count depends on the sampling interval (Greenwood 1984: finer
/// sampling finds more, smaller summits); the filter's short-wave cut-off ls should be
/// several spacings so that the grid resolves the summits it keeps.
[[nodiscard]] SummitSet find_summits(const HeightMap& map);

/// The summit heights' frequency polygon: `bins` equal bins from the lowest to the highest
/// summit, the density count_k / (n h) at each bin centre c_k and zero one bin beyond each
/// end. Linear between its points (as SummitHeightTable reads it) it integrates to 1, its
/// mean is the count-weighted mean of the bin centres and its variance that of the centres
/// plus h^2 / 6 (each hat function's own spread): wider bins widen the table.
struct SummitHistogram {
  std::vector<double> height;   ///< [m], bins + 2 points
  std::vector<double> density;  ///< [1/m]
  double bin_width = 0.0;       ///< h [m]
};

/// `bins` = 0 chooses Rice's rule, ceil(2 n^(1/3)) bins for n summits (at least 5). Throws
/// InvalidInput for fewer than 10 summits, all at one height, or bins above 10000.
[[nodiscard]] SummitHistogram summit_histogram(const SummitSet& set, std::size_t bins = 0);

/// The histogram as a table for the rough flat's sums; `what` names it in messages.
[[nodiscard]] SummitHeightTable summit_height_table(const SummitHistogram& histogram,
                                                    const std::string& what);

}  // namespace asperity::surface
