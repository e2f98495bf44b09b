#pragma once
// A measured summit-height table passed from Python: an (n, 2) array of heights [m] and
// densities (any positive factor), as surface::SummitHeightTable.
#include <Eigen/Dense>

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/surface/summit_heights.hpp"

namespace asperity::python {

/// The table of `heights` (null when absent) and sigma [m]. With a table, sigma is its
/// standard deviation: None is set to it, a given one must equal it to 1e-9; summit_sigma
/// is then true.
inline std::shared_ptr<const surface::SummitHeightTable> summit_table_from(
    const std::optional<Eigen::MatrixXd>& heights, const std::optional<double>& sigma_given,
    double& sigma, bool& summit_sigma) {
  if (!heights) {
    if (!sigma_given) throw InvalidInput("sigma = None: give sigma [m] or summit_heights");
    sigma = *sigma_given;
    return nullptr;
  }
  if (heights->cols() != 2)
    throw InvalidInput(
        fmt::format("summit_heights is {} x {}: give an (n, 2) array of heights [m] and densities",
                    heights->rows(), heights->cols()));
  const Eigen::VectorXd z = heights->col(0), p = heights->col(1);
  auto table = std::make_shared<const surface::SummitHeightTable>(
      std::vector<double>(z.begin(), z.end()), std::vector<double>(p.begin(), p.end()),
      "summit_heights");
  const double sd = table->standard_deviation();
  if (sigma_given && !(std::abs(*sigma_given / sd - 1.0) <= 1e-9)) {
    throw InvalidInput(fmt::format(
        "sigma = {} m with summit_heights: the flat's length scale is the table's standard "
        "deviation, {} m; give that or sigma = None",
        core::format_value(*sigma_given), core::format_value(sd)));
  }
  sigma = sd;
  summit_sigma = true;
  return table;
}

/// A table as (n, 2) [m, 1/m]: the standardized one scaled back by sigma [m].
inline Eigen::MatrixXd summit_table_array(const surface::SummitHeightTable& t, double sigma) {
  const auto n = static_cast<Eigen::Index>(t.z_star().size());
  Eigen::MatrixXd a(n, 2);
  for (Eigen::Index k = 0; k < n; ++k) {
    a(k, 0) = t.z_star()[static_cast<std::size_t>(k)] * sigma;
    a(k, 1) = t.density_star()[static_cast<std::size_t>(k)] / sigma;
  }
  return a;
}

}  // namespace asperity::python
