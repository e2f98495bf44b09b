#include "asperity/vibration/loop_fit.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "asperity/core/error.hpp"
#include "asperity/dynamics/friction_model.hpp"
#include "asperity/hysteresis/backbones.hpp"

namespace asperity::vibration {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::size_t parameter_count(LoopModel m) {
  return m == LoopModel::jenkins ? 2 : 4;
}

// Natural parameters from the unconstrained ones z: log k, log F [, logit(-chi), log beta].
std::vector<double> natural(LoopModel m, const Eigen::VectorXd& z) {
  if (m == LoopModel::jenkins) return {std::exp(z[0]), std::exp(z[1])};
  return {std::exp(z[0]), std::exp(z[1]), -1.0 / (1.0 + std::exp(-z[2])), std::exp(z[3])};
}

// Backbone of the natural parameters (Jenkins: k_t, F_s; iwan4: K_T, F_S, chi, beta), or
// null when they are outside the model's domain.
std::unique_ptr<hysteresis::Backbone> backbone_of(LoopModel m, const std::vector<double>& p) {
  for (double v : p)
    if (!std::isfinite(v)) return nullptr;
  if (m == LoopModel::jenkins) {
    if (!(p[0] > 0.0 && p[1] > 0.0)) return nullptr;
    return std::make_unique<hysteresis::JenkinsBackbone>(p[0], p[1]);
  }
  const dynamics::SegalmanIwanParameters s{.F_S = p[1], .K_T = p[0], .chi = p[2], .beta = p[3]};
  try {
    s.validate();
  } catch (const InvalidInput&) {
    return nullptr;
  }
  return std::make_unique<dynamics::SegalmanBackbone>(s);
}

// Residuals Q - Q_model with each loop's mean removed (the force offset Q_c, a linear
// nuisance parameter, profiled out); false when the parameters are outside the domain.
bool residuals(LoopModel m, const std::vector<double>& p, const std::vector<MeasuredLoop>& loops,
               Eigen::VectorXd& r, std::vector<double>* offsets = nullptr) {
  const auto b = backbone_of(m, p);
  if (!b) return false;
  std::size_t k = 0;
  if (offsets) offsets->clear();
  for (const auto& loop : loops) {
    const auto q = masing_loop(*b, loop);
    double mean = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i) mean += loop.Q[i] - q[i];
    mean /= static_cast<double>(q.size());
    if (offsets) offsets->push_back(mean);
    for (std::size_t i = 0; i < q.size(); ++i)
      r[static_cast<Eigen::Index>(k++)] = loop.Q[i] - q[i] - mean;
  }
  return r.allFinite();
}

// Forward-difference Jacobian of the residuals in the variables x (natural or z), with
// map(x) giving the natural parameters.
template <class Map>
bool jacobian(LoopModel m, const Eigen::VectorXd& x, const Eigen::VectorXd& r0, const Map& map,
              const std::vector<MeasuredLoop>& loops, Eigen::MatrixXd& J) {
  Eigen::VectorXd r(r0.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xh = x;
    // Central differences, step 1e-6 relative (1e-6 absolute near 0): truncation error
    // ~1e-12 of the derivative on a smooth model, round-off ~1e-10.
    const double h = 1e-6 * std::max(1.0, std::abs(x[j]));
    xh[j] = x[j] + h;
    Eigen::VectorXd rp(r0.size());
    if (!residuals(m, map(xh), loops, rp)) return false;
    xh[j] = x[j] - h;
    if (!residuals(m, map(xh), loops, r)) {
      J.col(j) = (rp - r0) / h;  // one-sided at the domain's edge
      continue;
    }
    J.col(j) = (rp - r) / (2.0 * h);
  }
  return J.allFinite();
}

struct Result {
  Eigen::VectorXd z;
  double cost = kInf;
  std::size_t iterations = 0;
};

