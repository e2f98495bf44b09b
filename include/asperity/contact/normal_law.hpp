#pragma once
// Normal load and contact radius of one spherical asperity against a rigid flat as
// functions of the dimensionless interference w = omega/omega_c (Appendix B.1).
#include <string_view>

namespace asperity::contact {

/// Load-interference laws: Hertz (B.1), Chang-Etsion-Bogy (B.2), Kogut-Etsion (B.3),
/// Brizmer-Kligerman-Etsion fully adhered (B.4).
enum class NormalLaw { hertz, ceb, ke, bke };

[[nodiscard]] std::string_view to_string(NormalLaw law);
/// "hertz", "ceb", "ke" or "bke"; throws InvalidInput listing the allowed names.
[[nodiscard]] NormalLaw parse_normal_law(std::string_view name);

/// Constants of the BKE fits (Brizmer et al., quoted under Eq. 3.5 and B.9). Valid
/// only where l_c > 0 and delta_c > 0, i.e. nu in about (0.118, 0.5).
struct BkeConstants {
  double l_c = 0.0;      ///< 8.88 nu - 10.13 (nu^2 + 0.089)
  double delta_c = 0.0;  ///< 6.82 nu - 7.83 (nu^2 + 0.0586)
  double alpha = 0.0;    ///< 0.174 + 0.08 nu
  double gamma = 0.0;    ///< 0.25 + 0.125 nu
  // Derived once, for the statistical sums' inner loops:
  double load_scale = 0.0;     ///< l_c / delta_c^{3/2} (B.4)
  double delta_c_alpha = 0.0;  ///< delta_c^alpha (B.4)
  double delta_c_gamma = 0.0;  ///< delta_c^gamma (B.8)
  /// Throws InvalidInput when nu gives l_c <= 0 or delta_c <= 0.
  static BkeConstants for_poisson(double nu);
};

/// P/P_c at w = omega/omega_c >= 0 (B.1-B.4). `nu` is used by BKE and KE (K in the
/// fourth KE branch, B.3 and SEED_NOTES.md).
[[nodiscard]] double normal_load_star(NormalLaw law, double w, double nu);

/// a/a_c at w = omega/omega_c >= 0 (B.5-B.8).
[[nodiscard]] double contact_radius_star(NormalLaw law, double w, double nu);

/// Inverse of normal_load_star: the interference w for a load P/P_c >= 0. CEB and KE
/// jump upward at their branch points (w = 1 for CEB; 1, 6, 110 for KE); a load
/// inside a jump returns the branch point (the smallest w whose load reaches P*).
/// Closed forms where they exist, TOMS 748 for BKE's plastic branch.
[[nodiscard]] double interference_star(NormalLaw law, double P_star, double nu);

namespace detail {
/// Unchecked forms for hot loops: w >= 0 and the constants already validated.
[[nodiscard]] double normal_load_star(NormalLaw law, double w, double K, const BkeConstants& bke);
[[nodiscard]] double contact_radius_star(NormalLaw law, double w, const BkeConstants& bke);
}  // namespace detail

}  // namespace asperity::contact
