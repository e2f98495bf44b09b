#include "asperity/surface/summit_heights.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::surface {

SummitHeightTable::SummitHeightTable(const std::vector<double>& z,
                                     const std::vector<double>& density, const std::string& what) {
  const auto fail = [&](const std::string& why) {
    throw InvalidInput(fmt::format("summit-height table {} is not a distribution: {}", what, why));
  };
  if (z.size() != density.size())
    fail(fmt::format("{} heights but {} densities", z.size(), density.size()));
  if (z.size() < 3) fail(fmt::format("{} points; give 3 or more", z.size()));
  for (std::size_t k = 0; k < z.size(); ++k) {
    if (!std::isfinite(z[k]) || !std::isfinite(density[k]))
      fail(fmt::format("point {} (height {}, density {}) is not finite", k + 1,
                       core::format_value(z[k]), core::format_value(density[k])));
    if (density[k] < 0.0)
      fail(fmt::format("density {} at point {} (height {}) is negative; a density is >= 0",
                       core::format_value(density[k]), k + 1, core::format_value(z[k])));
    if (k > 0 && !(z[k] > z[k - 1]))
      fail(
          fmt::format("height {} at point {} does not exceed the one before ({}); heights must "
                      "increase",
                      core::format_value(z[k]), k + 1, core::format_value(z[k - 1])));
  }
  // Exact moments of the piecewise-linear density.
  double I = 0.0, m1 = 0.0, m2 = 0.0;
  for (std::size_t k = 0; k + 1 < z.size(); ++k) {
    const double a = z[k], b = z[k + 1], pa = density[k], pb = density[k + 1], h = b - a;
    I += 0.5 * h * (pa + pb);
    m1 += h / 6.0 * (pa * (2.0 * a + b) + pb * (a + 2.0 * b));
    m2 += h / 12.0 *
          (pa * (3.0 * a * a + 2.0 * a * b + b * b) + pb * (a * a + 2.0 * a * b + 3.0 * b * b));
  }
  if (!(I > 0.0)) fail("its density is zero everywhere");
  mean_ = m1 / I;
  const double var = m2 / I - mean_ * mean_;
  if (!(var > 0.0) || !std::isfinite(var))
    fail(fmt::format("its heights have no spread (variance {})", core::format_value(var)));
  sd_ = std::sqrt(var);
  // Runs of zero density at either end are outside the support: one zero node is kept.
  std::size_t k0 = 0, k1 = z.size() - 1;
  while (k0 + 1 < z.size() && density[k0] == 0.0 && density[k0 + 1] == 0.0) ++k0;
  while (k1 > 0 && density[k1] == 0.0 && density[k1 - 1] == 0.0) --k1;
  z_.reserve(k1 - k0 + 1);
  p_.reserve(k1 - k0 + 1);
  for (std::size_t k = k0; k <= k1; ++k) {
    z_.push_back((z[k] - mean_) / sd_);
    p_.push_back(density[k] * sd_ / I);
  }
  above_.assign(z_.size(), 0.0);
  for (std::size_t k = z_.size() - 1; k-- > 0;)
    above_[k] = above_[k + 1] + 0.5 * (z_[k + 1] - z_[k]) * (p_[k] + p_[k + 1]);
}

double SummitHeightTable::density(double z_star) const {
  if (!(z_star >= z_.front()) || !(z_star <= z_.back())) return 0.0;
  const auto it = std::upper_bound(z_.begin(), z_.end(), z_star);
  const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - z_.begin(), 1)) - 1;
  if (k + 1 >= z_.size()) return p_.back();
  const double t = (z_star - z_[k]) / (z_[k + 1] - z_[k]);
  return p_[k] + t * (p_[k + 1] - p_[k]);
}

double SummitHeightTable::survival(double z_star) const {
  if (z_star <= z_.front()) return 1.0;
  if (!(z_star < z_.back())) return 0.0;
  const auto it = std::upper_bound(z_.begin(), z_.end(), z_star);
  const auto k = static_cast<std::size_t>(it - z_.begin()) - 1;
  // The rest of piece k above z*, then every node above.
  const double pz = density(z_star);
  return above_[k + 1] + 0.5 * (z_[k + 1] - z_star) * (pz + p_[k + 1]);
}

std::vector<double> SummitHeightTable::nodes_between(double lo, double hi) const {
  const auto first = std::upper_bound(z_.begin(), z_.end(), lo);
  const auto last = std::lower_bound(z_.begin(), z_.end(), hi);
  return first < last ? std::vector<double>(first, last) : std::vector<double>{};
}

SummitHeightTable read_summit_height_table(const std::string& path) {
  const core::CsvTable t = core::read_csv_table(path);
  const core::CsvColumn* z = t.find("height");
  const core::CsvColumn* p = t.find("density");
  if (!p) p = t.find("count");
  if (!z || !p)
    throw InvalidInput(fmt::format(
        "\"{}\": a summit-height table has the columns height[unit] and density (or count), "
        "e.g. height[m],density[1/m]",
        path));
  return SummitHeightTable(t.si_values(*z, core::dim::length), p->values,
                           fmt::format("\"{}\"", path));
}

}  // namespace asperity::surface