// Levenberg-Marquardt on z (Marquardt's scaling by diag(J^T J)).
Result levenberg_marquardt(LoopModel m, Eigen::VectorXd z, const std::vector<MeasuredLoop>& loops,
                           std::size_t n) {
  const auto map = [m](const Eigen::VectorXd& v) { return natural(m, v); };
  Eigen::VectorXd r(static_cast<Eigen::Index>(n));
  Result out;
  if (!residuals(m, map(z), loops, r)) return out;
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  Eigen::MatrixXd J(static_cast<Eigen::Index>(n), z.size());
  std::size_t it = 0;
  for (; it < 300; ++it) {
    if (!jacobian(m, z, r, map, loops, J)) break;
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 30 && !improved; ++tries) {
      Eigen::MatrixXd Al = A;
      for (Eigen::Index j = 0; j < z.size(); ++j) Al(j, j) += lambda * std::max(A(j, j), 1e-30);
      const Eigen::VectorXd step = Al.ldlt().solve(-g);
      if (!step.allFinite()) {
        lambda *= 10.0;
        continue;
      }
      const Eigen::VectorXd zn = z + step;
      Eigen::VectorXd rn(r.size());
      if (residuals(m, map(zn), loops, rn) && rn.squaredNorm() < cost) {
        const double reduction = (cost - rn.squaredNorm()) / cost;
        z = zn;
        r = rn;
        cost = rn.squaredNorm();
        lambda = std::max(lambda / 10.0, 1e-12);
        improved = true;
        // Converged: the cost no longer changes beyond round-off, or the step is tiny.
        if (reduction < 1e-14 || step.norm() < 1e-12 * (1.0 + z.norm())) {
          out = {z, cost, it + 1};
          return out;
        }
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) break;  // no step lowers the cost: a minimum to the resolution
  }
  out = {z, cost, it};
  return out;
}

double half_range(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return 0.5 * (*hi - *lo);
}

// The slope dQ/dx right after the reversals: least squares over the points of each
// branch within 10 % of the force range of its start.
double reversal_slope(const std::vector<MeasuredLoop>& loops) {
  double sxx = 0.0, sxy = 0.0;
  for (const auto& l : loops) {
    const double span = 2.0 * half_range(l.Q);
    for (int branch = 0; branch < 2; ++branch) {
      const std::size_t b = branch == 0 ? 0 : l.unloading;
      const std::size_t e = branch == 0 ? l.unloading : l.Q.size();
      const double x0 = l.delta[b], q0 = l.Q[b];
      for (std::size_t i = b; i < e; ++i) {
        if (std::abs(l.Q[i] - q0) > 0.1 * span) break;
        sxx += (l.delta[i] - x0) * (l.delta[i] - x0);
        sxy += (l.delta[i] - x0) * (l.Q[i] - q0);
      }
    }
  }
  return sxx > 0.0 && sxy > 0.0 ? sxy / sxx : 0.0;
}

}  // namespace

LoopModel parse_loop_model(std::string_view text, std::string_view field) {
  if (text == "jenkins") return LoopModel::jenkins;
  if (text == "iwan4") return LoopModel::iwan4;
  throw InvalidInput(fmt::format("{} = \"{}\" is not allowed: use jenkins or iwan4", field, text));
}

std::string_view to_string(LoopModel m) {
  return m == LoopModel::jenkins ? "jenkins" : "iwan4";
}

void MeasuredLoop::validate() const {
  const std::string name = source.empty() ? std::string("loop") : source;
  if (delta.size() != Q.size()) {
    throw InvalidInput(
        fmt::format("{}: {} displacements but {} forces", name, delta.size(), Q.size()));
  }
  if (unloading < 5 || Q.size() < unloading + 5) {
    throw InvalidInput(fmt::format(
        "{}: a loop needs at least 5 points on each branch (unloading {}, reloading {})", name,
        unloading, Q.size() >= unloading ? Q.size() - unloading : 0));
  }
  for (std::size_t i = 0; i < Q.size(); ++i) {
    if (!std::isfinite(delta[i]) || !std::isfinite(Q[i]))
      throw InvalidInput(fmt::format("{}: point {} is not finite", name, i + 1));
  }
  if (!(half_range(delta) > 0.0) || !(half_range(Q) > 0.0))
    throw InvalidInput(fmt::format("{}: the loop has no displacement or force range", name));
}

