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

}  // namespace asperity::vibration
