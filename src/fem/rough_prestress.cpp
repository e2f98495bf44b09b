#include "asperity/fem/rough_prestress.hpp"

#include <fmt/format.h>

#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>
#include <cmath>
#include <limits>
#include <optional>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/parallel.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::fem {

namespace {

// ln P*(d*) tabulated 0.02 sigma apart (cubic B-spline: ~1e-9 relative in P*) from the
// flat's lowest separation (-5 sigma_a) to kOpenSeparation; beyond it no asperity is
// counted in contact (P* < 1e-17 there for every accepted flat).
constexpr double kStep = 0.02;
constexpr double kOpenSeparation = 9.0;
constexpr double kResidualTolerance = 1e-10;
constexpr int kMaxIterations = 100;

class LoadingLaw {
 public:
  explicit LoadingLaw(const surface::RoughFlat& flat)
      : d_min_(-5.0 * flat.sigma_a_over_sigma() * (1.0 - 1e-9)) {
    auto n = static_cast<std::size_t>(std::ceil((kOpenSeparation - d_min_) / kStep)) + 1;
    if (const auto* table = flat.summit_heights()) {
      // A measured table ends at its highest summit: the grid stops half a step below it
      // (P* there ~ (top - d*)^{7/2} as the density falls linearly to zero; 0 beyond).
      const double top = table->top() - 0.5 * kStep;
      if (!(top > d_min_ + 3.0 * kStep)) {
        throw InvalidInput(fmt::format(
            "rough prestress: the summit-height table's highest summit lies at z/sigma = {}, "
            "below the rough flat's lowest separation {}: it cannot be a measured surface's",
            table->top(), d_min_));
      }
      n = std::min(n, static_cast<std::size_t>(std::floor((top - d_min_) / kStep)) + 1);
    }
    std::vector<double> lnP(n);
    core::parallel_for(n, [&](std::size_t k) {
      const double P = flat.normal_load_star(d_min_ + static_cast<double>(k) * kStep);
      if (!(P > 0.0)) {
        throw NumericalError(fmt::format(
            "rough prestress: the rough flat carries no load at d/sigma = {} (the normal law's "
            "table ends at {})",
            d_min_ + static_cast<double>(k) * kStep, kOpenSeparation));
      }
      lnP[k] = std::log(P);
    });
    d_max_ = d_min_ + static_cast<double>(n - 1) * kStep;
    spline_ = std::make_unique<boost::math::interpolators::cardinal_cubic_b_spline<double>>(
        lnP.data(), lnP.size(), d_min_, kStep);
  }
  [[nodiscard]] double d_min() const { return d_min_; }
  /// P* and dP*/dd* at d* >= d_min (0 beyond the table).
  [[nodiscard]] std::pair<double, double> at(double d) const {
    if (d >= d_max_) return {0.0, 0.0};
    if (!(d >= d_min_)) {  // also NaN: the spline does not check its range
      throw NumericalError(fmt::format(
          "rough prestress: separation d/sigma = {} is outside the rough flat's range (>= {})", d,
          d_min_));
    }
    const double P = std::exp((*spline_)(d));
    return {P, P * spline_->prime(d)};
  }

 private:
  double d_min_;
  double d_max_ = 0.0;
  std::unique_ptr<boost::math::interpolators::cardinal_cubic_b_spline<double>> spline_;
};

}  // namespace

