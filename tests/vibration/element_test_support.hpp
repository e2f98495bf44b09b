#pragma once
// Helpers shared by the vibration elements' tests.
#include <Eigen/Dense>

#include "asperity/dynamics/epb.hpp"
#include "asperity/vibration/elements.hpp"
#include "asperity/vibration/rough_contact.hpp"

namespace asperity::vibration::test_support {

/// The dense derivative d f_d(t_i) / d u_e(t_j) (row i + N d, column j + N e) from an
/// element's local tangent and history terms.
inline Eigen::MatrixXd dense_tangent(const PeriodicResponse& r, Eigen::Index N, Eigen::Index dirs) {
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(N * dirs, N * dirs);
  for (Eigen::Index i = 0; i < N; ++i) {
    for (Eigen::Index d = 0; d < dirs; ++d) {
      for (Eigen::Index e = 0; e < dirs; ++e) D(i + N * d, i + N * e) += r.du(i, d + dirs * e);
    }
  }
  for (const HistoryTerm& t : r.history) {
    D(static_cast<Eigen::Index>(t.i) + N * t.d, static_cast<Eigen::Index>(t.j) + N * t.d_src) +=
        t.value;
  }
  return D;
}

/// Table 7.2's rough surfaces (the thesis's chapter 7 contact) as an interface, BKE.
inline RoughInterfaceParameters table_7_2() {
  const dynamics::EpbContact c = dynamics::table_7_2_rough();
  return {.E_star = c.E_star,
          .G_star = c.G_star,
          .H = c.H,
          .nu = c.nu,
          .sigma = c.sigma,
          .R = c.R,
          .eta = c.eta,
          .model = contact::ModelName::bke,
          .friction = {}};
}

}  // namespace asperity::vibration::test_support
