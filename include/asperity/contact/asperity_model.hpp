#pragma once
// The four physics-based partial slip models of section 3.3: a normal law and a
// friction law fed into Cattaneo-Mindlin (Fig. 3.5). CFC pairs with Hertz; CEB, KE
// and BKE pair with their own normal law.
#include <array>
#include <string_view>
#include <vector>

#include "asperity/contact/friction_law.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/contact/mindlin.hpp"
#include "asperity/contact/normal_law.hpp"

namespace asperity::contact {

enum class ModelName { cfc, ceb, ke, bke };
inline constexpr std::array<ModelName, 4> kAllModels{ModelName::cfc, ModelName::ceb, ModelName::ke,
                                                     ModelName::bke};

[[nodiscard]] std::string_view to_string(ModelName m);
/// "cfc", "ceb", "ke" or "bke"; throws InvalidInput listing the allowed names.
[[nodiscard]] ModelName parse_model_name(std::string_view name);
[[nodiscard]] NormalLaw normal_law_of(ModelName m);
[[nodiscard]] FrictionLaw friction_law_of(ModelName m);

/// Which normal state (interference omega, contact radius a) a model is evaluated at.
///  - own: each model's own normal law (CFC: Hertz) gives omega and a; P as given
///    (or from the law, for a given omega*).
///  - hertz: Hertz's laws (B.1, B.5) give omega and a for every model, which then
///    contributes only its friction coefficient mu(omega*). This is the thesis's
///    reading of Table 3.2 ("the penetration for all the models is estimated to be
///    2.77 um", section 3.5, and K_T = 8 G* a = 16.17 N/um for all).
enum class InterferenceReading { own, hertz };
[[nodiscard]] std::string_view to_string(InterferenceReading r);
/// "own" or "hertz"; throws InvalidInput listing the allowed names.
[[nodiscard]] InterferenceReading parse_interference_reading(std::string_view name);

/// A model's asperity laws in dimensionless form, validated once: P/P_c, a/a_c and mu
/// as functions of w = omega/omega_c.
class AsperityLaws {
 public:
  AsperityLaws(ModelName model, double nu, const FrictionParameters& params = {});

  [[nodiscard]] ModelName model() const { return model_; }
  [[nodiscard]] double nu() const { return nu_; }
  [[nodiscard]] const FrictionParameters& friction_parameters() const { return params_; }
  [[nodiscard]] double load_star(double w) const;               ///< P/P_c (B.1-B.4)
  [[nodiscard]] double radius_star(double w) const;             ///< a/a_c (B.5-B.8)
  [[nodiscard]] double mu(double w) const;                      ///< B.10-B.13
  [[nodiscard]] double interference_star(double P_star) const;  ///< inverse of load_star
  /// P/P_c and mu together at w > 0 (finite, not checked): the statistical sums' inner
  /// loop. BKE shares one logarithm between B.4 and B.13.
  struct LoadAndFriction {
    double load_star;
    double mu;
  };
  [[nodiscard]] LoadAndFriction load_and_mu(double w) const;
  /// Interferences w where the laws switch branch (kinks or jumps of P, a or mu):
  /// CEB 1; KE 1, 6, 6.2, 110; BKE delta_c; none for CFC/Hertz. Quadratures split here.
  [[nodiscard]] std::vector<double> break_points() const;

 private:
  ModelName model_;
  double nu_;
  FrictionParameters params_;
  double K_;
  BkeConstants bke_{};
};

/// A sphere under a constant normal load with one of the four models: the normal
/// state (omega, a, P), mu, and its Cattaneo-Mindlin tangential response.
class PartialSlipModel {
 public:
  /// From a normal load P [N] > 0, which stays as given. With the own reading, inside
  /// a jump of the CEB or KE load law the interference is the branch point (see
  /// interference_star); with the hertz reading omega and a are Hertz's for P.
  static PartialSlipModel from_load(const ContactPair& pair, ModelName model, double P,
                                    const FrictionParameters& params = {},
                                    InterferenceReading reading = InterferenceReading::own);
  /// From the dimensionless interference omega* = omega/omega_c > 0; P and a follow
  /// from the model's normal law (own) or from Hertz's (hertz).
  static PartialSlipModel from_interference_star(
      const ContactPair& pair, ModelName model, double omega_star,
      const FrictionParameters& params = {},
      InterferenceReading reading = InterferenceReading::own);

  [[nodiscard]] ModelName model() const { return laws_.model(); }
  [[nodiscard]] InterferenceReading reading() const { return reading_; }
  [[nodiscard]] const ContactPair& pair() const { return pair_; }
  [[nodiscard]] const CriticalValues& critical() const { return critical_; }
  [[nodiscard]] double omega_star() const { return omega_star_; }
  [[nodiscard]] double omega() const { return omega_star_ * critical_.omega_c; }  ///< [m]
  [[nodiscard]] double a() const { return a_; }                                   ///< [m]
  [[nodiscard]] double P() const { return P_; }                                   ///< [N]
  [[nodiscard]] double mu() const { return contact_.mu(); }
  [[nodiscard]] double Q_max() const { return contact_.Q_max(); }    ///< mu P [N]
  [[nodiscard]] double K_T() const { return contact_.stiffness(); }  ///< 8 G* a [N/m]
  [[nodiscard]] const MindlinContact& contact() const { return contact_; }

  /// Thesis normalization of section 3.3: delta* = 16 G* a_c delta/(3 P_c),
  /// Q* = Q/P_c, Delta W* = G* a_c Delta W/P_c^2.
  [[nodiscard]] double delta_scale() const;   ///< 3 P_c/(16 G* a_c) [m]
  [[nodiscard]] double energy_scale() const;  ///< P_c^2/(G* a_c) [J]

  /// Energy per cycle for each displacement amplitude [J].
  [[nodiscard]] std::vector<double> energy_curve(const std::vector<double>& delta_max) const;

 private:
  PartialSlipModel(const ContactPair& pair, const AsperityLaws& laws, InterferenceReading reading,
                   double omega_star, double P);

  ContactPair pair_;
  CriticalValues critical_;
  AsperityLaws laws_;
  InterferenceReading reading_;
  double omega_star_;
  double a_;
  double P_;
  MindlinContact contact_;
};

}  // namespace asperity::contact