RoughPrestress rough_prestress(const ReducedModel& model, const surface::RoughFlat& flat,
                               const RoughSurfaceScales& scales, const Eigen::VectorXd& gap) {
  core::require_positive("rough prestress sigma", scales.sigma);
  core::require_positive("rough prestress pressure scale K H", scales.pressure_scale);
  core::require_positive("rough prestress eta", scales.eta);
  const Eigen::Index n = model.dofs();
  const auto ne = static_cast<Eigen::Index>(model.elements.size());
  if (ne == 0) throw InvalidInput("rough prestress: the reduced model has no interface element");
  if (gap.size() != 0 && gap.size() != ne) {
    throw InvalidInput(
        fmt::format("rough prestress: the gap map has {} values for {} elements", gap.size(), ne));
  }
  for (Eigen::Index e = 0; e < gap.size(); ++e) {
    if (!(std::isfinite(gap[e]) && gap[e] >= 0.0)) {
      throw InvalidInput(fmt::format(
          "rough prestress: gap of interface element {} = {} m: give a finite value >= 0", e,
          core::format_value(gap[e])));
    }
  }
  const double sigma = scales.sigma;
  const double KH = scales.pressure_scale;

  // Pre-tension sections (as linear_prestress).
  Eigen::MatrixXd K0 = model.K;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  RoughPrestress out;
  for (Eigen::Index b = 0; b < model.bolt_load.cols(); ++b) {
    const Eigen::RowVectorXd h = model.bolt_elongation.row(b);
    K0 -= model.bolt_axial_stiffness[b] * h.transpose() * h;
    f += model.bolt_preload[b] * model.bolt_load.col(b);
    out.bolt_load += model.bolt_preload[b];
  }
  if (!(out.bolt_load > 0.0)) {
    throw InvalidInput("rough prestress: the model has no bolt preload to press the interface");
  }
  Eigen::MatrixXd Qn(ne, n);
  Eigen::VectorXd area(ne);
  for (Eigen::Index e = 0; e < ne; ++e) {
    Qn.row(e) = model.Q.row(3 * e + 2);
    area[e] = model.elements[static_cast<std::size_t>(e)].area;
  }
  const LoadingLaw law(flat);
  const double p_mean = out.bolt_load / area.sum();
  const Eigen::VectorXd g0 = gap.size() == 0 ? Eigen::VectorXd::Zero(ne) : gap;
  // The reference separation: the undeformed interface (x = 0), moved rigidly along its
  // normal until it carries the bolt loads (the start of Newton's method).
  double d_ref = flat.separation_star(p_mean / KH);
  {
    const auto load_ratio = [&](double c) {
      double sum = 0.0;
      for (Eigen::Index e = 0; e < ne; ++e) sum += area[e] * law.at(c + g0[e] / sigma).first;
      return std::log(std::max(sum * KH / out.bolt_load, 1e-300));
    };
    const double lo = law.d_min() - g0.minCoeff() / sigma;
    // Where the undeformed interface cannot carry the loads within the flat's range (a gap
    // map much deeper than sigma), start with its lowest point one sigma above the range's
    // end: the bodies' deformation closes the rest in Newton's iterations.
    if (load_ratio(lo + 1.0) < 0.0) {
      d_ref = lo + 1.0;
    } else if (load_ratio(d_ref) < 0.0) {
      d_ref = core::find_root(load_ratio, lo + 1.0, d_ref, "reference separation", 50);
    }
  }

  // Rigid-body modes of the assembly (free-free): alpha M r r^T M regularises the Newton
  // matrix without changing the answer (the loads are self-equilibrated).
  Eigen::MatrixXd reg = Eigen::MatrixXd::Zero(n, n);
  {
    // A stiffness scale only: the rough flat's at the mean pressure.
    const double k_ref = KH / sigma * -law.at(flat.separation_star(p_mean / KH)).second;
    const Eigen::MatrixXd Kc = K0 + Qn.transpose() * (k_ref * area).asDiagonal() * Qn;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kc, model.M);
    const Eigen::VectorXd w2 = es.eigenvalues();
    const double tol = 1e-10 * std::abs(model.K.diagonal().sum()) / model.M.diagonal().sum();
    const double alpha = w2.cwiseAbs().maxCoeff() * 1e-3;
    for (Eigen::Index i = 0; i < w2.size(); ++i) {
      if (std::abs(w2[i]) <= tol) {
        const Eigen::VectorXd mr = model.M * es.eigenvectors().col(i);
        reg += alpha * mr * mr.transpose();
      }
    }
  }

  struct State {
    Eigen::VectorXd r, P, dP, d;
  };
  const auto evaluate = [&](const Eigen::VectorXd& x) -> std::optional<State> {
    State s;
    s.d = Eigen::VectorXd::Constant(ne, d_ref) + (g0 + Qn * x) / sigma;
    s.P.resize(ne);
    s.dP.resize(ne);
    for (Eigen::Index e = 0; e < ne; ++e) {
      if (s.d[e] < law.d_min()) return std::nullopt;  // pressed past the flat's range
      std::tie(s.P[e], s.dP[e]) = law.at(s.d[e]);
    }
    s.r = K0 * x - Qn.transpose() * (KH * area.cwiseProduct(s.P)) - f;
    return s;
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::optional<State> s = evaluate(x);
  const double f_norm = f.norm();
  for (out.iterations = 0;; ++out.iterations) {
    out.residual = s->r.norm() / f_norm;
    if (out.residual <= kResidualTolerance) break;
    if (out.iterations >= kMaxIterations) {
      throw NumericalError(fmt::format(
          "rough prestress: Newton's method did not converge in {} iterations (residual {:.3g} "
          "of the bolt loads); try a finer interface mesh (more patches) or check the gap map "
          "(a gap far larger than sigma leaves few elements to carry the bolts)",
          kMaxIterations, out.residual));
    }
    const Eigen::VectorXd kA = KH / sigma * area.cwiseProduct(-s->dP);
    const Eigen::MatrixXd J = K0 + Qn.transpose() * kA.asDiagonal() * Qn + reg;
    const auto ldlt = J.ldlt();
    Eigen::VectorXd dx = -ldlt.solve(s->r);
    dx -= ldlt.solve(J * dx + s->r);  // one refinement step
    double t = 1.0;
    for (;; t *= 0.5) {
      if (t < 1e-8) {
        throw NumericalError(fmt::format(
            "rough prestress: no step reduces the residual ({:.3g} of the bolt loads after {} "
            "iterations); check the gap map and the roughness",
            out.residual, out.iterations));
      }
      std::optional<State> trial = evaluate(x + t * dx);
      if (trial && trial->r.norm() < (1.0 - 1e-4 * t) * s->r.norm()) {
        x += t * dx;
        s = std::move(trial);
        break;
      }
    }
  }
  out.x = x;
  out.separation_star = s->d;
  out.pressure = KH * s->P;
  out.interface_load = area.dot(out.pressure);
  out.real_area_ratio = Eigen::VectorXd::Zero(ne);
  out.normal_stiffness = Eigen::VectorXd::Zero(ne);
  out.tangential_stiffness = Eigen::VectorXd::Zero(ne);
  // Linearised about the prestress: the unloading law's slope at the set (fourth-order
  // one-sided difference on the unloading side, as RoughContactElement) and the rough
  // flat's tangential stiffness at every reversal (Eq. 4.9 at delta = 0).
  core::parallel_for(static_cast<std::size_t>(ne), [&](std::size_t k) {
    const auto e = static_cast<Eigen::Index>(k);
    const double d = s->d[e];
    if (!(s->P[e] > 0.0)) return;
    const double hs = 0.025 / 16.0;
    double v[5];
    for (int j = 0; j < 5; ++j) v[j] = flat.normal_load_after_set_star(d + j * hs, d);
    const double slope =
        (-25.0 * v[0] + 48.0 * v[1] - 36.0 * v[2] + 16.0 * v[3] - 3.0 * v[4]) / (12.0 * hs);
    out.normal_stiffness[e] = -KH / sigma * slope;
    out.tangential_stiffness[e] = KH / sigma * flat.stiffness_star(d);
    out.real_area_ratio[e] = flat.contact_area_ratio(d);
  });
  out.in_contact.assign(static_cast<std::size_t>(ne), 0);
  for (Eigen::Index e = 0; e < ne; ++e) {
    if (scales.eta * area[e] * flat.contact_fraction(s->d[e]) >= 1.0) {
      out.in_contact[static_cast<std::size_t>(e)] = 1;
      out.contact_area += area[e];
    }
    out.real_contact_area += area[e] * out.real_area_ratio[e];
  }
  return out;
}

}  // namespace asperity::fem
