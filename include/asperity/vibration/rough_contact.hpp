#pragma once
// The thesis's rough flat as the contact law of a zero-thickness interface element in three
// directions (t1, t2 tangential, n normal; docs/rough_contact.md has the equations and the
// assumptions):
//
//  - normal: the Greenwood-Williamson sum of the asperity model's elastic-plastic normal law
//    (Eq. 4.4, appendix B) loads the element to its prestress separation d0; vibration then
//    unloads and reloads every asperity elastically from the plastic set the prestress left
//    (RoughFlat::normal_load_after_set_star); asperities first touching closer than d0 load
//    along their virgin law; past the last asperity the element separates (zero traction);
//  - tangential: in each tangential direction, Masing's rules with loop memory on the rough
//    flat's virgin tangential curve (Eq. 4.9-4.13) at the element's current normal pressure:
//    a branch from the reversal (x_r, Q_r) is Q_r + 2 Q_l(|x - x_r|/2; p(t)); the traction
//    vector is then limited to the rough flat's static friction at p(t) (Eq. 4.7; radial
//    return: it slips along the direction of its trial value).
//
// At constant normal load and motion along one direction this is exactly today's rough flat
// element (the same table, the same Masing memory). The normal pressure enters the
// tangential law as a family of tabulated backbones over ln p shared by the elements of one
// interface, interpolated with cubic Lagrange weights, with the element's own table at its
// prestress pressure exact: Q_l(x; p) = p [T0(x)/p0 + I(x; ln p) - I(x; ln p0)].
#include <memory>
#include <string>
#include <vector>

#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/fem/reduced_model.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "asperity/vibration/elements.hpp"

namespace asperity::vibration {

/// The two rough surfaces of an interface, as combined values (SI).
struct RoughInterfaceParameters {
  double E_star = 0.0;  ///< combined Young's modulus E* [Pa], > 0
  double G_star = 0.0;  ///< combined shear modulus G* [Pa], in (0, E*)
  double H = 0.0;       ///< hardness of the softer material [Pa], in (0, E*)
  double nu = 0.3;      ///< Poisson's ratio of the softer material, [0, 0.5)
  double sigma = 0.0;   ///< combined rms roughness [m], > 0
  double R = 0.0;       ///< mean asperity radius [m], > 0
  double eta = 0.0;     ///< areal density of asperities [1/m^2], > 0
  contact::ModelName model = contact::ModelName::bke;
  contact::FrictionParameters friction{};
  /// sigma is the standard deviation of the summit heights (a measured summit distribution,
  /// RoughFlatParameters::summit_sigma), not the surface's rms roughness.
  bool summit_sigma = false;
  /// A measured summit-height table to sum over instead of the Gaussian (null: Gaussian);
  /// needs summit_sigma, with sigma its standard deviation [m].
  std::shared_ptr<const surface::SummitHeightTable> summit_heights;
  void validate() const;
};

/// An interface's rough flat per unit nominal area and its tangential tables over the normal
/// pressure. Immutable after construction; shared by the interface's elements.
class RoughContactSurface {
 public:
  /// Tables from p_low to p_high [Pa] (0 < p_low < p_high, p_high at most the flat's largest
  /// load), log-spaced 2^(1/8) apart from p_low up (at least 4), or ending at p_high when
  /// the last would pass the flat's largest load (the first then lies below p_low). Below p_low the
  /// tangential curve's shape is the one at p_low, scaled with p (to zero at separation); above
  /// p_high an element throws.
  RoughContactSurface(const RoughInterfaceParameters& params, double p_low, double p_high);

  [[nodiscard]] const RoughInterfaceParameters& parameters() const { return params_; }
  [[nodiscard]] const surface::RoughFlat& flat() const { return flat_; }
  /// K H [Pa]: pressures over it are the flat's P* (forces over K H A0).
  [[nodiscard]] double pressure_scale() const { return pressure_scale_; }
  [[nodiscard]] double sigma() const { return params_.sigma; }
  [[nodiscard]] double p_low() const { return p_low_; }
  [[nodiscard]] double p_high() const { return p_high_; }

  /// Table k (0 .. count-1) at ln p* = ln_p_first + k h, its p* and Q*_max/p*.
  [[nodiscard]] std::size_t tables() const { return tables_.size(); }
  [[nodiscard]] const surface::RoughFlatBackbone& table(std::size_t k) const { return *tables_[k]; }
  [[nodiscard]] double table_pressure_star(std::size_t k) const { return p_star_[k]; }
  [[nodiscard]] double ln_p_first() const { return ln_p_first_; }
  [[nodiscard]] double ln_p_step() const { return h_; }

