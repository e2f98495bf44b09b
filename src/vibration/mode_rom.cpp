#include "asperity/vibration/mode_rom.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "asperity/core/error.hpp"

namespace asperity::vibration {

ModeRomCurve nonlinear_mode_rom(const HarmonicBalance& hb, const NonlinearModeResult& mode,
                                const Eigen::VectorXd& force,
                                const std::vector<Eigen::Index>& outputs, int subdivisions) {
  const Eigen::Index nu = hb.unknowns();
  if (force.size() != nu || !force.allFinite()) {
    throw InvalidInput(
        fmt::format("nonlinear_mode_rom: the force must hold {} finite coefficients (got {})", nu,
                    force.size()));
  }
  const auto np = static_cast<std::size_t>(mode.amplitude.size());
  if (subdivisions < 1 || subdivisions > 10000) {
    throw InvalidInput(fmt::format(
        "nonlinear_mode_rom.subdivisions = {}: give 1 .. 10000 points per backbone interval",
        subdivisions));
  }
  if (np == 0 || mode.harmonics.size() != np) {
    throw InvalidInput("nonlinear_mode_rom: the nonlinear mode has no points");
  }
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    if (outputs[k] < 0 || outputs[k] >= hb.dofs()) {
      throw InvalidInput(fmt::format("output_dofs[{}] = {}: DOFs are numbered 0 .. {}", k + 1,
                                     outputs[k], hb.dofs() - 1));
    }
  }
  const auto c1 = static_cast<std::size_t>(hb.basis().index_of(1, 0));
  const auto s1 = static_cast<std::size_t>(hb.basis().index_of(1, 1));
  double f1 = 0.0;
  for (Eigen::Index d = 0; d < hb.dofs(); ++d) {
    f1 = std::max(f1, std::hypot(force(hb.index(d, c1)), force(hb.index(d, s1))));
  }
  if (f1 == 0.0) {
    throw InvalidInput(
        "nonlinear_mode_rom: the force has no first harmonic (force_cos or "
        "force_sin of harmonic 1)");
  }
  for (std::size_t k = 0; k < np; ++k) {
    if (mode.harmonics[k].size() != nu) {
      throw InvalidInput(fmt::format(
          "nonlinear_mode_rom: the mode's harmonics have {} coefficients, the system {}",
          mode.harmonics[k].size(), nu));
    }
  }
  // The backbone between its points: omega, xi and Psi = U / a linear in log a
  // (subdivisions per interval), so that the peak is resolved between the EPMC's points.
  struct Point {
    double a, w, xi;
    Eigen::VectorXd psi;
  };
  std::vector<Point> pts;
  const auto at = [&](std::size_t k) {
    const auto i = static_cast<Eigen::Index>(k);
    return Point{mode.amplitude(i), mode.omega(i), mode.xi(i),
                 mode.harmonics[k] / mode.amplitude(i)};
  };
  for (std::size_t k = 0; k < np; ++k) {
    const Point p0 = at(k);
    pts.push_back(p0);
    if (k + 1 == np) break;
    const Point p1 = at(k + 1);
    for (int j = 1; j < subdivisions; ++j) {
      const double t = static_cast<double>(j) / subdivisions;
      pts.push_back({std::exp((1 - t) * std::log(p0.a) + t * std::log(p1.a)),
                     (1 - t) * p0.w + t * p1.w, (1 - t) * p0.xi + t * p1.xi,
                     (1 - t) * p0.psi + t * p1.psi});
    }
  }
  std::vector<double> a_low, w_low, a_high, w_high;
  std::vector<std::size_t> k_low, k_high;
  double peak = 0.0;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const Point& P = pts[k];
    const double a = P.a, w = P.w, xi = P.xi;
    // psi^H F = sum_d (Psi_c + i Psi_s)(F_c - i F_s).
    double re = 0.0, im = 0.0;
    for (Eigen::Index d = 0; d < hb.dofs(); ++d) {
      const double pc = P.psi(hb.index(d, c1)), ps = P.psi(hb.index(d, s1));
      const double fc = force(hb.index(d, c1)), fs = force(hb.index(d, s1));
      re += pc * fc + ps * fs;
      im += ps * fc - pc * fs;
    }
    const double g2 = (re * re + im * im) / (a * a);
    const double disc = g2 - xi * xi * (w * w - 0.25 * xi * xi);
    if (disc < 0.0) continue;  // beyond the peak: the force cannot drive this amplitude
    peak = std::max(peak, a);
    const double mid = w * w - 0.5 * xi * xi, root = std::sqrt(disc);
    if (mid - root > 0.0) {
      a_low.push_back(a);
      w_low.push_back(std::sqrt(mid - root));
      k_low.push_back(k);
    }
    if (mid + root > 0.0) {
      a_high.push_back(a);
      w_high.push_back(std::sqrt(mid + root));
      k_high.push_back(k);
    }
  }
  ModeRomCurve c;
  if (a_low.empty() && a_high.empty()) {
    c.warnings.push_back(fmt::format(
        "nonlinear_mode_rom: the force drives no amplitude of the backbone (a = {} .. {}): "
        "start the nonlinear mode's amplitude range lower or raise the force",
        pts.front().a, pts.back().a));
  } else if (peak == pts.back().a) {
    c.warnings.push_back(fmt::format(
        "nonlinear_mode_rom: the force drives the mode beyond the backbone's last amplitude "
        "(a = {}): the resonance is cut off; extend the nonlinear mode's amplitude range",
        peak));
  }
  const auto n = static_cast<Eigen::Index>(a_low.size() + a_high.size());
  const auto no = static_cast<Eigen::Index>(outputs.size());
  c.omega.resize(n);
  c.amplitude.resize(n);
  c.output_amplitude.resize(n, no);
  c.low_side_points = a_low.size();
  c.peak_amplitude = peak;
  const auto put = [&](Eigen::Index i, double a, double w, std::size_t k) {
    c.omega(i) = w;
    c.amplitude(i) = a;
    for (Eigen::Index o = 0; o < no; ++o) {
      c.output_amplitude(i, o) =
          hb.harmonic_amplitude(a * pts[k].psi, outputs[static_cast<std::size_t>(o)], 1);
    }
  };
  Eigen::Index i = 0;
  for (std::size_t j = 0; j < a_low.size(); ++j) put(i++, a_low[j], w_low[j], k_low[j]);
  for (std::size_t j = a_high.size(); j-- > 0;) put(i++, a_high[j], w_high[j], k_high[j]);
  return c;
}

}  // namespace asperity::vibration
