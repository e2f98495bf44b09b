#pragma once
// Contact elements of the vibration layer beyond the 2-D dry friction element: a
// unilateral spring with a gap or a preload, and dry friction in three directions (two
// tangential, one normal). Conventions as elements.hpp: u = T x, the force acts on the
// structure as T^T f, u_n > 0 presses the surfaces together.
#include <memory>
#include <string>

#include <Eigen/Dense>

#include "asperity/vibration/elements.hpp"

namespace asperity::vibration {

/// Unilateral spring: a contact force f_c = max(N0 + k (u - g), 0) (u > 0 closes the
/// contact). A gap g > 0 opens the contact at rest (the structure receives f_c, zero at
/// rest); a preload N0 > 0 closes it, carried by the bolt outside the model (the
/// structure receives f_c - N0, so that u = 0 is the equilibrium at rest, and -N0 in
/// separation). Memoryless: a piecewise-linear (bilinear) stiffness.
struct UnilateralSpringParameters {
  double k = 0.0;    ///< [N/m], > 0
  double gap = 0.0;  ///< [m], >= 0
  double N0 = 0.0;   ///< [N], >= 0; not together with gap > 0
  void validate() const;
};
class UnilateralSpringElement final : public Element {
 public:
  explicit UnilateralSpringElement(UnilateralSpringParameters p);
  [[nodiscard]] std::string type() const override { return "unilateral_spring"; }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override;
  [[nodiscard]] double slip_force() const override;
  [[nodiscard]] dynamics::SummaryObject describe() const override;
  [[nodiscard]] const UnilateralSpringParameters& parameters() const { return p_; }

 private:
  UnilateralSpringParameters p_;
};

[[nodiscard]] std::shared_ptr<const Element> make_unilateral_spring_element(
    const UnilateralSpringParameters& p);

/// Elastic dry friction in three directions (tangential t1 = 0, t2 = 1, normal n = 2): the
/// normal contact force f_n = max(N0 + k_n u_n, 0) as in ElasticDryFriction2dParameters
/// (a preload N0 > 0 carried outside the model, a gap -N0 / k_n when N0 < 0), and a 2-D
/// tangential spring k_t in series with an isotropic slider that slips at |f_t| = mu f_n.
/// At each sample the trial force f_t,prev + k_t (u_t - u_t,prev) is returned radially to
/// the circle of radius mu f_n when outside it (backward Euler of the associated flow
/// rule: the slip is along the force); in separation f_t = 0 and the slider follows.
/// The tangent is exact: the slip direction depends on the earlier samples through the
/// trial force, so d f_t(t_i) / d u(t_j) is carried forward sample by sample (a 2 x 3 N
/// sensitivity) and every non-zero entry for j != i is a history term; along a curved
/// slip path these are dense (up to 6 N per sample).
struct ElasticDryFriction3dParameters {
  double k_t = 0.0;  ///< [N/m], > 0
  double k_n = 0.0;  ///< [N/m], > 0
  double mu = 0.0;   ///< > 0
  double N0 = 0.0;   ///< [N], finite: normal force at u_n = 0 (> 0 a preload, < 0 a gap -N0/k_n)
  void validate() const;
};
class ElasticDryFriction3dElement final : public Element {
 public:
  explicit ElasticDryFriction3dElement(ElasticDryFriction3dParameters p);
  [[nodiscard]] std::string type() const override { return "elastic_dry_friction_3d"; }
  [[nodiscard]] std::size_t directions() const override { return 3; }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override;
  [[nodiscard]] double slip_force() const override;
  [[nodiscard]] dynamics::SummaryObject describe() const override;

 private:
  ElasticDryFriction3dParameters p_;
};

[[nodiscard]] std::shared_ptr<const Element> make_elastic_dry_friction_3d_element(
    const ElasticDryFriction3dParameters& p);

}  // namespace asperity::vibration