 private:
  RoughInterfaceParameters params_;
  surface::RoughFlat flat_;
  double pressure_scale_;
  double p_low_, p_high_;
  double ln_p_first_ = 0.0, h_ = 0.0;
  std::vector<std::shared_ptr<const surface::RoughFlatBackbone>> tables_;
  std::vector<double> p_star_;
};

/// One zero-thickness element with the rough contact law; directions t1, t2, n (u_n > 0
/// presses the surfaces together). u = 0 is the prestressed state: the structure receives
/// the tangential tractions and the normal force's change from the prestress, times the area.
class RoughContactElement final : public Element {
 public:
  /// area [m^2] > 0; pressure: the prestress normal pressure [Pa] in [p_low, p_high] of the
  /// surface; name for messages (e.g. "interface element 12").
  RoughContactElement(std::shared_ptr<const RoughContactSurface> surface, double area,
                      double pressure, std::string name);
  [[nodiscard]] std::string type() const override { return "rough_contact"; }
  [[nodiscard]] std::size_t directions() const override { return 3; }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override;
  [[nodiscard]] double slip_force() const override;
  /// Samples with the tangential traction at Q_max(p) of the sample's pressure (Eq. 4.7);
  /// open samples (p <= 0) do not count.
  [[nodiscard]] double gross_slip_fraction(const PeriodicResponse& r) const override;
  [[nodiscard]] dynamics::SummaryObject describe() const override;

  /// The prestress pressure p0 [Pa] and the nominal area [m^2]; the element's normal force
  /// (its third direction) is the change from p0 A.
  [[nodiscard]] double prestress_pressure() const { return p0_; }
  [[nodiscard]] double area() const { return area_; }
  [[nodiscard]] const RoughContactSurface& surface() const { return *surface_; }

  /// Normal pressure over K H (p*) at closure u_n [m] from the prestress, and dp*/dy* with
  /// y* = u_n / sigma (both dimensionless; p* K H is the pressure in Pa).
  struct Pressure {
    double p = 0.0;
    double dp = 0.0;
  };
  [[nodiscard]] Pressure pressure(double u_n) const;
  /// The prestress separation d0 over sigma and the element's exact table there.
  [[nodiscard]] double d0_star() const { return d0_star_; }
  [[nodiscard]] const surface::RoughFlatBackbone& prestress_table() const { return *table0_; }

  /// Q*_l(x*; p*) and its derivatives in x* and p* (star: over K H A, lengths over sigma).
  struct Tangential {
    double Q = 0.0, Qx = 0.0, Qp = 0.0;
  };
  [[nodiscard]] Tangential tangential_star(double x_star, double p_star) const;
  /// Q*_max(p*) and dQ*_max/dp*.
  [[nodiscard]] Tangential limit_star(double p_star) const;

 private:
  struct Stencil {
    std::size_t k0 = 0;
    double w[4] = {0, 0, 0, 0};
    double dw[4] = {0, 0, 0, 0};  // d w / d ln p
  };
  [[nodiscard]] Stencil stencil(double p_star) const;
  // The tables one pressure combines, the prestress stencil's subtracted: at p*,
  // F(x) = T0(x)/p0* + sum_j a_j T_k(j)(x) and dF/d ln p = sum_j b_j T_k(j)(x).
  struct Blend {
    std::size_t n = 0;
    std::size_t k[8] = {};
    double a[8] = {};
    double b[8] = {};
  };
  [[nodiscard]] Blend blend(double p_star) const;
  [[nodiscard]] Tangential tangential_at(double x_star, double p_star, const Blend& b) const;
  [[nodiscard]] Tangential limit_at(double p_star, const Blend& b) const;

  std::shared_ptr<const RoughContactSurface> surface_;
  double area_;
  double p0_;       // [Pa]
  double p0_star_;  // p0 / (K H)
  double d0_star_;
  std::string name_;
  std::shared_ptr<const surface::RoughFlatBackbone> table0_;
  Stencil stencil0_;
  // Normal: P*(d*) after the prestress set, on d* in [d_lo, d_hi]; 0 beyond d_hi.
  std::shared_ptr<const boost::math::interpolators::cardinal_cubic_b_spline<double>> compression_,
      unloading_;
  double d_lo_ = 0.0, d_hi_ = 0.0;
  double p_ref_star_ = 0.0;  // the sum at d0 (differs from p0* by separation_star's tolerance)
};

/// The rough interface of a reduced model (its [rough_contact] record) as rough-contact
/// elements: one per interface element in contact at the rough prestress (at least one
/// asperity expected in contact and a pressure > 0), directions t1, t2, -n (T from the rows
/// of Q: tangential, then the closure), all on one surface with tables from p_min/8 to
/// 8 p_max (at most 0.999 of the largest load the rough flat represents).
struct InterfaceRoughContact {
  std::vector<PlacedElement> elements;
  std::vector<Eigen::Index> interface_elements;  ///< the model's element of each, ascending
};

/// `name` names the placed elements ("NAME E"), `what` the elements' messages ("WHAT
/// (interface element E)"). Throws InvalidInput when the model has no [rough_contact]
/// record or none of its elements is in contact.
[[nodiscard]] InterfaceRoughContact interface_rough_contact(
    const fem::ReducedModel& model, contact::ModelName asperity_model,
    const contact::FrictionParameters& friction, const std::string& name, const std::string& what);

}  // namespace asperity::vibration
