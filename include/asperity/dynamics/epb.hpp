#pragma once
// The physics-based (EPB) friction law of section 7.3 from Table 7.2-style inputs: the
// rough flat's backbone (surface/rough_flat.hpp) in SI units, ready for
// make_physics_based(backbone, k, A).
#include <memory>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/contact/friction_law.hpp"
#include "asperity/hysteresis/masing.hpp"

namespace asperity::dynamics {

/// Combined properties and roughness as Table 7.2 gives them (SI units).
struct EpbContact {
  double E_star = 106e9;   ///< combined Young's modulus E* [Pa]
  double G_star = 22.9e9;  ///< combined shear modulus G* [Pa]
  double H = 5.8e9;        ///< hardness of the softer material [Pa]
  double nu = 0.3;         ///< Poisson's ratio of the softer material
  double sigma = 2.7e-6;   ///< combined rms roughness [m]
  double R = 30.1e-6;      ///< mean asperity radius [m]
  double eta = 2.9e8;      ///< areal density of asperities [1/m^2]
  double A0 = 0.0;         ///< nominal contact area [m^2] (Table 7.2 gives none)
  double P = 0.0;          ///< normal load [N]
  contact::ModelName model = contact::ModelName::bke;  ///< asperity law (BKE: section 7.3)
  contact::FrictionParameters friction{};
  void validate() const;
};

/// Table 7.2's rough and smooth roughness parameters (A0 and P left for the caller).
[[nodiscard]] EpbContact table_7_2_rough();
[[nodiscard]] EpbContact table_7_2_smooth();

/// The rough flat's virgin loading curve Q(delta) [N over m]: beta = sigma R eta,
/// psi = (2E*/(pi K H)) sqrt(sigma_a/R) on the asperity-height spread (SEED_NOTES.md),
/// G*/E*; the separation carrying P; the tabulated backbone scaled by sigma and K H A0.
[[nodiscard]] std::shared_ptr<const hysteresis::Backbone> epb_backbone(const EpbContact& c);

}  // namespace asperity::dynamics