std::vector<double> masing_loop(const hysteresis::Backbone& b, const MeasuredLoop& loop) {
  const auto [lo, hi] = std::minmax_element(loop.delta.begin(), loop.delta.end());
  const double x_top = *hi, x_bot = *lo, a = 0.5 * (x_top - x_bot);
  const double Qa = b.force(a);
  std::vector<double> q(loop.delta.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double x = loop.delta[i];
    q[i] = i < loop.unloading ? Qa - 2.0 * b.force(0.5 * (x_top - x))
                              : -Qa + 2.0 * b.force(0.5 * (x - x_bot));
  }
  return q;
}

double LoopFit::value(std::string_view name) const {
  for (const auto& p : parameters)
    if (p.name == name) return p.value;
  throw InvalidInput(fmt::format("the {} fit has no parameter {}", to_string(model), name));
}

std::shared_ptr<const Element> LoopFit::element() const {
  if (model == LoopModel::jenkins) return make_jenkins_element(value("k_t"), value("F_s"));
  return make_iwan4_element(
      {.F_S = value("F_S"), .K_T = value("K_T"), .chi = value("chi"), .beta = value("beta")});
}

std::string LoopFit::case_toml() const {
  std::string t = fmt::format(
      "# {} fit of {} loop{} ({} points): rms residual {:.4g} N ({:.3g} % of the mean half "
      "peak-to-peak force)\n[[element]]\ntype = \"{}\"\nT = [[1.0]]  # set: one row per direction, "
      "one column per DOF\n",
      to_string(model), loops, loops == 1 ? "" : "s", points, residual_rms,
      100.0 * relative_residual, to_string(model));
  for (const auto& p : parameters) {
    const std::string se =
        std::isfinite(p.standard_error)
            ? fmt::format("+- {:.3g}{}", p.standard_error, p.unit.empty() ? "" : " " + p.unit)
            : std::string("not determined by these loops");
    if (p.unit.empty()) {
      t += fmt::format("{} = {:.10g}  # {}\n", p.name, p.value, se);
    } else {
      t += fmt::format("{} = \"{:.10g} {}\"  # {}\n", p.name, p.value, p.unit, se);
    }
  }
  return t;
}

