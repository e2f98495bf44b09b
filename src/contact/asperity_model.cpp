#include "asperity/contact/asperity_model.hpp"

#include <fmt/format.h>

#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::contact {

std::string_view to_string(ModelName m) {
  switch (m) {
    case ModelName::cfc:
      return "cfc";
    case ModelName::ceb:
      return "ceb";
    case ModelName::ke:
      return "ke";
    case ModelName::bke:
      return "bke";
  }
  return "?";
}

ModelName parse_model_name(std::string_view name) {
  for (auto m : kAllModels) {
    if (name == to_string(m)) return m;
  }
  throw InvalidInput(fmt::format("model \"{}\" is unknown: allowed are cfc, ceb, ke, bke", name));
}

std::string_view to_string(InterferenceReading r) {
  return r == InterferenceReading::hertz ? "hertz" : "own";
}

InterferenceReading parse_interference_reading(std::string_view name) {
  if (name == "hertz") return InterferenceReading::hertz;
  if (name == "own") return InterferenceReading::own;
  throw InvalidInput(
      fmt::format("interference reading \"{}\" is unknown: allowed are hertz, own", name));
}

NormalLaw normal_law_of(ModelName m) {
  switch (m) {
    case ModelName::cfc:
      return NormalLaw::hertz;
    case ModelName::ceb:
      return NormalLaw::ceb;
    case ModelName::ke:
      return NormalLaw::ke;
    case ModelName::bke:
      return NormalLaw::bke;
  }
  return NormalLaw::hertz;
}

FrictionLaw friction_law_of(ModelName m) {
  switch (m) {
    case ModelName::cfc:
      return FrictionLaw::cfc;
    case ModelName::ceb:
      return FrictionLaw::ceb;
    case ModelName::ke:
      return FrictionLaw::ke;
    case ModelName::bke:
      return FrictionLaw::bke;
  }
  return FrictionLaw::cfc;
}

AsperityLaws::AsperityLaws(ModelName model, double nu, const FrictionParameters& params)
    : model_(model), nu_(nu), params_(params), K_(hardness_factor(nu)) {
  core::require_in_half_open("nu", nu, 0.0, 0.5);
  params.validate();
  if (model == ModelName::bke) bke_ = BkeConstants::for_poisson(nu);
}

// Validated once in the constructor; these run in the statistical sums' inner loops.
double AsperityLaws::load_star(double w) const {
  core::require_non_negative("interference w = omega/omega_c", w);
  return detail::normal_load_star(normal_law_of(model_), w, K_, bke_);
}
double AsperityLaws::radius_star(double w) const {
  core::require_non_negative("interference w = omega/omega_c", w);
  return detail::contact_radius_star(normal_law_of(model_), w, bke_);
}
double AsperityLaws::mu(double w) const {
  if (model_ != ModelName::cfc && !(w > 0.0)) {
    return friction_coefficient(friction_law_of(model_), w, nu_, params_);  // throws
  }
  return detail::friction_coefficient(friction_law_of(model_), w, nu_, bke_.delta_c, params_);
}
AsperityLaws::LoadAndFriction AsperityLaws::load_and_mu(double w) const {
  if (model_ != ModelName::bke || !(w < 1e150)) {  // beyond: B.4's logarithmic form
    return {detail::normal_load_star(normal_law_of(model_), w, K_, bke_),
            detail::friction_coefficient(friction_law_of(model_), w, nu_, bke_.delta_c, params_)};
  }
  // B.4 and B.13 with w^alpha and (w/delta_c)^0.46 from one log w (as the separate
  // functions compute them, to round-off).
  const double log_w = std::log(w);
  const double elastic = bke_.load_scale * w * std::sqrt(w);
  double load = elastic;
  if (w > bke_.delta_c) {
    const double gap = std::exp(bke_.alpha * log_w) - bke_.delta_c_alpha;
    if (gap > 0.0) load = elastic * -std::expm1(-bke_.delta_c_alpha / gap);
  }
  const double mu = 0.26 / std::tanh(0.27 * std::exp(0.46 * (log_w - std::log(bke_.delta_c))));
  return {load, mu};
}

double AsperityLaws::interference_star(double P_star) const {
  return contact::interference_star(normal_law_of(model_), P_star, nu_);
}

std::vector<double> AsperityLaws::break_points() const {
  switch (model_) {
    case ModelName::cfc:
      return {};
    case ModelName::ceb: {
      std::vector<double> b;
      if (const auto w = ceb_branch_crossing(nu_, params_.zeta)) b.push_back(*w);
      b.push_back(1.0);
      return b;
    }
    case ModelName::ke:
      return {1.0, 6.0, 6.2, 110.0};
    case ModelName::bke:
      return {BkeConstants::for_poisson(nu_).delta_c};
  }
  return {};
}

PartialSlipModel::PartialSlipModel(const ContactPair& pair, const AsperityLaws& laws,
                                   InterferenceReading reading, double omega_star, double P)
    : pair_(pair),
      critical_(pair.critical()),
      laws_(laws),
      reading_(reading),
      omega_star_(omega_star),
      // B.5 (Hertz) for the hertz reading, else the model's own B.5-B.8.
      a_(critical_.a_c * (reading == InterferenceReading::hertz ? std::sqrt(omega_star)
                                                                : laws.radius_star(omega_star))),
      P_(P),
      contact_(laws.mu(omega_star), P_, pair.G_star, a_) {}

PartialSlipModel PartialSlipModel::from_load(const ContactPair& pair, ModelName model, double P,
                                             const FrictionParameters& params,
                                             InterferenceReading reading) {
  pair.validate();
  core::require_positive("P", P);
  AsperityLaws laws(model, pair.nu, params);
  const double P_star = P / pair.critical().P_c;
  const double w = reading == InterferenceReading::hertz
                       ? interference_star(NormalLaw::hertz, P_star, pair.nu)  // B.1 inverted
                       : laws.interference_star(P_star);
  return PartialSlipModel(pair, laws, reading, w, P);
}

PartialSlipModel PartialSlipModel::from_interference_star(const ContactPair& pair, ModelName model,
                                                          double omega_star,
                                                          const FrictionParameters& params,
                                                          InterferenceReading reading) {
  pair.validate();
  core::require_positive("omega_star", omega_star);
  const AsperityLaws laws(model, pair.nu, params);
  const double P_star = reading == InterferenceReading::hertz
                            ? normal_load_star(NormalLaw::hertz, omega_star, pair.nu)  // B.1
                            : laws.load_star(omega_star);
  return PartialSlipModel(pair, laws, reading, omega_star, pair.critical().P_c * P_star);
}

double PartialSlipModel::delta_scale() const {
  return 3.0 * critical_.P_c / (16.0 * pair_.G_star * critical_.a_c);
}

double PartialSlipModel::energy_scale() const {
  return critical_.P_c * critical_.P_c / (pair_.G_star * critical_.a_c);
}

std::vector<double> PartialSlipModel::energy_curve(const std::vector<double>& delta_max) const {
  std::vector<double> out;
  out.reserve(delta_max.size());
  for (double d : delta_max) out.push_back(contact_.energy_per_cycle(d));
  return out;
}

}  // namespace asperity::contact
