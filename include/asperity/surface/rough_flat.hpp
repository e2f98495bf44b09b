#pragma once
// A nominally flat rough contact: Greenwood-Williamson summation of the asperity
// models of chapter 3 over Gaussian asperity heights (thesis chapter 4, Eq. 4.1-4.14,
// with the conventions and the Eq. 4.9-4.10 erratum of SEED_NOTES.md).
//
// Normalization (SEED_NOTES.md): lengths over sigma_s (rms of surface heights):
// d* = d/sigma_s, delta* = delta/sigma_s; forces over K H A0; energies over
// K H A0 sigma_s; stiffness over K H A0/sigma_s.
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/hysteresis/masing.hpp"
#include "asperity/hysteresis/tabulated_backbone.hpp"
#include "asperity/surface/summit_heights.hpp"

namespace asperity::surface {

/// How an asperity's slip displacement scales (Eq. 4.8).
enum class SlipScaling {
  /// Thesis Eq. 4.8: the elastic ratio a/P for every asperity, also plastic ones:
  /// delta~ = 4 G* delta*/(mu E* (z* - d*)). The default.
  elastic,
  /// Each law's own a(w) and P(w): delta~ = 16 G* a delta/(3 mu P).
  own_law,
};

/// Smallest plasticity index accepted: below it omega_c* = (sigma_a/sigma_s)/psi^2 > 350,
/// no asperity yields, and the asperity friction laws of ch. 3 (whose mu grows without
/// bound as P/P_c -> 0) give mu of 10 and more (BKE at P* = 1e-3: 14 at psi = 0.05, 7.9
/// at 0.1, 49.9 at 0.01);
/// the thesis computes psi = 0.5 to 4.7 (Fig. 4.4-4.6, Table 5.4).
inline constexpr double kMinPlasticityIndex = 0.05;
/// Largest roughness parameter beta = sigma_s R eta accepted, 1/pi: the asperities within
/// one sigma_s of their summits would cover pi beta > 1 of the nominal area (cap area
/// pi R sigma_s each, eta per area), so they could not be the isolated asperities of the
/// Greenwood-Williamson sum. Engineering surfaces: 0.02-0.06 (thesis, below Eq. 4.2).
inline constexpr double kMaxRoughnessParameter = std::numbers::inv_pi;

/// Normalized inputs of a rough flat.
struct RoughFlatParameters {
  contact::ModelName model = contact::ModelName::bke;
  double beta = 0.0;      ///< sigma_s R eta; in (0.01928, 1/pi] (sigma_a real; isolated asperities)
  double psi = 0.0;       ///< plasticity index on sigma_a, (2E*/(pi K H)) sqrt(sigma_a/R); >= 0.05
  double nu = 0.3;        ///< Poisson's ratio of the softer material, [0, 0.5)
  double G_over_E = 0.0;  ///< G*/E*, in (0, 1) (0.2059 for identical materials, nu = 0.3)
  contact::FrictionParameters friction{};
  SlipScaling slip_scaling = SlipScaling::elastic;
  /// True when the length scale is the standard deviation of the summit heights itself
  /// (a measured summit distribution): sigma_a/sigma_s = 1, beta = sigma_a R eta in (0, 1/pi],
  /// no McCool relation (Eq. 4.2's sigma_a/sigma_s = sqrt(1 - 3.717e-4/beta^2) is for sigma_s
  /// the rms of the surface heights).
  bool summit_sigma = false;
  /// A measured summit-height density to sum over instead of Eq. 4.2's Gaussian (null:
  /// Gaussian). Needs summit_sigma: lengths are then over the table's standard deviation.
  std::shared_ptr<const SummitHeightTable> summit_heights;

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

/// A sentence when a friction coefficient mu = Q_max/P is above 3, more than any of the
/// thesis's computations (BKE at psi = 0.5, P* = 1e-3, Fig. 4.4: 2.0) or measurements
/// (0.33-0.35, ch. 5), else empty.
[[nodiscard]] std::string friction_coefficient_warning(double mu);

/// Sum of the asperity models over Gaussian asperity heights (Eq. 4.2), or over a measured
/// summit-height table (RoughFlatParameters::summit_heights). Every member is const
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

  /// The normalized flat of combined properties E*, G*, hardness H and nu of the softer body,
  /// rms roughness sigma [m], R [m] and eta [1/m^2] (no scales): beta = sigma R eta, psi on
  /// sigma_a (SEED_NOTES.md), G*/E*.
  /// With `summit_sigma`, sigma is the standard deviation of the summit heights
  /// (RoughFlatParameters::summit_sigma, as from_summit_heights).
  /// With `heights` (which needs summit_sigma), the sums run over that table, and sigma must
  /// be its standard deviation in metres.
  static RoughFlat from_combined(double E_star, double G_star, double H, double nu, double sigma,
                                 double R, double eta, contact::ModelName model,
                                 const contact::FrictionParameters& friction = {},
                                 bool summit_sigma = false,
                                 std::shared_ptr<const SummitHeightTable> heights = nullptr);

