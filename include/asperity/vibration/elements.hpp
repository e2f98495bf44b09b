#pragma once
// Nonlinear joint elements of the vibration layer. An element acts on the relative
// displacement u = T x of the structure (one row of T per element direction) and
// returns its force to the structure as T^T f.
//
// For harmonic balance (AFT) an element gives its steady periodic response to sampled
// displacements (and velocities) over one period: the force at each sample, its local
// tangent, and, for hysteretic elements, how the force depends on the displacement at
// earlier samples (the reversal or last-slip points). Hysteretic elements start from
// their virgin state at u = 0 (the assembled joint at rest), move to the first sample,
// run the period twice and keep the second pass: under Masing's rules (and for a
// slider) the second pass is periodic once the first has visited the extremes.
// Reversals are taken at the samples where the direction of motion changes (the AFT
// sampling of the path), so every force is a function of the sample values alone and
// its derivative with respect to them is exact.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/dynamics/case.hpp"
#include "asperity/dynamics/friction_model.hpp"
#include "asperity/hysteresis/backbone.hpp"
#include "asperity/hysteresis/odfalk_vingsbo.hpp"

namespace asperity::vibration {

/// d f_d(t_i) / d u_{d_src}(t_j): a force's dependence on the displacement at another
/// sample (j may equal i only through the history of a reversal, never for the local
/// tangent, which is in PeriodicResponse::du).
struct HistoryTerm {
  std::uint32_t i = 0;      ///< sample of the force
  std::uint32_t j = 0;      ///< sample of the displacement
  std::uint16_t d = 0;      ///< direction of the force
  std::uint16_t d_src = 0;  ///< direction of the displacement
  double value = 0.0;
};

/// The steady periodic response of an element over one period of N samples.
struct PeriodicResponse {
  Eigen::MatrixXd f;   ///< N x directions: force
  Eigen::MatrixXd du;  ///< N x directions^2: d f_d(t_i)/d u_e(t_i) in column d + D e
  Eigen::MatrixXd dv;  ///< N x directions^2: d f_d(t_i)/d v_e(t_i); empty unless velocity dependent
  std::vector<HistoryTerm> history;
};

/// A joint element.
class Element {
 public:
  virtual ~Element() = default;
  Element() = default;
  Element(const Element&) = default;
  Element& operator=(const Element&) = default;

  /// "rough_flat", "jenkins", "iwan4", "masing_table", "coulomb", "elastic_dry_friction_2d",
  /// "polynomial_stiffness", "cubic_damping", ... (make_odfalk_vingsbo_element's below).
  [[nodiscard]] virtual std::string type() const = 0;
  /// Number of directions (rows of T).
  [[nodiscard]] virtual std::size_t directions() const { return 1; }
  /// True if the force depends on the velocity (regularized Coulomb).
  [[nodiscard]] virtual bool velocity_dependent() const { return false; }
  /// Steady response to the samples u, v (N x directions each) of one period; the
  /// tangents (du, dv, history) only when `tangent`. Throws InvalidInput for a
  /// non-finite sample.
  virtual void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                                 PeriodicResponse& out) const = 0;
  /// Force at u reached from the virgin state by a monotone (proportional) push, and its
  /// tangent d f/d u (directions x directions): the static response of a quasi-static
  /// modal analysis. Velocity-dependent elements give zero.
  virtual void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                               Eigen::MatrixXd& K) const = 0;
  /// Tangent stiffness at rest (u = 0, virgin): the stuck joint of the linear modes.
  [[nodiscard]] virtual Eigen::MatrixXd initial_stiffness() const = 0;
  /// Largest force the element can carry along direction 0 (its slip limit; +inf when
  /// unbounded): for messages and scales.
  [[nodiscard]] virtual double slip_force() const = 0;
  /// False for a hysteretic law whose loops are not Masing's construction on its virgin
  /// curve (the Odfalk-Vingsbo law): the quasi-static modal estimate, which builds the energy
  /// per cycle from the static push by Masing's rules, refuses it.
  [[nodiscard]] virtual bool masing_from_virgin_curve() const { return true; }
  /// The fraction of a periodic response's samples `r` (from periodic_response) at which the
  /// element slips grossly (its force at the slip limit), or NaN for an element without a
  /// stuck state to leave (springs, dampers, regularized Coulomb) or not yet covered (the
  /// dry-friction elements): the start check of nonlinear modes and the interface maps.
  [[nodiscard]] virtual double gross_slip_fraction(const PeriodicResponse& r) const;
  /// The parameters in SI, for summaries.
  [[nodiscard]] virtual dynamics::SummaryObject describe() const = 0;
};

