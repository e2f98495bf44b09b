#include "asperity/surface/rough_flat.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "asperity/contact/mindlin.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"
#include "detail/piecewise_quadrature.hpp"
#include "rough_flat_tolerances.hpp"

namespace asperity::surface {

namespace {

// Lowest separation accepted, in units of sigma_a.
constexpr double kMinSeparationSigmaA = -5.0;

// 1 - (1 - t)^{3/2} for t < 1, else 1: an asperity's loading force over mu P at
// delta~ = t (B.15 inverted).
// expm1/log1p keep full relative accuracy for small t, where the asperity is far from
// gross slip and 1 - (1 - t)^{3/2} ~ 3t/2 would cancel.
double slip_response(double t) {
  return t >= 1.0 ? 1.0 : -std::expm1(1.5 * std::log1p(-t));
}
double slip_response_slope(double t) {
  return t >= 1.0 ? 0.0 : 1.5 * std::sqrt(1.0 - t);
}

// Break point of an integration over u = z* - d*: `sqrt_type` marks slip boundaries,
// where the integrand behaves like (u - u_b)^{1/2} or ^{3/2}.
struct Break {
  double u;
  bool sqrt_type;
};

// Everything about a rough flat at one separation d*, in u = z* - d*.
class Kernel {
 public:
  Kernel(const RoughFlat& flat, double d_star)
      : flat_(flat),
        table_(flat.summit_heights()),
        d_(d_star),
        s_a_(flat.sigma_a_over_sigma()),
        wc_(flat.omega_c_star()) {
    auto range = detail::height_range(table_, d_, s_a_, detail::kTailExponent);
    u_max_ = range.u_max;
    table_breaks_ = std::move(range.nodes);
    for (double w : flat.laws().break_points()) {
      const double u = w * wc_;
      if (u < u_max_) law_breaks_.push_back(u);
    }
    norm_ = 1.0 / (std::sqrt(2.0 * std::numbers::pi) * s_a_);
  }

  [[nodiscard]] double u_max() const { return u_max_; }
  [[nodiscard]] double phi(double u) const {  // Eq. 4.2, or the measured table
    if (table_) return table_->density(d_ + u);
    const double z = (d_ + u) / s_a_;
    return norm_ * std::exp(-0.5 * z * z);
  }
  [[nodiscard]] double w(double u) const { return u / wc_; }
  [[nodiscard]] double load(double u) const { return flat_.laws().load_star(w(u)); }
  [[nodiscard]] double mu(double u) const { return flat_.laws().mu(w(u)); }
  [[nodiscard]] double radius(double u) const { return flat_.laws().radius_star(w(u)); }
  /// Slip length lambda(u): an asperity slips fully when 4 (G*/E*) delta* >= lambda
  /// (Eq. 4.8): mu u for the elastic ratio, mu omega_c* f/a* with the own law.
  [[nodiscard]] double lambda(double u) const {
    if (u <= 0.0) return 0.0;
    const double m = mu(u);
    if (flat_.parameters().slip_scaling == SlipScaling::elastic) return m * u;
    const double a = radius(u);
    return a > 0.0 ? m * wc_ * load(u) / a : 0.0;
  }

  /// (2 pi/3) beta omega_c* times the sum over asperities of mu P/P_c * response(lambda):
  /// the common form of Eq. 4.7, 4.10, 4.12 and 4.14 (asperities with mu = 0 carry no
  /// tangential force), split at the given slip boundaries.
  template <class Response>
  [[nodiscard]] double tangential_sum(double prefactor, Response response,
                                      const std::vector<double>& slip_breaks) const {
    return prefactor * integrate(
                           [&](double u) {
                             if (u <= 0.0) return 0.0;
                             const double m = mu(u);
                             if (m == 0.0) return 0.0;
                             // An asperity whose load or slip length underflows (u -> 0 with
                             // the own-law scaling, lambda ~ f/a) carries no force.
                             const double f = load(u);
                             const double lam = lambda(u);
                             if (f == 0.0 || !(lam > 0.0)) return 0.0;
                             return m * f * response(lam) * phi(u);
                           },
                           slip_breaks);
  }

