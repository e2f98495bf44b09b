#include "asperity/vibration/contact_elements.hpp"

#include <algorithm>
#include <cmath>
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

}  // namespace asperity::vibration