/// Any Masing backbone (SI: N against m) as an element: the rough flat at a preload,
/// Segalman's four-parameter Iwan model (exactly Masing), a Jenkins or a
/// Cattaneo-Mindlin backbone. Branch rules as hysteresis::Hysteresis (loop memory);
/// the tangent after a reversal at (x_r, Q_r) is Q_l'(|x - x_r|/2) at x and its negative
/// at x_r, plus the dependence of Q_r on earlier samples.
class MasingElement final : public Element {
 public:
  MasingElement(std::shared_ptr<const hysteresis::Backbone> backbone, std::string type,
                dynamics::SummaryObject parameters);
  [[nodiscard]] std::string type() const override { return type_; }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override;
  [[nodiscard]] double slip_force() const override { return backbone_->limit(); }
  [[nodiscard]] double gross_slip_fraction(const PeriodicResponse& r) const override;
  [[nodiscard]] dynamics::SummaryObject describe() const override { return parameters_; }
  [[nodiscard]] const hysteresis::Backbone& backbone() const { return *backbone_; }
  [[nodiscard]] std::shared_ptr<const hysteresis::Backbone> backbone_ptr() const {
    return backbone_;
  }

 private:
  std::shared_ptr<const hysteresis::Backbone> backbone_;
  std::string type_;
  dynamics::SummaryObject parameters_;
};

/// Jenkins element: spring k_t in series with a Coulomb slider of slip force F_s.
struct JenkinsParameters {
  double k_t = 0.0;  ///< [N/m], > 0
  double F_s = 0.0;  ///< [N], > 0
  void validate() const;
};
class JenkinsElement final : public Element {
 public:
  explicit JenkinsElement(JenkinsParameters p);
  [[nodiscard]] std::string type() const override { return "jenkins"; }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override;
  [[nodiscard]] double slip_force() const override { return p_.F_s; }
  [[nodiscard]] double gross_slip_fraction(const PeriodicResponse& r) const override;
  [[nodiscard]] dynamics::SummaryObject describe() const override;
  [[nodiscard]] const JenkinsParameters& parameters() const { return p_; }

 private:
  JenkinsParameters p_;
};

/// Regularized Coulomb friction, Eq. 7.3 in SI: f = F_s tanh(k_tan v).
struct CoulombParameters {
  double F_s = 0.0;    ///< [N], > 0
  double k_tan = 0.0;  ///< [s/m], > 0: the slope at v = 0 over F_s
  void validate() const;
};
class CoulombElement final : public Element {
 public:
  explicit CoulombElement(CoulombParameters p);
  [[nodiscard]] std::string type() const override { return "coulomb"; }
  [[nodiscard]] bool velocity_dependent() const override { return true; }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override;
  [[nodiscard]] double slip_force() const override { return p_.F_s; }
  [[nodiscard]] dynamics::SummaryObject describe() const override;

 private:
  CoulombParameters p_;
};

/// Elastic dry friction in two directions (tangential 0, normal 1): a normal contact
/// force f_n = max(N0 + k_n u_n, 0) (u_n > 0 presses the surfaces together; f_n = 0 is
/// separation) and a tangential spring k_t in series with a slider that slips at
/// mu f_n. In separation the tangential force is zero and the slider follows. The
/// preload N0 > 0 is carried by the bolt (outside the model): the structure receives the
/// normal force's change f_n - N0, so that u = 0 is the equilibrium at rest; with N0 = 0
/// (the default) the structure receives f_n itself. N0 < 0 is a gap g = -N0 / k_n: the
/// surfaces touch once u_n > g, and the structure receives f_n (zero at rest).
struct ElasticDryFriction2dParameters {
  double k_t = 0.0;  ///< [N/m], > 0
  double k_n = 0.0;  ///< [N/m], > 0
  double mu = 0.0;   ///< > 0
  double N0 = 0.0;   ///< [N], finite: normal force at u_n = 0 (> 0 a preload, < 0 a gap -N0/k_n)
  void validate() const;
};
class ElasticDryFriction2dElement final : public Element {
 public:
  explicit ElasticDryFriction2dElement(ElasticDryFriction2dParameters p);
  [[nodiscard]] std::string type() const override { return "elastic_dry_friction_2d"; }
  [[nodiscard]] std::size_t directions() const override { return 2; }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override;
  [[nodiscard]] double slip_force() const override;
  [[nodiscard]] dynamics::SummaryObject describe() const override;

