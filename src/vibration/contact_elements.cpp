#include "asperity/vibration/contact_elements.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <fmt/format.h>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::vibration {

// ---------------------------------------------------------------------------------------
// Unilateral spring

void UnilateralSpringParameters::validate() const {
  core::require_positive("unilateral_spring.k", k);
  core::require_finite("unilateral_spring.gap", gap);
  core::require_finite("unilateral_spring.N0", N0);
  if (gap < 0.0) {
    throw InvalidInput(fmt::format(
        "unilateral_spring.gap = {} m is negative: give a gap >= 0 (a closed contact at rest "
        "is a preload N0 > 0)",
        gap));
  }
  if (N0 < 0.0) {
    throw InvalidInput(fmt::format(
        "unilateral_spring.N0 = {} N is negative: give a preload >= 0 (an open contact at rest "
        "is a gap > 0)",
        N0));
  }
  if (gap > 0.0 && N0 > 0.0) {
    throw InvalidInput(fmt::format(
        "unilateral_spring: gap = {} m and N0 = {} N both given: the contact is either open at "
        "rest (gap) or preloaded (N0), give one",
        gap, N0));
  }
}

UnilateralSpringElement::UnilateralSpringElement(UnilateralSpringParameters p) : p_(p) {
  p_.validate();
}

void UnilateralSpringElement::periodic_response(const Eigen::MatrixXd& u,
                                                const Eigen::MatrixXd& /*v*/, bool tangent,
                                                PeriodicResponse& out) const {
  if (!u.allFinite()) throw InvalidInput("element displacement samples hold a NaN or infinity");
  out.f.setZero(u.rows(), 1);
  out.history.clear();
  out.dv.resize(0, 0);
  if (tangent) {
    out.du.setZero(u.rows(), 1);
  } else {
    out.du.resize(0, 0);
  }
  for (Eigen::Index i = 0; i < u.rows(); ++i) {
    const double fc = p_.N0 + p_.k * (u(i, 0) - p_.gap);
    out.f(i, 0) = std::max(fc, 0.0) - p_.N0;
    if (tangent && fc > 0.0) out.du(i, 0) = p_.k;
  }
}

void UnilateralSpringElement::static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                                              Eigen::MatrixXd& K) const {
  core::require_finite("element displacement", u(0));
  const double fc = p_.N0 + p_.k * (u(0) - p_.gap);
  f = Eigen::VectorXd::Constant(1, std::max(fc, 0.0) - p_.N0);
  K = Eigen::MatrixXd::Constant(1, 1, fc > 0.0 ? p_.k : 0.0);
}

Eigen::MatrixXd UnilateralSpringElement::initial_stiffness() const {
  return Eigen::MatrixXd::Constant(1, 1, p_.N0 > 0.0 ? p_.k : 0.0);
}

double UnilateralSpringElement::slip_force() const {
  return std::numeric_limits<double>::infinity();
}

dynamics::SummaryObject UnilateralSpringElement::describe() const {
  return {{"type", "unilateral_spring"}, {"k_N_per_m", p_.k}, {"gap_m", p_.gap}, {"N0_N", p_.N0}};
}

std::shared_ptr<const Element> make_unilateral_spring_element(const UnilateralSpringParameters& p) {
  return std::make_shared<UnilateralSpringElement>(p);
}

// ---------------------------------------------------------------------------------------
// Elastic dry friction in three directions

void ElasticDryFriction3dParameters::validate() const {
  core::require_positive("elastic_dry_friction_3d.k_t", k_t);
  core::require_positive("elastic_dry_friction_3d.k_n", k_n);
  core::require_positive("elastic_dry_friction_3d.mu", mu);
  core::require_finite("elastic_dry_friction_3d.N0", N0);
}

ElasticDryFriction3dElement::ElasticDryFriction3dElement(ElasticDryFriction3dParameters p) : p_(p) {
  p_.validate();
}

