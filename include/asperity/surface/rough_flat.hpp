#pragma once
// A nominally flat rough contact: Greenwood-Williamson summation of the asperity
// models of chapter 3 over Gaussian asperity heights (thesis chapter 4, Eq. 4.1-4.14,
// with the conventions and the Eq. 4.9-4.10 erratum of SEED_NOTES.md).
//
// Normalization (SEED_NOTES.md): lengths over sigma_s (rms of surface heights):
// d* = d/sigma_s, delta* = delta/sigma_s; forces over K H A0; energies over
// K H A0 sigma_s; stiffness over K H A0/sigma_s.
#include <memory>
#include <optional>
#include <vector>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/hysteresis/masing.hpp"

namespace asperity::surface {

/// How an asperity's slip displacement scales (Eq. 4.8).
enum class SlipScaling {
  /// Thesis Eq. 4.8: the elastic ratio a/P for every asperity, also plastic ones:
  /// delta~ = 4 G* delta*/(mu E* (z* - d*)). The default.
  elastic,
  /// Each law's own a(w) and P(w): delta~ = 16 G* a delta/(3 mu P).
  own_law,
};

/// Normalized inputs of a rough flat.
struct RoughFlatParameters {
  contact::ModelName model = contact::ModelName::bke;
  double beta = 0.0;      ///< sigma_s R eta; must exceed 0.01928 (sigma_a real)
  double psi = 0.0;       ///< plasticity index on sigma_a, (2E*/(pi K H)) sqrt(sigma_a/R); > 0
  double nu = 0.3;        ///< Poisson's ratio of the softer material, [0, 0.5)
  double G_over_E = 0.0;  ///< G*/E*, > 0 (0.2059 for identical materials with nu = 0.3)
  contact::FrictionParameters friction{};
  SlipScaling slip_scaling = SlipScaling::elastic;

  void validate() const;
};

/// SI scales of a rough flat built from dimensional inputs.
struct RoughFlatScales {
  double sigma = 0.0;  ///< rms surface height sigma_s [m]: the length scale
  double force = 0.0;  ///< K H A0 [N]: the force scale
  double A0 = 0.0;     ///< nominal area [m^2]
  double eta = 0.0;    ///< areal density of asperities [1/m^2]
  double R = 0.0;      ///< mean asperity radius [m]
  contact::ContactPair pair{};
};

class RoughFlatBackbone;

/// Sum of the asperity models over Gaussian asperity heights. Every member is const
/// and thread-safe; integrals are adaptive quadratures split at the asperity laws'
/// branch points and at each asperity slip boundary (relative accuracy ~1e-12).
class RoughFlat {
 public:
  explicit RoughFlat(const RoughFlatParameters& params);
  /// From a material pair (flat contact: R2 infinite in the pair is irrelevant here),
  /// combined roughness sigma [m], eta [1/m^2], R [m], and nominal area A0 [m^2].
  /// psi uses the asperity-height spread sigma_a (SEED_NOTES.md).
  static RoughFlat from_dimensional(const contact::Material& body1, const contact::Material& body2,
                                    double sigma, double eta, double R, double A0,
                                    contact::ModelName model,
                                    const contact::FrictionParameters& friction = {},
                                    SlipScaling scaling = SlipScaling::elastic);

  [[nodiscard]] const RoughFlatParameters& parameters() const { return params_; }
  [[nodiscard]] const std::optional<RoughFlatScales>& scales() const { return scales_; }
  [[nodiscard]] const contact::AsperityLaws& laws() const { return laws_; }
  /// sigma_a/sigma_s = sqrt(1 - 3.717e-4/beta^2) (below Eq. 4.2).
  [[nodiscard]] double sigma_a_over_sigma() const { return s_a_; }
  /// omega_c/sigma_s = (sigma_a/sigma_s)/psi^2 (Eq. 4.5 on sigma_a).
  [[nodiscard]] double omega_c_star() const { return omega_c_star_; }

  /// P/(K H A0) at separation d* (Eq. 4.4).
  [[nodiscard]] double normal_load_star(double d_star) const;
  /// The separation d* carrying P* = P/(K H A0) (Eq. 4.4 inverted); P* from 1e-12 up to
  /// the load at d* = -5 sigma_a/sigma_s. Throws InvalidInput beyond.
  [[nodiscard]] double separation_star(double P_star) const;
  /// Largest P* accepted by separation_star.
  [[nodiscard]] double max_load_star() const;
  /// Static friction Q_max/(K H A0) at d* (Eq. 4.7).
  [[nodiscard]] double static_friction_star(double d_star) const;
  /// Real contact area over A0: pi beta omega_c* Int (a/a_c)^2 phi* dz*.
  [[nodiscard]] double contact_area_ratio(double d_star) const;
  /// Fraction of all asperities in contact, Int_{d*}^inf phi* dz* (times eta A0: number).
  [[nodiscard]] double contact_fraction(double d_star) const;