  /// As from_dimensional, with sigma_summits the standard deviation of the summit heights
  /// (RoughFlatParameters::summit_sigma): the form a measured summit distribution gives.
  /// With `heights`, the sums run over that table, and sigma_summits must be its standard
  /// deviation in metres.
  static RoughFlat from_summit_heights(const contact::Material& body1,
                                       const contact::Material& body2, double sigma_summits,
                                       double eta, double R, double A0, contact::ModelName model,
                                       const contact::FrictionParameters& friction = {},
                                       std::shared_ptr<const SummitHeightTable> heights = nullptr);

  [[nodiscard]] const RoughFlatParameters& parameters() const { return params_; }
  [[nodiscard]] const std::optional<RoughFlatScales>& scales() const { return scales_; }
  [[nodiscard]] const contact::AsperityLaws& laws() const { return laws_; }
  /// The measured summit-height table summed over, or null for the Gaussian of Eq. 4.2.
  [[nodiscard]] const SummitHeightTable* summit_heights() const {
    return params_.summit_heights.get();
  }
  /// sigma_a/sigma_s = sqrt(1 - 3.717e-4/beta^2) (below Eq. 4.2).
  [[nodiscard]] double sigma_a_over_sigma() const { return s_a_; }
  /// omega_c/sigma_s = (sigma_a/sigma_s)/psi^2 (Eq. 4.5 on sigma_a).
  [[nodiscard]] double omega_c_star() const { return omega_c_star_; }
  /// Where the inputs leave the range the thesis's laws were built for (accepted, but to
  /// be read with care): psi < 0.5 (the smallest plasticity index of ch. 4, Fig. 4.4) and
  /// beta > 0.06 (engineering surfaces: 0.02-0.06, below Eq. 4.2). One sentence each.
  [[nodiscard]] std::vector<std::string> warnings() const;

  /// P/(K H A0) at separation d* (Eq. 4.4).
  [[nodiscard]] double normal_load_star(double d_star) const;
  /// The separation d* carrying P* = P/(K H A0) (Eq. 4.4 inverted); P* from 1e-12 up to
  /// the load at d* = -5 sigma_a/sigma_s, and only while the real contact area stays below
  /// the nominal one (A_r < A0). Throws InvalidInput beyond.
  [[nodiscard]] double separation_star(double P_star) const;
  /// P* at d* = -5 sigma_a/sigma_s: no larger load is accepted by separation_star (which
  /// may refuse smaller ones too, where A_r/A0 >= 1).
  [[nodiscard]] double max_load_star() const;
  /// P/(K H A0) at separation d* of a flat first pressed to d_set* (its closest approach):
  /// every asperity that touched at d_set* unloads and reloads elastically from its plastic
  /// set, as a Hertzian contact with the contact radius a_m it had there (continuity of P
  /// and of dP/domega = 2 E* a at the set): P = P_m ((w - w_m + delta_u)/delta_u)^{3/2}
  /// while w > w_m - delta_u, with delta_u = (P_m/P_c)/(a_m/a_c) in omega_c (Eq. A.1-A.2's
  /// Hertz scales); asperities first touching closer than d_set* follow their virgin law.
  /// Equals normal_load_star(d*) at d* = d_set*, and everywhere for an elastic flat.
  [[nodiscard]] double normal_load_after_set_star(double d_star, double d_set_star) const;
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
  /// The backbone in SI at the preload P [N] of a flat built by from_dimensional: the
  /// tabulated backbone at d* = separation_star(P/(K H A0)) scaled to Q_l [N] of delta [m]
  /// (delta = delta* sigma_s, Q = Q* K H A0), for hysteresis::Hysteresis. Throws InvalidInput
  /// for a normalized flat (no scales) or a preload out of separation_star's range.
  [[nodiscard]] std::shared_ptr<const hysteresis::ScaledBackbone> backbone_at_preload(
      double P, double rel_tol = 1e-9) const;

 private:
  RoughFlatParameters params_;
  std::optional<RoughFlatScales> scales_;
  contact::AsperityLaws laws_;
  double s_a_;
  double omega_c_star_;
  double prefactor_;  // (2 pi/3) beta omega_c*
};

/// The virgin loading curve Q*_l(delta*) of a rough flat at one separation, tabulated
/// once (hysteresis::TabulatedBackbone: Q_l = delta* G(sqrt(delta*)), G piecewise quintic
/// Hermite, bisected until it matches the sum at every interval midpoint to `rel_tol`, the
/// verified error bound). Node values and first and second derivatives come from one
/// fixed-rule Gauss-Legendre pass over the asperity heights per node; knots sit where Q_l
/// is less smooth (a slip boundary crossing a jump or extremum of the asperities' slip
/// length); beyond the table's end Q_l equals Q_max to < 1e-12 relative. A force costs a
/// look-up by the bits of delta* and a quintic (bench/: 1.5 times a regularized Coulomb law
/// through the Masing engine).
class RoughFlatBackbone final : public hysteresis::TabulatedBackbone {
 public:
  RoughFlatBackbone(const RoughFlat& flat, double d_star, double rel_tol = 1e-9);

  [[nodiscard]] double d_star() const { return d_star_; }

 private:
  double d_star_;
};

}  // namespace asperity::surface
