#include "asperity/surface/summits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "asperity/core/error.hpp"

namespace asperity::surface {

double SummitSet::density() const {
  return static_cast<double>(summits.size()) / area;
}

double SummitSet::mean_height() const {
  double s = 0.0;
  for (const auto& p : summits) s += p.z;
  return s / static_cast<double>(summits.size());
}

double SummitSet::height_standard_deviation() const {
  const double m = mean_height();
  double s = 0.0;
  for (const auto& p : summits) s += (p.z - m) * (p.z - m);
  return std::sqrt(s / static_cast<double>(summits.size()));
}

double SummitSet::radius() const {
  double s = 0.0;
  for (const auto& p : summits) s += p.curvature;
  return static_cast<double>(summits.size()) / s;
}

SummitSet find_summits(const HeightMap& map) {
  map.validate();
  if (map.nx < 3 || map.ny < 3)
    throw InvalidInput(fmt::format("{}: summits need a map of 3 x 3 points or more; it has {} x {}",
                                   map.source, map.nx, map.ny));
  if (const std::size_t bad = map.invalid_count(); bad > 0)
    throw InvalidInput(
        fmt::format("{}: summits need every point of the map (a summit is compared with its eight "
                    "neighbours), and {} of the {} points are invalid",
                    map.source, bad, map.z.size()));
  SummitSet out;
  out.points = (map.nx - 2) * (map.ny - 2);
  out.area = static_cast<double>(map.nx - 2) * map.dx * static_cast<double>(map.ny - 2) * map.dy;
  const auto z = [&](std::size_t ix, std::size_t iy) { return map.z[ix + map.nx * iy]; };
  for (std::size_t iy = 1; iy + 1 < map.ny; ++iy)
    for (std::size_t ix = 1; ix + 1 < map.nx; ++ix) {
      const double c = z(ix, iy);
      // Earlier neighbours (the row below, and the left one) must be lower; later ones
      // lower or equal.
      const bool summit = c > z(ix - 1, iy - 1) && c > z(ix, iy - 1) && c > z(ix + 1, iy - 1) &&
                          c > z(ix - 1, iy) && c >= z(ix + 1, iy) && c >= z(ix - 1, iy + 1) &&
                          c >= z(ix, iy + 1) && c >= z(ix + 1, iy + 1);
      if (!summit) continue;
      const double zxx = (z(ix + 1, iy) - 2.0 * c + z(ix - 1, iy)) / (map.dx * map.dx);
      const double zyy = (z(ix, iy + 1) - 2.0 * c + z(ix, iy - 1)) / (map.dy * map.dy);
      const double kappa = -0.5 * (zxx + zyy);
      // kappa > 0 unless the summit is flat along both axes (then it is left out: no tip).
      if (!(kappa > 0.0)) continue;
      out.summits.push_back({map.x0 + static_cast<double>(ix) * map.dx,
                             map.y0 + static_cast<double>(iy) * map.dy, c, kappa});
    }
  if (out.summits.empty())
    throw InvalidInput(
        fmt::format("{}: no summit (a point higher than its eight neighbours) in the map's {} "
                    "interior points",
                    map.source, out.points));
  return out;
}

SummitHistogram summit_histogram(const SummitSet& set, std::size_t bins) {
  const std::size_t n = set.summits.size();
  if (n < 10)
    throw InvalidInput(fmt::format(
        "a summit-height histogram needs 10 summits or more; the map has {} (a larger scan, or "
        "a shorter ls, finds more)",
        n));
  if (bins > 10000)
    throw InvalidInput(
        fmt::format("summit-height bins = {}: allowed are 1 to 10000 (0 = Rice's "
                    "rule)",
                    bins));
  if (bins == 0)
    bins = std::max<std::size_t>(
        5, static_cast<std::size_t>(std::ceil(2.0 * std::cbrt(static_cast<double>(n)))));
  const auto [lo_it, hi_it] =
      std::minmax_element(set.summits.begin(), set.summits.end(),
                          [](const Summit& a, const Summit& b) { return a.z < b.z; });
  const double lo = lo_it->z, hi = hi_it->z;
  if (!(hi > lo))
    throw InvalidInput(
        fmt::format("all {} summits are at one height ({} m): no distribution of heights", n, lo));
  const double h = (hi - lo) / static_cast<double>(bins);
  std::vector<double> count(bins, 0.0);
  for (const auto& s : set.summits) {
    const auto k = static_cast<std::size_t>((s.z - lo) / h);
    ++count[std::min(k, bins - 1)];  // the highest summit closes the last bin
  }
  SummitHistogram out;
  out.bin_width = h;
  out.height.reserve(bins + 2);
  out.density.reserve(bins + 2);
  out.height.push_back(lo - 0.5 * h);
  out.density.push_back(0.0);
  for (std::size_t k = 0; k < bins; ++k) {
    out.height.push_back(lo + (static_cast<double>(k) + 0.5) * h);
    out.density.push_back(count[k] / (static_cast<double>(n) * h));
  }
  out.height.push_back(hi + 0.5 * h);
  out.density.push_back(0.0);
  return out;
}

SummitHeightTable summit_height_table(const SummitHistogram& histogram, const std::string& what) {
  return SummitHeightTable(histogram.height, histogram.density, what);
}

}  // namespace asperity::surface