 private:
  ElasticDryFriction2dParameters p_;
};

/// Polynomial stiffness (Duffing's when only k1 and k3 are given): f = sum_j k_j u^j,
/// j = 1 .. 3. Memoryless and odd or not as its coefficients are.
struct PolynomialStiffnessParameters {
  double k1 = 0.0;        ///< [N/m]
  double k2 = 0.0;        ///< [N/m^2]
  double k3 = 0.0;        ///< [N/m^3]
  void validate() const;  ///< finite, not all zero
};
class PolynomialStiffnessElement final : public Element {
 public:
  explicit PolynomialStiffnessElement(PolynomialStiffnessParameters p);
  [[nodiscard]] std::string type() const override { return "polynomial_stiffness"; }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override;
  [[nodiscard]] double slip_force() const override;
  [[nodiscard]] dynamics::SummaryObject describe() const override;

 private:
  PolynomialStiffnessParameters p_;
};

/// Cubic damping: f = c3 v^3.
struct CubicDampingParameters {
  double c3 = 0.0;  ///< [N s^3/m^3], finite, != 0
  void validate() const;
};
class CubicDampingElement final : public Element {
 public:
  explicit CubicDampingElement(CubicDampingParameters p);
  [[nodiscard]] std::string type() const override { return "cubic_damping"; }
  [[nodiscard]] bool velocity_dependent() const override { return true; }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override;
  [[nodiscard]] double slip_force() const override;
  [[nodiscard]] dynamics::SummaryObject describe() const override;

 private:
  CubicDampingParameters p_;
};

/// An element placed in a structure: u = T x (T: directions x dofs).
struct PlacedElement {
  std::shared_ptr<const Element> element;
  Eigen::MatrixXd T;
  std::string name;  ///< for messages and summaries ("element 1" when not given)
};

/// Factories with the elements' usual parameters.
[[nodiscard]] std::shared_ptr<const Element> make_jenkins_element(double k_t, double F_s);
[[nodiscard]] std::shared_ptr<const Element> make_iwan4_element(
    const dynamics::SegalmanIwanParameters& p);
[[nodiscard]] std::shared_ptr<const Element> make_coulomb_element(double F_s, double k_tan);
/// "masing_table": a backbone given as a table of force Q [N] against displacement x [m]
/// (hysteresis::TableBackbone: checked monotone and through the origin, monotone cubic
/// interpolation, constant beyond the last point) under Masing's rules.
[[nodiscard]] std::shared_ptr<const Element> make_masing_table_element(
    std::vector<double> x, std::vector<double> Q, const std::string& source = "table");
[[nodiscard]] std::shared_ptr<const Element> make_elastic_dry_friction_2d_element(
    const ElasticDryFriction2dParameters& p);
[[nodiscard]] std::shared_ptr<const Element> make_polynomial_stiffness_element(
    const PolynomialStiffnessParameters& p);
[[nodiscard]] std::shared_ptr<const Element> make_cubic_damping_element(double c3);
/// The rough flat (or any SI backbone) as an element; `parameters` describe it.
[[nodiscard]] std::shared_ptr<const Element> make_rough_flat_element(
    std::shared_ptr<const hysteresis::Backbone> backbone_si, dynamics::SummaryObject parameters);
/// "odfalk_vingsbo": the elastic-plastic tangential law of Eq. 3.10 (hysteresis::
/// OdfalkVingsboHysteresis): Masing's loop on `elastic_si` with the parallelogram of plastic
/// slip in series, Q_ty and k_p measured (docs/joints.md). Its steady response is where the
/// plastic flows of a period balance (found by shooting on the force at the largest elastic
/// displacement), with the exact derivative with respect to every sample; below Q_ty it is
/// the Masing element's response (to round-off). type() is `parameters`' "type" if given
/// (a case file's "rough_flat"), else "odfalk_vingsbo".
[[nodiscard]] std::shared_ptr<const Element> make_odfalk_vingsbo_element(
    std::shared_ptr<const hysteresis::Backbone> elastic_si,
    const hysteresis::OdfalkVingsboParameters& p, dynamics::SummaryObject parameters);

}  // namespace asperity::vibration