  /// Virgin loading Q_l/(K H A0) at delta* >= 0 (Eq. 4.9-4.10 with the erratum: the
  /// slip state is decided per asperity from delta~).
  [[nodiscard]] double loading_force_star(double delta_star, double d_star) const;
  /// d Q*_l/d delta* at delta* >= 0.
  [[nodiscard]] double loading_stiffness_star(double delta_star, double d_star) const;
  /// Unloading from delta*_max (Eq. 4.11-4.12), delta* in [-delta*_max, delta*_max], by
  /// direct summation of every asperity's Mindlin-Deresiewicz unloading.
  [[nodiscard]] double unloading_force_star(double delta_star, double delta_max_star,
                                            double d_star) const;
  /// Reloading (Eq. 4.13): -unloading(-delta*).
  [[nodiscard]] double reloading_force_star(double delta_star, double delta_max_star,
                                            double d_star) const;
  /// Energy per cycle W/(K H A0 sigma_s) (Eq. 4.14) as the sum over asperities of each
  /// asperity's loop area (B.19, or its gross-slip form) - the loop integral of Eq. 4.14
  /// with the order of integration swapped.
  [[nodiscard]] double energy_star(double delta_max_star, double d_star) const;
  /// Tangential stiffness at every reversal, dQ*_l/d delta* at 0 (over K H A0/sigma_s).
  [[nodiscard]] double stiffness_star(double d_star) const;

  /// The tabulated backbone at separation d* (see RoughFlatBackbone); rel_tol is the
  /// verified bound on its relative error.
  [[nodiscard]] std::shared_ptr<const RoughFlatBackbone> backbone(double d_star,
                                                                  double rel_tol = 1e-9) const;

 private:
  RoughFlatParameters params_;
  std::optional<RoughFlatScales> scales_;
  contact::AsperityLaws laws_;
  double s_a_;
  double omega_c_star_;
  double prefactor_;  // (2 pi/3) beta omega_c*
};

/// The virgin loading curve Q*_l(delta*) of a rough flat at one separation, tabulated
/// once: Q_l = delta* G(sqrt(delta*)) with G a quintic Hermite interpolant, uniform in
/// s = sqrt(delta*) on segments between knots placed where Q_l is less smooth (a slip
/// boundary crossing a jump or extremum of the asperities' slip length); node values and
/// first and second derivatives come from one fixed-rule quadrature pass per node. The grid is
/// refined until the interpolant matches the quadrature at every interval midpoint to `rel_tol`
/// (the verified error bound); beyond the table's end Q_l equals Q_max to < 1e-12 relative.
/// Evaluation costs a square root, a segment search and a quintic (about one `tanh`;
/// through the Masing engine about twice a regularized Coulomb law, bench/).
class RoughFlatBackbone final : public hysteresis::Backbone {
 public:
  RoughFlatBackbone(const RoughFlat& flat, double d_star, double rel_tol = 1e-9);

  [[nodiscard]] double force(double delta_star) const override;
  [[nodiscard]] double displacement(double Q_star) const override;
  [[nodiscard]] double limit() const override { return Q_max_; }
  [[nodiscard]] double initial_stiffness() const override { return k0_; }
  [[nodiscard]] double integral(double delta_star) const override;

  [[nodiscard]] double d_star() const { return d_star_; }
  /// Largest relative difference between the table and the quadrature found at the
  /// check points (interval midpoints) when the table was built.
  [[nodiscard]] double verified_error() const { return verified_error_; }
  [[nodiscard]] std::size_t intervals() const { return n_; }
  [[nodiscard]] double table_end() const { return x_end_; }

 private:
  double d_star_;
  double Q_max_;
  double k0_;
  double x_end_;       // delta* where the table ends
  std::size_t n_ = 0;  // intervals over all segments
  struct Segment {     // uniform in s = sqrt(delta*) between two knots
    double s0;
    double h;
    double inv_h;
    std::size_t n;
    std::size_t offset;  // index of its first interval
  };
  [[nodiscard]] double partial_integral(const Segment& seg, std::size_t i, double fraction) const;
  [[nodiscard]] std::pair<const Segment*, double> locate(double s) const;

  std::vector<Segment> segments_;
  std::vector<double> coef_;  // quintic in t per interval: G(s) = Q_l/delta*, s = sqrt(delta*)
  std::vector<double> cumulative_;  // Int_0^{x_i} Q dx at nodes
  double verified_error_ = 0.0;
};

}  // namespace asperity::surface