  /// Roots of lambda(u) = level in (0, u_max), found by sampling each law segment and
  /// refining sign changes with TOMS 748.
  [[nodiscard]] std::vector<double> slip_boundaries(double level) const {
    std::vector<double> roots;
    if (!(level > 0.0)) return roots;
    if (flat_.laws().model() == contact::ModelName::cfc &&
        flat_.parameters().slip_scaling == SlipScaling::elastic) {
      const double u = level / flat_.parameters().friction.mu_cfc;  // lambda = mu u
      if (u < u_max_) roots.push_back(u);
      return roots;
    }
    std::vector<double> edges{0.0};
    edges.insert(edges.end(), law_breaks_.begin(), law_breaks_.end());
    edges.push_back(u_max_);
    constexpr int kSamples = 32;
    for (std::size_t s = 0; s + 1 < edges.size(); ++s) {
      const double a = edges[s];
      const double b = edges[s + 1];
      auto g = [&](double u) { return lambda(u) - level; };
      // Samples just inside the segment (laws jump at its ends), denser near u = 0.
      double u_prev = a + (b - a) * 1e-12;
      double g_prev = g(u_prev);
      for (int i = 1; i <= kSamples; ++i) {
        const double t = static_cast<double>(i) / kSamples;
        const double u = (s == 0) ? a + (b - a) * t * t : a + (b - a) * t;
        const double ui = (i == kSamples) ? b - (b - a) * 1e-12 : u;
        const double gi = g(ui);
        if ((g_prev < 0.0) != (gi < 0.0)) {
          roots.push_back(core::find_root(g, u_prev, ui, "asperity slip boundary", 52));
        }
        u_prev = ui;
        g_prev = gi;
      }
    }
    std::sort(roots.begin(), roots.end());
    return roots;
  }

  /// Integral over u in [0, u_max] of g, split at u = 0, the law branch points and the
  /// given slip boundaries, where the integrand may behave like (u - u_b)^{k/2} (or, for
  /// CEB near w = 1, like a square root just outside the piece): tanh-sinh on each piece,
  /// whose double-exponential clustering at the ends copes with both; a measured table's
  /// nodes split the pieces further (detail::integrate_between_nodes).
  template <class G>
  [[nodiscard]] double integrate(G g, const std::vector<double>& slip_breaks = {}) const {
    std::vector<double> breaks;
    breaks.reserve(law_breaks_.size() + slip_breaks.size() + 2);
    breaks.push_back(0.0);
    breaks.insert(breaks.end(), law_breaks_.begin(), law_breaks_.end());
    for (double u : slip_breaks) {
      if (u > 0.0 && u < u_max_) breaks.push_back(u);
    }
    breaks.push_back(u_max_);
    std::sort(breaks.begin(), breaks.end());
    auto checked = [&](double u) {
      const double v = g(u);
      if (!std::isfinite(v)) {
        throw NumericalError(fmt::format(
            "rough-flat statistical sum: non-finite integrand {} at z* - d* = {:.17g} (d* = {})", v,
            u, d_));
      }
      return v;
    };
    const auto tanh_sinh = [](const auto& f, double a, double b) {
      return core::integrate_tanh_sinh(f, a, b, detail::kQuadratureTol,
                                       "rough-flat statistical sum")
          .value;
    };
    return detail::integrate_between_nodes(checked, tanh_sinh, breaks, table_breaks_);
  }

