#pragma once
// Materials of two bodies in contact and their combined properties (thesis Eq. 3.5,
// B.9; SEED_NOTES.md "Combined properties").
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace asperity::contact {

/// One body's elastic and plastic properties, SI units.
struct Material {
  double E = 0.0;   ///< Young's modulus [Pa], > 0
  double nu = 0.0;  ///< Poisson's ratio, in [0, 0.5)
  double G = 0.0;   ///< shear modulus [Pa]; 0 means "derive from E and nu", E/(2(1+nu))
  double H = 0.0;   ///< hardness [Pa]; 0 means "not given" (the other body is softer)

  /// Throws InvalidInput naming `name`.field, its value and the allowed range.
  void validate(std::string_view name = "material") const;
  /// G if given, else E/(2(1+nu)).
  [[nodiscard]] double shear_modulus() const;
};

/// Hardness factor K = 0.454 + 0.41 nu (Chang et al., Eq. 3.5).
[[nodiscard]] double hardness_factor(double nu);

/// Critical values at the inception of plastic yield (Eq. 3.5 / B.9).
struct CriticalValues {
  double omega_c = 0.0;  ///< critical interference [m]
  double a_c = 0.0;      ///< critical contact radius [m]
  double P_c = 0.0;      ///< critical normal load [N]
};

/// Throws InvalidInput unless E/3 <= G <= E/2: an isotropic elastic material has
/// G = E/(2(1 + nu)), and G <= E/2 is nu >= 0, G >= E/3 is nu <= 0.5. The message names
/// `G_name` and `E_name` (a flag or a field) with both values.
void require_shear_modulus_range(std::string_view G_name, double G, std::string_view E_name,
                                 double E);

/// Sentences for a contact whose hardness is far from any solid's relative to E*
/// (H/E* outside [1e-3, 0.2]: from lead to diamond-like coatings), where the asperity laws
/// of ch. 3 (fitted to metals) and their critical interference omega_c = (pi K H/(2E*))^2 R
/// (Eq. 3.5) leave their range; empty otherwise.
[[nodiscard]] std::vector<std::string> hardness_warnings(double H, double E_star);

/// Combined properties of a sphere-on-flat (or sphere-on-sphere) contact, SI units.
/// Hardness H and Poisson's ratio nu are those of the softer material.
struct ContactPair {
  double E_star = 0.0;  ///< combined Young's modulus 1/((1-nu1^2)/E1 + (1-nu2^2)/E2) [Pa]
  double G_star = 0.0;  ///< combined shear modulus 1/((2-nu1)/G1 + (2-nu2)/G2) [Pa]
  double R = 0.0;       ///< combined radius 1/(1/R1 + 1/R2) [m]
  double H = 0.0;       ///< hardness of the softer material [Pa]
  double nu = 0.0;      ///< Poisson's ratio of the softer material

  /// Combines two bodies of radii R1 and R2 (R2 = infinity for a flat). The softer
  /// material is the one with the smaller H; a body with H = 0 is taken as harder.
  static ContactPair combine(const Material& body1, const Material& body2, double R1,
                             double R2 = std::numeric_limits<double>::infinity());

  void validate() const;
  [[nodiscard]] double K() const { return hardness_factor(nu); }
  [[nodiscard]] CriticalValues critical() const;
};

}  // namespace asperity::contact
