#pragma once
// The bolt preloads on an interface whose normal law is the thesis's rough flat (Eq. 4.4:
// Greenwood-Williamson sum of the asperity model's elastic-plastic law), with an initial
// (mesoscale) gap per element, and the interface stiffnesses linearised about the result
// (docs/rough_contact.md, docs/structures.md).
//
// Static equilibrium of the reduced model with the bolts as pre-tension sections (as
// linear_prestress): K0 x - sum_e A_e p_e(g_e) q_e = sum_b F_b f_b, where q_e is element
// e's normal row of Q (its opening g = q.x), and p_e = K H P*(d_e) with the separation
// d_e = d_ref + (gap_e + q_e.x)/sigma. The reference d_ref is the separation carrying the
// mean pressure (sum of preloads over the interface area): a rigid normal translation of one
// side, free under pre-tension, absorbs any other choice. Tangentially the interface is
// frictionless while the bolts are tightened (the usual assumption: the preload builds up
// before any tangential load), and vibration starts from zero tangential traction.
#include <vector>

#include <Eigen/Dense>

#include "asperity/fem/reduced_model.hpp"
#include "asperity/surface/rough_flat.hpp"

namespace asperity::fem {

/// The rough surfaces of an interface (combined values, SI).
struct RoughSurfaceScales {
  double sigma = 0.0;           ///< combined rms roughness [m], > 0
  double pressure_scale = 0.0;  ///< K H [Pa], > 0: P* = p/(K H)
  double eta = 0.0;             ///< areal density of asperities [1/m^2], > 0
};

struct RoughPrestress {
  Eigen::VectorXd x;                     ///< reduced static displacement [m]
  Eigen::VectorXd pressure;              ///< nominal pressure per element [Pa]
  Eigen::VectorXd separation_star;       ///< d/sigma per element
  Eigen::VectorXd real_area_ratio;       ///< A_r/A0 per element
  Eigen::VectorXd normal_stiffness;      ///< unloading at the set, -dp/dg [Pa/m] per element
  Eigen::VectorXd tangential_stiffness;  ///< dQ_l/ddelta at 0 (rough flat) [Pa/m] per element
  double interface_load = 0.0;           ///< sum p A [N]
  double bolt_load = 0.0;                ///< sum of preloads [N]
  /// Nominal area of the elements in contact: at least one asperity expected in contact,
  /// eta A Phi(d) >= 1 (Phi: fraction of summits above the separation) [m^2].
  double contact_area = 0.0;
  std::vector<char> in_contact;    ///< per element, by the same rule
  double real_contact_area = 0.0;  ///< sum A_r [m^2]
  int iterations = 0;
  double residual = 0.0;  ///< |r| / |f| at the end
};

/// Elements with separation beyond the normal law's reach (no asperity in contact) carry no
/// pressure. `gap` is N values [m] (>= 0, finite; empty: no gap). Throws InvalidInput for
/// a gap of the wrong size or value, NumericalError (with the residual and what to try) when
/// Newton's method does not converge in 100 iterations.
[[nodiscard]] RoughPrestress rough_prestress(const ReducedModel& model,
                                             const surface::RoughFlat& flat,
                                             const RoughSurfaceScales& scales,
                                             const Eigen::VectorXd& gap);

}  // namespace asperity::fem