LoopFit fit_loops(const std::vector<MeasuredLoop>& loops, LoopModel model) {
  if (loops.empty()) throw InvalidInput("no loop to fit");
  std::size_t n = 0;
  double Qmax = 0.0, Qmean = 0.0;
  for (const auto& l : loops) {
    l.validate();
    n += l.Q.size();
    Qmax = std::max(Qmax, half_range(l.Q));
    Qmean += half_range(l.Q) / static_cast<double>(loops.size());
  }
  const std::size_t np = parameter_count(model);
  if (n <= np + loops.size()) {
    throw InvalidInput(fmt::format("{} points cannot determine {} parameters and {} offsets", n, np,
                                   loops.size()));
  }
  double k0 = reversal_slope(loops);
  if (!(k0 > 0.0)) {
    double amax = 0.0;
    for (const auto& l : loops) amax = std::max(amax, half_range(l.delta));
    k0 = 2.0 * Qmax / amax;
  }
  std::vector<Eigen::VectorXd> starts;
  if (model == LoopModel::jenkins) {
    for (double f : {1.0, 1.3}) starts.push_back(Eigen::Vector2d(std::log(k0), std::log(f * Qmax)));
  } else {
    for (double chi : {-0.2, -0.5, -0.8})
      for (double beta : {0.03, 0.3})
        for (double f : {1.02, 1.5}) {
          Eigen::Vector4d z(std::log(k0), std::log(f * Qmax), std::log(-chi / (1.0 + chi)),
                            std::log(beta));
          starts.push_back(z);
        }
  }
  Result best;
  for (const auto& z0 : starts) {
    auto r = levenberg_marquardt(model, z0, loops, n);
    if (r.cost < best.cost) best = r;
  }
  if (!std::isfinite(best.cost)) {
    throw NumericalError(fmt::format(
        "the {} fit did not converge from any of its {} starts (Levenberg-Marquardt from the "
        "reversal slope {:.4g} N/m and the largest half peak-to-peak force {:.4g} N)",
        to_string(model), starts.size(), k0, Qmax));
  }
  const auto p = natural(model, best.z);
  LoopFit fit;
  fit.model = model;
  fit.points = n;
  fit.loops = loops.size();
  fit.iterations = best.iterations;
  Eigen::VectorXd r(static_cast<Eigen::Index>(n));
  residuals(model, p, loops, r, &fit.Q_offsets);
  fit.residual_rms = std::sqrt(r.squaredNorm() / static_cast<double>(n));
  fit.relative_residual = fit.residual_rms / Qmean;
  // Covariance in the natural parameters: s^2 (J^T J)^-1 with the Jacobian in them.
  Eigen::VectorXd x(static_cast<Eigen::Index>(np));
  for (std::size_t j = 0; j < np; ++j) x[static_cast<Eigen::Index>(j)] = p[j];
  const auto identity = [](const Eigen::VectorXd& v) {
    return std::vector<double>(v.data(), v.data() + v.size());
  };
  Eigen::MatrixXd J(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(np));
  std::vector<double> se(np, kInf);
  // Scaled to unit columns so that the condition number judges identifiability, not units.
  if (jacobian(model, x, r, identity, loops, J)) {
    Eigen::VectorXd scale = J.colwise().norm().transpose();
    bool ok = (scale.array() > 0.0).all();
    if (ok) {
      const Eigen::MatrixXd Js = J * scale.cwiseInverse().asDiagonal();
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js, Eigen::ComputeThinV);
      const auto& sv = svd.singularValues();
      const Eigen::MatrixXd& V = svd.matrixV();
      const double dof = static_cast<double>(n - np - loops.size());
      const double s2 = r.squaredNorm() / dof;
      // cov = s^2 V S^-2 V^T over the directions the data determine. A singular value below
      // 1e-10 of the largest is at the Jacobian's own error (central differences, ~1e-10
      // relative): its direction is not determined, and so is every parameter with a
      // share in it (standard error infinite).
      for (std::size_t j = 0; j < np; ++j) {
        const auto jj = static_cast<Eigen::Index>(j);
        double var = 0.0;
        bool determined = true;
        for (Eigen::Index k = 0; k < sv.size(); ++k) {
          if (sv[k] <= 1e-10 * sv[0]) {
            if (std::abs(V(jj, k)) > 1e-6) determined = false;
            continue;
          }
          var += V(jj, k) * V(jj, k) / (sv[k] * sv[k]);
        }
        if (determined) se[j] = std::sqrt(s2 * var) / scale[jj];
      }
    }
  }
  if (model == LoopModel::iwan4) {
    // At a bound of the domain (chi -> 0 or -1, beta -> 0) the optimum is on the boundary,
    // where the Gauss-Newton covariance does not apply: not determined.
    if (p[2] > -1e-9 || p[2] < -1.0 + 1e-9) se[2] = kInf;
    if (p[3] < 1e-9) se[3] = kInf;
  }
  if (model == LoopModel::jenkins) {
    fit.parameters = {{"k_t", "N/m", p[0], se[0]}, {"F_s", "N", p[1], se[1]}};
  } else {
    fit.parameters = {{"F_S", "N", p[1], se[1]},
                      {"K_T", "N/m", p[0], se[0]},
                      {"chi", "", p[2], se[2]},
                      {"beta", "", p[3], se[3]}};
  }
  const auto b = backbone_of(model, p);
  for (std::size_t k = 0; k < loops.size(); ++k) {
    auto q = masing_loop(*b, loops[k]);
    for (auto& v : q) v += fit.Q_offsets[k];
    fit.Q_model.push_back(std::move(q));
  }
  return fit;
}

}  // namespace asperity::vibration
