#pragma once
// Static friction coefficient of one asperity (Appendix B.2, Eq. B.10-B.13).
#include <optional>
#include <string_view>

namespace asperity::contact {

/// Constant (Bowden-Tabor / Burwell-Rabinowicz, B.10), Chang-Etsion-Bogy (B.11),
/// Kogut-Etsion (B.12), Brizmer-Kligerman-Etsion (B.13).
enum class FrictionLaw { cfc, ceb, ke, bke };

[[nodiscard]] std::string_view to_string(FrictionLaw law);
/// "cfc", "ceb", "ke" or "bke"; throws InvalidInput listing the allowed names.
[[nodiscard]] FrictionLaw parse_friction_law(std::string_view name);

/// Parameters of the friction laws that are not in the contact pair.
struct FrictionParameters {
  /// Constant friction coefficient of CFC, mu = s/H (B.10); > 0. Only CFC uses it.
  double mu_cfc = 0.3;
  /// CEB: depth of first yield over contact radius; 0.48 for nu = 0.3 (under B.13).
  double zeta = 0.48;

  void validate() const;
};

/// CFC friction coefficient from the shear strength s and hardness H of the softer
/// material (B.10).
[[nodiscard]] double cfc_coefficient(double shear_strength, double hardness);

/// mu at w = omega/omega_c > 0 (0 allowed for CFC). CEB gives 0 for w >= 1, KE for
/// w > 6.2 (SEED_NOTES.md). BKE uses B.13, mu = 0.26 coth(0.27 (w/delta_c)^0.46),
/// not the differently grouped Eq. 3.16.
[[nodiscard]] double friction_coefficient(FrictionLaw law, double w, double nu,
                                          const FrictionParameters& params = {});

/// The interference w in (0, 1) where the two branches of B.11's min() cross (a kink
/// of the CEB mu), if any.
[[nodiscard]] std::optional<double> ceb_branch_crossing(double nu, double zeta);

/// mu(w) * P(w)/P_c: the static friction force over P_c, finite (0) at w = 0 where
/// mu of CEB, KE and BKE diverges like w^-1/2. `normal_load_star` is P/P_c at w.
[[nodiscard]] double static_friction_star(FrictionLaw law, double w, double nu,
                                          double normal_load_star,
                                          const FrictionParameters& params = {});

namespace detail {
/// Unchecked mu for hot loops: w > 0 (any w >= 0 for CFC), parameters validated;
/// `delta_c` is BKE's constant (unused otherwise).
[[nodiscard]] double friction_coefficient(FrictionLaw law, double w, double nu, double delta_c,
                                          const FrictionParameters& params);
}  // namespace detail

}  // namespace asperity::contact