void ElasticDryFriction3dElement::periodic_response(const Eigen::MatrixXd& u,
                                                    const Eigen::MatrixXd& /*v*/, bool tangent,
                                                    PeriodicResponse& out) const {
  if (!u.allFinite()) throw InvalidInput("element displacement samples hold a NaN or infinity");
  if (u.cols() != 3) {
    throw InvalidInput(fmt::format(
        "elastic_dry_friction_3d acts on 3 directions (t1, t2, normal), got {}", u.cols()));
  }
  const Eigen::Index n = u.rows();
  out.f.setZero(n, 3);
  out.history.clear();
  out.dv.resize(0, 0);
  if (tangent) {
    out.du.setZero(n, 9);
    out.history.reserve(static_cast<std::size_t>(6 * n * n));  // dense on a curved slip path
  } else {
    out.du.resize(0, 0);
  }
  if (n == 0) return;
  const double kt = p_.k_t, kn = p_.k_n, mu = p_.mu;
  const double preload = std::max(p_.N0, 0.0);  // carried by the bolt; none with a gap
  // S(d, j + N e) = d f_t,d / d u_e(t_j) of the current tangential force (the same sample
  // j in both passes is one unknown).
  Eigen::MatrixXd S;
  if (tangent) S.setZero(2, 3 * n);
  Eigen::Vector2d ft = Eigen::Vector2d::Zero(), ut_prev = Eigen::Vector2d::Zero();
  Eigen::Index prev = -1;  // the virgin state u = 0 before the first sample
  for (Eigen::Index step = 0; step < 2 * n; ++step) {
    const Eigen::Index i = step % n;
    const Eigen::Vector2d ut(u(i, 0), u(i, 1));
    const double fn_trial = p_.N0 + kn * u(i, 2);
    const bool contact = fn_trial > 0.0;
    const double fn = contact ? fn_trial : 0.0;
    if (!contact) {
      ft.setZero();
      if (tangent) S.setZero();
    } else {
      const Eigen::Vector2d trial = ft + kt * (ut - ut_prev);
      if (tangent) {
        for (Eigen::Index d = 0; d < 2; ++d) {
          S(d, i + n * d) += kt;
          if (prev >= 0) S(d, prev + n * d) -= kt;
        }
      }
      const double norm = trial.norm();
      if (norm >= mu * fn) {
        // Radial return: f_t = mu f_n e, e = trial / |trial|;
        // d f_t = mu k_n e d u_n + (mu f_n / |trial|) (I - e e^T) d trial.
        const Eigen::Vector2d e = trial / norm;
        ft = mu * fn * e;
        if (tangent) {
          const Eigen::Matrix2d P =
              (mu * fn / norm) * (Eigen::Matrix2d::Identity() - e * e.transpose());
          for (Eigen::Index c = 0; c < S.cols(); ++c) {  // S = P S, in place
            const double a = S(0, c), b = S(1, c);
            S(0, c) = P(0, 0) * a + P(0, 1) * b;
            S(1, c) = P(1, 0) * a + P(1, 1) * b;
          }
          S.col(i + 2 * n) += mu * kn * e;
        }
      } else {
        ft = trial;
      }
    }
    ut_prev = ut;
    prev = i;
    if (step < n) continue;
    out.f(i, 0) = ft(0);
    out.f(i, 1) = ft(1);
    out.f(i, 2) = fn - preload;
    if (!tangent) continue;
    if (contact) out.du(i, 2 + 3 * 2) = kn;
    const auto ui = static_cast<std::uint32_t>(i);
    for (Eigen::Index e = 0; e < 3; ++e) {
      for (Eigen::Index d = 0; d < 2; ++d) out.du(i, d + 3 * e) = S(d, i + n * e);
      for (Eigen::Index j = 0; j < n; ++j) {
        if (j == i) continue;
        for (Eigen::Index d = 0; d < 2; ++d) {
          const double value = S(d, j + n * e);
          if (value != 0.0) {
            out.history.push_back({ui, static_cast<std::uint32_t>(j), static_cast<std::uint16_t>(d),
                                   static_cast<std::uint16_t>(e), value});
          }
        }
      }
    }
  }
}

void ElasticDryFriction3dElement::static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                                                  Eigen::MatrixXd& K) const {
  for (Eigen::Index d = 0; d < 3; ++d) core::require_finite("element displacement", u(d));
  f = Eigen::VectorXd::Zero(3);
  K = Eigen::MatrixXd::Zero(3, 3);
  const double preload = std::max(p_.N0, 0.0);
  f(2) = -preload;
  const double fn = p_.N0 + p_.k_n * u(2);
  if (fn <= 0.0) return;
  f(2) = fn - preload;
  K(2, 2) = p_.k_n;
  const Eigen::Vector2d trial = p_.k_t * u.head<2>();
  const double norm = trial.norm();
  if (norm >= p_.mu * fn) {
    const Eigen::Vector2d e = trial / norm;
    f.head<2>() = p_.mu * fn * e;
    K.topLeftCorner<2, 2>() =
        (p_.mu * fn / norm) * p_.k_t * (Eigen::Matrix2d::Identity() - e * e.transpose());
    K.block<2, 1>(0, 2) = p_.mu * p_.k_n * e;
  } else {
    f.head<2>() = trial;
    K.topLeftCorner<2, 2>() = p_.k_t * Eigen::Matrix2d::Identity();
  }
}

Eigen::MatrixXd ElasticDryFriction3dElement::initial_stiffness() const {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3, 3);
  if (p_.N0 > 0.0) {
    K(0, 0) = K(1, 1) = p_.k_t;
    K(2, 2) = p_.k_n;
  }
  return K;
}

double ElasticDryFriction3dElement::slip_force() const {
  return p_.mu * std::max(p_.N0, 0.0);
}

dynamics::SummaryObject ElasticDryFriction3dElement::describe() const {
  return {{"type", "elastic_dry_friction_3d"},
          {"k_t_N_per_m", p_.k_t},
          {"k_n_N_per_m", p_.k_n},
          {"mu", p_.mu},
          {"N0_N", p_.N0}};
}

std::shared_ptr<const Element> make_elastic_dry_friction_3d_element(
    const ElasticDryFriction3dParameters& p) {
  return std::make_shared<ElasticDryFriction3dElement>(p);
}

}  // namespace asperity::vibration
