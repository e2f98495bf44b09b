#include "asperity/fem/gap_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::fem {

namespace {

// Grid coordinates agree when within this fraction of the spacing.
constexpr double kGridTolerance = 1e-6;

std::vector<double> distinct(const Eigen::VectorXd& v, double tol) {
  std::vector<double> s(v.data(), v.data() + v.size());
  std::sort(s.begin(), s.end());
  std::vector<double> out;
  for (double x : s)
    if (out.empty() || x - out.back() > tol) out.push_back(x);
  return out;
}

}  // namespace

GapMap read_gap_map(const std::string& path, const std::string& variable) {
  const Eigen::MatrixXd xyg = read_mat_matrix(path, variable);
  if (xyg.cols() != 3 || xyg.rows() < 4) {
    throw InvalidInput(
        fmt::format("\"{}\": {} must be P x 3 (x, y, gap) with P >= 4; it is {} x {}", path,
                    variable, xyg.rows(), xyg.cols()));
  }
  if (!xyg.leftCols(2).allFinite()) {
    throw InvalidInput(fmt::format("\"{}\": {} has a non-finite x or y", path, variable));
  }
  const double span = std::max(xyg.col(0).maxCoeff() - xyg.col(0).minCoeff(),
                               xyg.col(1).maxCoeff() - xyg.col(1).minCoeff());
  const auto xs = distinct(xyg.col(0), 1e-9 * span), ys = distinct(xyg.col(1), 1e-9 * span);
  GapMap m;
  m.source = path;
  m.nx = static_cast<Eigen::Index>(xs.size());
  m.ny = static_cast<Eigen::Index>(ys.size());
  if (m.nx < 2 || m.ny < 2 || m.nx * m.ny != xyg.rows()) {
    throw InvalidInput(fmt::format(
        "\"{}\": {} is not a full regular grid ({} distinct x, {} distinct y, {} points)", path,
        variable, m.nx, m.ny, xyg.rows()));
  }
  m.x0 = xs.front();
  m.y0 = ys.front();
  m.dx = (xs.back() - xs.front()) / static_cast<double>(m.nx - 1);
  m.dy = (ys.back() - ys.front()) / static_cast<double>(m.ny - 1);
  m.gap = Eigen::MatrixXd::Constant(m.nx, m.ny, std::numeric_limits<double>::quiet_NaN());
  Eigen::MatrixXi seen = Eigen::MatrixXi::Zero(m.nx, m.ny);
  for (Eigen::Index p = 0; p < xyg.rows(); ++p) {
    const double fi = (xyg(p, 0) - m.x0) / m.dx, fj = (xyg(p, 1) - m.y0) / m.dy;
    const auto i = static_cast<Eigen::Index>(std::llround(fi));
    const auto j = static_cast<Eigen::Index>(std::llround(fj));
    if (std::abs(fi - static_cast<double>(i)) > kGridTolerance ||
        std::abs(fj - static_cast<double>(j)) > kGridTolerance || seen(i, j)) {
      throw InvalidInput(
          fmt::format("\"{}\": {} is not a regular grid (point {} at x = {} m, "
                      "y = {} m)",
                      path, variable, p + 1, xyg(p, 0), xyg(p, 1)));
    }
    seen(i, j) = 1;
    const double g = xyg(p, 2);
    if (std::isinf(g) || g < 0.0) {
      throw InvalidInput(fmt::format(
          "\"{}\": {} point {}: gap = {} m; give a finite value >= 0 (NaN marks a hole)", path,
          variable, p + 1, core::format_value(g)));
    }
    m.gap(i, j) = g;
  }
  return m;
}

Eigen::VectorXd gap_at_elements(const GapMap& map, const ReducedModel& model,
                                const Eigen::Vector3d& origin) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(model.elements.size()));
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const Eigen::Vector3d c = model.elements[e].centroid - origin;
    const double fi = (c.x() - map.x0) / map.dx, fj = (c.y() - map.y0) / map.dy;
    const auto outside = [&](double f, Eigen::Index n) {
      return f < -0.5 || f > static_cast<double>(n) - 0.5;
    };
    if (!std::isfinite(fi) || !std::isfinite(fj) || outside(fi, map.nx) || outside(fj, map.ny)) {
      throw InvalidInput(fmt::format(
          "the gap map \"{}\" does not cover interface element {} (centroid at x = {:.6g} m, y = "
          "{:.6g} m from the map's origin; the map spans x {:.6g} .. {:.6g} m, y {:.6g} .. {:.6g} "
          "m): check gap_origin",
          map.source, e, c.x(), c.y(), map.x0, map.x0 + map.dx * static_cast<double>(map.nx - 1),
          map.y0, map.y0 + map.dy * static_cast<double>(map.ny - 1)));
    }
    const auto i0 =
        std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::floor(fi)), 0, map.nx - 2);
    const auto j0 =
        std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::floor(fj)), 0, map.ny - 2);
    const double u = std::clamp(fi - static_cast<double>(i0), 0.0, 1.0);
    const double v = std::clamp(fj - static_cast<double>(j0), 0.0, 1.0);
    const double w[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
    const double g[4] = {map.gap(i0, j0), map.gap(i0 + 1, j0), map.gap(i0, j0 + 1),
                         map.gap(i0 + 1, j0 + 1)};
    double sum = 0.0, wsum = 0.0, mean = 0.0;
    int valid = 0;
    for (int k = 0; k < 4; ++k) {
      if (std::isnan(g[k])) continue;
      sum += w[k] * g[k];
      wsum += w[k];
      mean += g[k];
      ++valid;
    }
    if (valid == 0) {
      throw InvalidInput(fmt::format(
          "the gap map \"{}\" has no surface (NaN) around interface element {} (centroid at x = "
          "{:.6g} m, y = {:.6g} m from the map's origin)",
          map.source, e, c.x(), c.y()));
    }
    out[static_cast<Eigen::Index>(e)] = valid == 4 ? sum : mean / valid;
  }
  return out;
}

}  // namespace asperity::fem