 private:
  const RoughFlat& flat_;
  const SummitHeightTable* table_;
  double d_;
  double s_a_;
  double wc_;
  double u_max_ = 0.0;
  double norm_ = 0.0;
  std::vector<double> law_breaks_;
  std::vector<double> table_breaks_;  // the table's nodes in u, ascending
};

void require_separation(double d_star) {
  core::require_finite("separation d*", d_star);
}

}  // namespace

void RoughFlatParameters::validate() const {
  if (summit_heights && !summit_sigma) {
    throw InvalidInput(
        "a summit-height table sets the length scale (its standard deviation): the rough flat "
        "needs summit_sigma = true with it");
  }
  if (summit_sigma && !(std::isfinite(beta) && beta > 0.0)) {
    throw InvalidInput(
        fmt::format("beta = sigma_a R eta = {} is not allowed: give sigma_a, R and eta > 0",
                    core::format_value(beta)));
  }
  if (!summit_sigma && (!std::isfinite(beta) || beta <= 0.01928)) {
    throw InvalidInput(fmt::format(
        "beta = sigma_s R eta = {} is not allowed: it must exceed 0.01928, below which "
        "sigma_a/sigma_s = sqrt(1 - 3.717e-4/beta^2) is not real (Eq. 4.2); check sigma, R and "
        "eta",
        core::format_value(beta)));
  }
  if (!std::isfinite(beta) || beta > kMaxRoughnessParameter) {
    throw InvalidInput(fmt::format(
        "beta = sigma_s R eta = {} is not allowed: it must be at most 1/pi = 0.318, beyond which "
        "the asperity caps within one sigma_s of their summits would cover more than the nominal "
        "area, so they cannot be the isolated asperities of the Greenwood-Williamson sum (Eq. "
        "4.4; engineering surfaces give 0.02-0.06); check sigma, R and eta",
        core::format_value(beta)));
  }
  if (!std::isfinite(psi) || !(psi >= kMinPlasticityIndex)) {
    throw InvalidInput(fmt::format(
        "psi (plasticity index) = {} is not allowed: it must be at least {}; below it "
        "omega_c/sigma = (sigma_a/sigma)/psi^2 exceeds 350, no asperity yields and the asperity "
        "friction laws give mu of 10 and more (BKE at P* = 1e-3: 14 at psi = 0.05, 49.9 at "
        "0.01; the thesis uses psi = 0.5 to 4.7)",
        core::format_value(psi), kMinPlasticityIndex));
  }
  core::require_in_half_open("nu", nu, 0.0, 0.5);
  // Isotropic bodies give (1 - nu)/(2 (2 - nu)), 0.17-0.25, for each body and any pair;
  // measured shear moduli may differ, but not by a factor of four.
  core::require_positive("G*/E*", G_over_E);
  if (!(G_over_E < 1.0)) {
    throw InvalidInput(
        fmt::format("G*/E* = {} is not allowed: it must lie in (0, 1); isotropic materials give "
                    "(1 - nu)/(2 (2 - nu)) = 0.17-0.25",
                    core::format_value(G_over_E)));
  }
  friction.validate();
}

RoughFlat::RoughFlat(const RoughFlatParameters& params)
    : params_(params), laws_((params.validate(), params.model), params.nu, params.friction) {
  s_a_ = params.summit_sigma ? 1.0 : std::sqrt(1.0 - 3.717e-4 / (params.beta * params.beta));
  omega_c_star_ = s_a_ / (params.psi * params.psi);
  prefactor_ = 2.0 * std::numbers::pi / 3.0 * params.beta * omega_c_star_;
}

namespace {

// Validates p, naming the dimensional inputs it came from.
void validate_from_inputs(const RoughFlatParameters& p, double E_star, double H,
                          const char* sigma_name, double sigma, double R, double eta) {
  try {
    p.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(
        fmt::format("{} (from E* = {} Pa, H = {} Pa of the softer material, {} = {} m, R = {} m, "
                    "eta = {} 1/m^2)",
                    e.what(), core::format_value(E_star), core::format_value(H), sigma_name,
                    core::format_value(sigma), core::format_value(R), core::format_value(eta)));
  }
}

}  // namespace

RoughFlat RoughFlat::from_combined(double E_star, double G_star, double H, double nu, double sigma,
                                   double R, double eta, contact::ModelName model,
                                   const contact::FrictionParameters& friction, bool summit_sigma,
                                   std::shared_ptr<const SummitHeightTable> heights) {
  core::require_positive("E_star", E_star);
  core::require_positive("G_star", G_star);
  core::require_positive("H", H);
  core::require_positive(
      summit_sigma ? "sigma_a (standard deviation of the summit heights)" : "sigma (rms roughness)",
      sigma);
  core::require_positive("R (mean asperity radius)", R);
  core::require_positive("eta (areal density of asperities)", eta);
  RoughFlatParameters p;
  p.model = model;
  p.beta = sigma * R * eta;
  p.nu = nu;
  p.G_over_E = G_star / E_star;
  p.friction = friction;
  if (summit_sigma) {
    // As from_summit_heights: sigma is sigma_a itself (no McCool relation).
    p.summit_sigma = true;
    p.summit_heights = std::move(heights);
    p.psi =
        2.0 * E_star / (std::numbers::pi * contact::hardness_factor(nu) * H) * std::sqrt(sigma / R);
    validate_from_inputs(p, E_star, H, "sigma_a", sigma, R, eta);
    return RoughFlat(p);
  }
  if (heights) {
    throw InvalidInput(
        "a summit-height table needs sigma to be the summit heights' standard deviation "
        "(summit_sigma), not the rms roughness of the surface");
  }
  if (!(p.beta > 0.01928)) p.validate();  // throws with the message about beta
  const double s_a = std::sqrt(1.0 - 3.717e-4 / (p.beta * p.beta));
  // Plasticity index on sigma_a (SEED_NOTES.md): psi = (2E*/(pi K H)) sqrt(sigma_a/R).
  p.psi = 2.0 * E_star / (std::numbers::pi * contact::hardness_factor(nu) * H) *
          std::sqrt(s_a * sigma / R);
  validate_from_inputs(p, E_star, H, "sigma", sigma, R, eta);
  return RoughFlat(p);
}

RoughFlat RoughFlat::from_summit_heights(const contact::Material& body1,
                                         const contact::Material& body2, double sigma_summits,
                                         double eta, double R, double A0, contact::ModelName model,
                                         const contact::FrictionParameters& friction,
                                         std::shared_ptr<const SummitHeightTable> heights) {
  core::require_positive("sigma_a (standard deviation of the summit heights)", sigma_summits);
  core::require_positive("eta (areal density of asperities)", eta);
  core::require_positive("R (mean asperity radius)", R);
  core::require_positive("A0 (nominal area)", A0);
  const auto pair = contact::ContactPair::combine(body1, body2, R);
  RoughFlatParameters p;
  p.model = model;
  p.summit_sigma = true;
  p.summit_heights = std::move(heights);
  p.beta = sigma_summits * R * eta;
  p.nu = pair.nu;
  p.G_over_E = pair.G_star / pair.E_star;
  p.friction = friction;
  p.psi = 2.0 * pair.E_star / (std::numbers::pi * pair.K() * pair.H) * std::sqrt(sigma_summits / R);
  validate_from_inputs(p, pair.E_star, pair.H, "sigma_a", sigma_summits, R, eta);
  RoughFlat flat(p);
  flat.scales_ = RoughFlatScales{.sigma = sigma_summits,
                                 .force = pair.K() * pair.H * A0,
                                 .A0 = A0,
                                 .eta = eta,
                                 .R = R,
                                 .pair = pair};
  return flat;
}

std::vector<std::string> RoughFlat::warnings() const {
  std::vector<std::string> w;
  if (params_.psi < 0.5) {
    w.push_back(fmt::format(
        "plasticity index psi = {:.4g} is below 0.5, the smallest of the thesis (Fig. 4.4): the "
        "asperities stay elastic (omega_c/sigma = {:.4g}) where the asperity friction laws give "
        "mu growing as the load falls; read mu with care",
        params_.psi, omega_c_star_));
  }
  if (params_.psi > 4.7) {
    w.push_back(fmt::format(
        "plasticity index psi = {:.4g} is above 4.7, the largest of the thesis (Table 5.4): "
        "omega_c/sigma = {:.4g}, so the asperities in contact are deformed far beyond first "
        "yield, where the CEB and KE predictions lose validity (thesis, ch. 5); read mu and "
        "the stiffness with care",
        params_.psi, omega_c_star_));
  }
  if (params_.beta > 0.06) {
    w.push_back(fmt::format(
        "roughness parameter beta = sigma R eta = {:.4g} is above 0.06, the top of the range of "
        "engineering surfaces (0.02-0.06, thesis below Eq. 4.2): the asperities are dense for the "
        "Greenwood-Williamson sum of independent asperities",
        params_.beta));
  }
  return w;
}

std::string friction_coefficient_warning(double mu) {
  if (!(mu > 3.0)) return {};
  return fmt::format(
      "friction coefficient mu = {:.4g} is above 3: more than any of the thesis's computations "
      "(BKE at psi = 0.5, P* = 1e-3, Fig. 4.4: 2.0) or measurements (0.33-0.35, ch. 5); check "
      "the plasticity index and the model",
      mu);
}

RoughFlat RoughFlat::from_dimensional(const contact::Material& body1,
                                      const contact::Material& body2, double sigma, double eta,
                                      double R, double A0, contact::ModelName model,
                                      const contact::FrictionParameters& friction,
                                      SlipScaling scaling) {
  core::require_positive("sigma (rms roughness)", sigma);
  core::require_positive("eta (areal density of asperities)", eta);
  core::require_positive("R (mean asperity radius)", R);
  core::require_positive("A0 (nominal area)", A0);
  const auto pair = contact::ContactPair::combine(body1, body2, R);
  RoughFlatParameters p;
  p.model = model;
  p.beta = sigma * R * eta;
  p.nu = pair.nu;
  p.G_over_E = pair.G_star / pair.E_star;
  p.friction = friction;
  p.slip_scaling = scaling;
  if (!(p.beta > 0.01928)) p.validate();  // throws with the message about beta
  const double s_a = std::sqrt(1.0 - 3.717e-4 / (p.beta * p.beta));
  // Plasticity index on sigma_a (SEED_NOTES.md): psi = (2E*/(pi K H)) sqrt(sigma_a/R).
  p.psi = 2.0 * pair.E_star / (std::numbers::pi * pair.K() * pair.H) * std::sqrt(s_a * sigma / R);
  validate_from_inputs(p, pair.E_star, pair.H, "sigma", sigma, R, eta);
  RoughFlat flat(p);
  flat.scales_ = RoughFlatScales{
      .sigma = sigma, .force = pair.K() * pair.H * A0, .A0 = A0, .eta = eta, .R = R, .pair = pair};
  return flat;
}

double RoughFlat::normal_load_star(double d_star) const {
  require_separation(d_star);
  const Kernel k(*this, d_star);
  return prefactor_ * k.integrate([&](double u) { return k.load(u) * k.phi(u); });  // Eq. 4.4
}

double RoughFlat::static_friction_star(double d_star) const {
  require_separation(d_star);
  const Kernel k(*this, d_star);
  return k.tangential_sum(prefactor_, [](double) { return 1.0; }, {});  // Eq. 4.7
}

double RoughFlat::contact_area_ratio(double d_star) const {
  require_separation(d_star);
  const Kernel k(*this, d_star);
  // A_r/A0 = eta Int pi a^2 phi dz = pi beta omega_c* Int (a/a_c)^2 phi* dz*.
  const double a_factor = std::numbers::pi * params_.beta * omega_c_star_;
  return a_factor * k.integrate([&](double u) {
    const double a = k.radius(u);
    return a * a * k.phi(u);
  });
}

double RoughFlat::contact_fraction(double d_star) const {
  require_separation(d_star);
  if (const auto* t = summit_heights()) return t->survival(d_star);
  return 0.5 * std::erfc(d_star / (s_a_ * std::numbers::sqrt2));
}

double RoughFlat::max_load_star() const {
  return normal_load_star(kMinSeparationSigmaA * s_a_);
}

double RoughFlat::separation_star(double P_star) const {
  if (!std::isfinite(P_star) || P_star < 1e-12) {
    throw InvalidInput(
        fmt::format("normalized preload P* = P/(K H A0) = {} is not allowed: it must be >= 1e-12",
                    core::format_value(P_star)));
  }
  const double d_min = kMinSeparationSigmaA * s_a_;
  const double P_max = normal_load_star(d_min);
  // In newtons too when the flat was built from dimensional inputs.
  auto in_newtons = [&](double P) {
    return scales_ ? fmt::format(" (P = {} N)", core::format_value(P * scales_->force))
                   : std::string();
  };
  if (P_star > P_max) {
    throw InvalidInput(fmt::format(
        "normalized preload P* = {}{} is more than this rough flat can carry in the "
        "Greenwood-Williamson model: at separation d* = {} (5 sigma_a below the mean asperity "
        "height) P* = {}{}; reduce the preload or enlarge the nominal area",
        core::format_value(P_star), in_newtons(P_star), core::format_value(d_min),
        core::format_value(P_max), in_newtons(P_max)));
  }
  const double target = std::log(P_star);
  auto g = [&](double d) {
    const double P = normal_load_star(d);
    return (P > 0.0 ? std::log(P) : -1e300) - target;
  };
  // P*(d*) decreases monotonically; step up from d_min by sigma_a until it drops below.
  double lo = d_min;
  double hi = d_min;
  double g_hi = std::log(P_max) - target;
  while (g_hi > 0.0) {
    lo = hi;
    hi += s_a_;
    g_hi = g(hi);
    if (hi > 60.0 * s_a_) {
      throw NumericalError(
          fmt::format("separation for P* = {}: no bracket found", core::format_value(P_star)));
    }
  }
  const double d = core::find_root(g, lo, hi, "separation for a preload (Eq. 4.4)", 50);
  // The sum treats asperities as independent contacts on a nominal area A0: a real contact
  // area beyond A0 is outside the model (GW's assumptions fail well before).
  const double area_ratio = contact_area_ratio(d);
  if (area_ratio >= 1.0) {
    throw InvalidInput(fmt::format(
        "normalized preload P* = {}{} would make the real contact area larger than the nominal "
        "area (A_r/A0 = {:.3g} at d* = {:.4g}), which the Greenwood-Williamson sum of independent "
        "asperities cannot describe; reduce the preload or enlarge the nominal area",
        core::format_value(P_star), in_newtons(P_star), area_ratio, d));
  }
  return d;
}

double RoughFlat::loading_force_star(double delta_star, double d_star) const {
  core::require_non_negative("tangential displacement delta*", delta_star);
  require_separation(d_star);
  const Kernel k(*this, d_star);
  const double c = 4.0 * params_.G_over_E * delta_star;
  // Eq. 4.9-4.10 with the erratum: full slip (Q = mu P) where delta~ = c/lambda >= 1.
  return k.tangential_sum(
      prefactor_, [&](double lam) { return slip_response(c / lam); }, k.slip_boundaries(c));
}

double RoughFlat::loading_stiffness_star(double delta_star, double d_star) const {
  core::require_non_negative("tangential displacement delta*", delta_star);
  require_separation(d_star);
  const Kernel k(*this, d_star);
  const double dc = 4.0 * params_.G_over_E;
  const double c = dc * delta_star;
  return k.tangential_sum(
      prefactor_, [&](double lam) { return slip_response_slope(c / lam) * dc / lam; },
      k.slip_boundaries(c));
}

double RoughFlat::stiffness_star(double d_star) const {
  return loading_stiffness_star(0.0, d_star);
}

double RoughFlat::unloading_force_star(double delta_star, double delta_max_star,
                                       double d_star) const {
  core::require_non_negative("delta*_max", delta_max_star);
  require_separation(d_star);
  if (!(std::abs(delta_star) <= delta_max_star)) {
    throw InvalidInput(fmt::format("delta* = {} must lie in [-delta*_max, delta*_max] = [-{}, {}]",
                                   core::format_value(delta_star),
                                   core::format_value(delta_max_star),
                                   core::format_value(delta_max_star)));
  }
  const Kernel k(*this, d_star);
  const double cm = 4.0 * params_.G_over_E * delta_max_star;
  const double cr = 0.5 * 4.0 * params_.G_over_E * (delta_max_star - delta_star);
  auto breaks = k.slip_boundaries(cm);
  const auto more = k.slip_boundaries(cr);
  breaks.insert(breaks.end(), more.begin(), more.end());
  // Eq. 4.11-4.12: each asperity unloads by Mindlin-Deresiewicz from its own state at
  // delta*_max: mu P [h(c_m/lambda) - 2 h((c_m - c)/(2 lambda))].
  return k.tangential_sum(
      prefactor_,
      [&](double lam) { return slip_response(cm / lam) - 2.0 * slip_response(cr / lam); }, breaks);
}

double RoughFlat::reloading_force_star(double delta_star, double delta_max_star,
                                       double d_star) const {
  return -unloading_force_star(-delta_star, delta_max_star, d_star);  // Eq. 4.13
}

double RoughFlat::energy_star(double delta_max_star, double d_star) const {
  core::require_non_negative("delta*_max", delta_max_star);
  require_separation(d_star);
  const Kernel k(*this, d_star);
  const double g = 4.0 * params_.G_over_E;
  const double cm = g * delta_max_star;
  // An asperity's loop area is mu P * delta_s * 4.8 E~(delta~_max) (B.19 scaled:
  // 9/10 / (3/16) = 4.8), with delta_s* = lambda/g its gross-slip displacement.
  return k.tangential_sum(
      prefactor_,
      [&](double lam) {
        return (lam / g) * 4.8 * contact::mindlin::energy_tilde_for_displacement(cm / lam);
      },
      k.slip_boundaries(cm));
}

std::shared_ptr<const RoughFlatBackbone> RoughFlat::backbone(double d_star, double rel_tol) const {
  return std::make_shared<const RoughFlatBackbone>(*this, d_star, rel_tol);
}

std::shared_ptr<const hysteresis::ScaledBackbone> RoughFlat::backbone_at_preload(
    double P, double rel_tol) const {
  if (!scales_) {
    throw InvalidInput(
        "backbone_at_preload: the rough flat is normalized (no SI scales): build it with "
        "RoughFlat::from_dimensional, or use backbone(d_star)");
  }
  if (!(P > 0.0) || !std::isfinite(P)) {
    throw InvalidInput(
        fmt::format("backbone_at_preload: P = {} N: the preload must be positive and finite", P));
  }
  const double d_star = separation_star(P / scales_->force);
  return std::make_shared<const hysteresis::ScaledBackbone>(backbone(d_star, rel_tol),
                                                            scales_->sigma, scales_->force);
}

}  // namespace asperity::surface
