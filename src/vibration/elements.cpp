#include "asperity/vibration/elements.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/hysteresis/table_backbone.hpp"
#include "common.hpp"
#include "masing_memory.hpp"

namespace asperity::vibration {

namespace {

void require_finite_samples(const Eigen::MatrixXd& u, const char* what) {
  if (!u.allFinite()) {
    throw InvalidInput(fmt::format("element {} samples hold a NaN or infinity", what));
  }
}

void prepare(PeriodicResponse& out, Eigen::Index n, Eigen::Index dirs, bool tangent,
             bool velocity) {
  out.f.setZero(n, dirs);
  out.history.clear();
  if (tangent) {
    out.du.setZero(n, dirs * dirs);
    if (velocity) {
      out.dv.setZero(n, dirs * dirs);
    } else {
      out.dv.resize(0, 0);
    }
  } else {
    out.du.resize(0, 0);
    out.dv.resize(0, 0);
  }
}

// The sample index of pass-local step s (0 .. 2N-1) in one period.
std::uint32_t sample_of(std::size_t step, std::size_t n) {
  return static_cast<std::uint32_t>(step % n);
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Masing element

MasingElement::MasingElement(std::shared_ptr<const hysteresis::Backbone> backbone, std::string type,
                             dynamics::SummaryObject parameters)
    : backbone_(std::move(backbone)), type_(std::move(type)), parameters_(std::move(parameters)) {
  if (!backbone_) throw InvalidInput("a Masing element needs a backbone");
}

namespace {

// dQ/du of the sample at one step as a sparse list over samples: the local term is kept
// apart; `origin` is the reversal point whose branch the sample is on (-1: virgin curve).
struct Term {
  std::uint32_t j;
  double value;
};

struct Reversal {
  double x;
  double Q;
  double direction;
  double closes_at;
  std::uint32_t sample;  // the sample where the motion reversed
  std::vector<Term> dQ;  // dQ_r/du over samples (all of it, local term included)
};

}  // namespace

double Element::gross_slip_fraction(const PeriodicResponse& /*r*/) const {
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {

// Samples of direction 0 at the slip force (to 1e-9 of it, the rounding of the branch laws).
double samples_at_limit(const PeriodicResponse& r, double limit) {
  if (!std::isfinite(limit) || r.f.rows() == 0) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>((r.f.col(0).array().abs() >= (1.0 - 1e-9) * limit).count()) /
         static_cast<double>(r.f.rows());
}

}  // namespace

double MasingElement::gross_slip_fraction(const PeriodicResponse& r) const {
  return samples_at_limit(r, backbone_->limit());
}

double JenkinsElement::gross_slip_fraction(const PeriodicResponse& r) const {
  return samples_at_limit(r, p_.F_s);
}

void MasingElement::periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& /*v*/,
                                      bool tangent, PeriodicResponse& out) const {
  require_finite_samples(u, "displacement");
  const auto n = static_cast<std::size_t>(u.rows());
  prepare(out, u.rows(), 1, tangent, false);
  if (n == 0) return;
  const hysteresis::Backbone& bb = *backbone_;
  std::vector<Reversal> stack;
  stack.reserve(16);
  double x_prev = 0.0, Q_prev = 0.0, dir_prev = 0.0;
  // Derivative of the previous sample's force: k_prev at its own sample, -k_prev at its
  // branch origin (if any), plus that origin's list (materialised only on a reversal).
  double k_prev = 0.0;
  std::uint32_t s_prev = 0;
  bool prev_has_sample = false;  // false while at the virgin origin (x = 0, no sample)

  for (std::size_t step = 0; step < 2 * n; ++step) {
    const std::uint32_t i = sample_of(step, n);
    const double x = u(static_cast<Eigen::Index>(i), 0);
    const int d = detail::sign_of(x - x_prev);
    double Q = Q_prev;
    double kt = 0.0;
    if (d == 0) {
      // No motion: the force and its dependence are those of the previous sample.
      Q = Q_prev;
      kt = k_prev;
    } else {
      if (dir_prev != 0.0 && d != static_cast<int>(dir_prev)) {
        // A reversal at the previous sample (as Hysteresis::update_general).
        Reversal r{x_prev, Q_prev, static_cast<double>(d), stack.empty() ? -x_prev : stack.back().x,
                   s_prev, {}};
        if (tangent && prev_has_sample) {
          r.dQ.push_back({s_prev, k_prev});
          if (!stack.empty()) {
            const Reversal& o = stack.back();
            r.dQ.push_back({o.sample, -k_prev});
            r.dQ.insert(r.dQ.end(), o.dQ.begin(), o.dQ.end());
          }
        }
        stack.push_back(std::move(r));
      }
      dir_prev = d;
      const std::size_t k = detail::masing_active_depth(stack, x);
      stack.resize(k);
      if (k == 0) {
        const double ax = std::abs(x);
        Q = std::copysign(bb.force(ax), x);
        if (tangent) kt = bb.stiffness(ax);
      } else {
        const Reversal& r = stack.back();
        const double half = std::abs(x - r.x) * 0.5;
        Q = r.Q + r.direction * 2.0 * bb.force(half);
        if (tangent) kt = bb.stiffness(half);
      }
    }
    if (step >= n) {
      out.f(i, 0) = Q;
      if (tangent) {
        if (d == 0 && !prev_has_sample) {
          // Still at the origin: no dependence.
        } else if (d == 0) {
          // Same force as the previous sample: its local term becomes a history term.
          out.history.push_back({i, s_prev, 0, 0, k_prev});
          if (!stack.empty()) {
            const Reversal& o = stack.back();
            out.history.push_back({i, o.sample, 0, 0, -k_prev});
            for (const Term& t : o.dQ) out.history.push_back({i, t.j, 0, 0, t.value});
          }
        } else {
          out.du(i, 0) = kt;
          if (!stack.empty()) {
            const Reversal& o = stack.back();
            out.history.push_back({i, o.sample, 0, 0, -kt});
            for (const Term& t : o.dQ) out.history.push_back({i, t.j, 0, 0, t.value});
          }
        }
      }
    }
    if (d != 0) {
      k_prev = kt;
      s_prev = i;
      prev_has_sample = true;
    }
    x_prev = x;
    Q_prev = Q;
  }
}

void MasingElement::static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                                    Eigen::MatrixXd& K) const {
  core::require_finite("element displacement", u(0));
  const double ax = std::abs(u(0));
  f.resize(1);
  K.resize(1, 1);
  f(0) = std::copysign(backbone_->force(ax), u(0));
  K(0, 0) = backbone_->stiffness(ax);
}

Eigen::MatrixXd MasingElement::initial_stiffness() const {
  return Eigen::MatrixXd::Constant(1, 1, backbone_->initial_stiffness());
}

// ---------------------------------------------------------------------------------------
// Jenkins element

void JenkinsParameters::validate() const {
  core::require_positive("jenkins.k_t", k_t);
  core::require_positive("jenkins.F_s", F_s);
}

JenkinsElement::JenkinsElement(JenkinsParameters p) : p_(p) {
  p_.validate();
}

void JenkinsElement::periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& /*v*/,
                                       bool tangent, PeriodicResponse& out) const {
  require_finite_samples(u, "displacement");
  const auto n = static_cast<std::size_t>(u.rows());
  prepare(out, u.rows(), 1, tangent, false);
  if (n == 0) return;
  const double k = p_.k_t;
  const double F = p_.F_s;
  // Return mapping from the virgin state (f = 0 at u = 0). Since the last slip at sample
  // s, f_i = f_s + k (u_i - u_s) with f_s = +-F_s (no dependence): df_i = k (e_i - e_s).
  double f = 0.0, u_prev = 0.0;
  bool slipped = false;
  std::uint32_t s = 0;
  for (std::size_t step = 0; step < 2 * n; ++step) {
    const std::uint32_t i = sample_of(step, n);
    const double ui = u(static_cast<Eigen::Index>(i), 0);
    const double trial = f + k * (ui - u_prev);
    const bool slip = std::abs(trial) >= F;
    f = slip ? std::copysign(F, trial) : trial;
    u_prev = ui;
    if (step >= n) {
      out.f(i, 0) = f;
      if (tangent && !slip) {
        out.du(i, 0) = k;
        if (slipped) out.history.push_back({i, s, 0, 0, -k});
      }
    }
    if (slip) {
      slipped = true;
      s = i;
    }
  }
}

void JenkinsElement::static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                                     Eigen::MatrixXd& K) const {
  core::require_finite("element displacement", u(0));
  f.resize(1);
  K.resize(1, 1);
  const double trial = p_.k_t * u(0);
  const bool slip = std::abs(trial) >= p_.F_s;
  f(0) = slip ? std::copysign(p_.F_s, trial) : trial;
  K(0, 0) = slip ? 0.0 : p_.k_t;
}

Eigen::MatrixXd JenkinsElement::initial_stiffness() const {
  return Eigen::MatrixXd::Constant(1, 1, p_.k_t);
}

dynamics::SummaryObject JenkinsElement::describe() const {
  return {{"type", "jenkins"}, {"k_t_N_per_m", p_.k_t}, {"F_s_N", p_.F_s}};
}

// ---------------------------------------------------------------------------------------
// Regularized Coulomb element

void CoulombParameters::validate() const {
  core::require_positive("coulomb.F_s", F_s);
  core::require_positive("coulomb.k_tan", k_tan);
}

CoulombElement::CoulombElement(CoulombParameters p) : p_(p) {
  p_.validate();
}

void CoulombElement::periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v,
                                       bool tangent, PeriodicResponse& out) const {
  require_finite_samples(v, "velocity");
  prepare(out, u.rows(), 1, tangent, true);
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    const double t = std::tanh(p_.k_tan * v(i, 0));  // Eq. 7.3
    out.f(i, 0) = p_.F_s * t;
    if (tangent) out.dv(i, 0) = p_.F_s * p_.k_tan * (1.0 - t * t);
  }
}

void CoulombElement::static_response(const Eigen::VectorXd& /*u*/, Eigen::VectorXd& f,
                                     Eigen::MatrixXd& K) const {
  f = Eigen::VectorXd::Zero(1);
  K = Eigen::MatrixXd::Zero(1, 1);
}

Eigen::MatrixXd CoulombElement::initial_stiffness() const {
  return Eigen::MatrixXd::Zero(1, 1);
}

dynamics::SummaryObject CoulombElement::describe() const {
  return {{"type", "coulomb"}, {"F_s_N", p_.F_s}, {"k_tan_s_per_m", p_.k_tan}};
}

// ---------------------------------------------------------------------------------------
// Elastic dry friction in two directions

void ElasticDryFriction2dParameters::validate() const {
  core::require_positive("elastic_dry_friction_2d.k_t", k_t);
  core::require_positive("elastic_dry_friction_2d.k_n", k_n);
  core::require_positive("elastic_dry_friction_2d.mu", mu);
  core::require_finite("elastic_dry_friction_2d.N0", N0);
}

ElasticDryFriction2dElement::ElasticDryFriction2dElement(ElasticDryFriction2dParameters p) : p_(p) {
  p_.validate();
}

void ElasticDryFriction2dElement::periodic_response(const Eigen::MatrixXd& u,
                                                    const Eigen::MatrixXd& /*v*/, bool tangent,
                                                    PeriodicResponse& out) const {
  require_finite_samples(u, "displacement");
  if (u.cols() != 2) {
    throw InvalidInput(fmt::format(
        "elastic_dry_friction_2d acts on 2 directions (tangential, normal), got {}", u.cols()));
  }
  const auto n = static_cast<std::size_t>(u.rows());
  prepare(out, u.rows(), 2, tangent, false);
  if (n == 0) return;
  const double kt = p_.k_t, kn = p_.k_n, mu = p_.mu;
  const double preload = std::max(p_.N0, 0.0);  // carried by the bolt; none with a gap
  // Columns of du: d + 2 e (d: force direction, e: displacement direction).
  constexpr Eigen::Index tt = 0, nt = 1, tn = 2, nn = 3;
  // Since the last event s (slip or separation), f_t,i = f_t,s + k_t (u_t,i - u_t,s); at a
  // slip f_t,s = sgn mu (N0 + k_n u_n,s), at a separation f_t,s = 0.
  double ft = 0.0, ut_prev = 0.0;
  enum class Event { none, slip, separation } event = Event::none;
  std::uint32_t s = 0;
  double sgn_s = 0.0;
  for (std::size_t step = 0; step < 2 * n; ++step) {
    const std::uint32_t i = sample_of(step, n);
    const auto ii = static_cast<Eigen::Index>(i);
    const double ut = u(ii, 0), un = u(ii, 1);
    const double fn_trial = p_.N0 + kn * un;
    const bool contact = fn_trial > 0.0;
    const double fn = contact ? fn_trial : 0.0;
    Event now = Event::none;
    double sgn = 0.0;
    if (!contact) {
      ft = 0.0;
      now = Event::separation;
    } else {
      const double trial = ft + kt * (ut - ut_prev);
      if (std::abs(trial) >= mu * fn) {
        sgn = trial >= 0.0 ? 1.0 : -1.0;
        ft = sgn * mu * fn;
        now = Event::slip;
      } else {
        ft = trial;
      }
    }
    ut_prev = ut;
    if (step >= n) {
      out.f(ii, 0) = ft;
      out.f(ii, 1) = fn - preload;
      if (tangent && contact) {
        out.du(ii, nn) = kn;
        if (now == Event::slip) {
          out.du(ii, tn) = sgn * mu * kn;
        } else {
          out.du(ii, tt) = kt;
          if (event != Event::none) out.history.push_back({i, s, 0, 0, -kt});
          if (event == Event::slip) out.history.push_back({i, s, 0, 1, sgn_s * mu * kn});
        }
      }
      (void)nt;
    }
    if (now != Event::none) {
      event = now;
      s = i;
      sgn_s = sgn;
    }
  }
}

void ElasticDryFriction2dElement::static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                                                  Eigen::MatrixXd& K) const {
  core::require_finite("element tangential displacement", u(0));
  core::require_finite("element normal displacement", u(1));
  f = Eigen::VectorXd::Zero(2);
  K = Eigen::MatrixXd::Zero(2, 2);
  const double preload = std::max(p_.N0, 0.0);
  f(1) = -preload;
  const double fn = p_.N0 + p_.k_n * u(1);
  if (fn <= 0.0) return;
  f(1) = fn - preload;
  K(1, 1) = p_.k_n;
  const double trial = p_.k_t * u(0);
  if (std::abs(trial) >= p_.mu * fn) {
    const double sgn = trial >= 0.0 ? 1.0 : -1.0;
    f(0) = sgn * p_.mu * fn;
    K(0, 1) = sgn * p_.mu * p_.k_n;
  } else {
    f(0) = trial;
    K(0, 0) = p_.k_t;
  }
}

Eigen::MatrixXd ElasticDryFriction2dElement::initial_stiffness() const {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(2, 2);
  if (p_.N0 > 0.0) {
    K(0, 0) = p_.k_t;
    K(1, 1) = p_.k_n;
  }
  return K;
}

double ElasticDryFriction2dElement::slip_force() const {
  return p_.mu * std::max(p_.N0, 0.0);
}

dynamics::SummaryObject ElasticDryFriction2dElement::describe() const {
  return {{"type", "elastic_dry_friction_2d"},
          {"k_t_N_per_m", p_.k_t},
          {"k_n_N_per_m", p_.k_n},
          {"mu", p_.mu},
          {"N0_N", p_.N0}};
}

// ---------------------------------------------------------------------------------------
// Polynomial stiffness and cubic damping

void PolynomialStiffnessParameters::validate() const {
  core::require_finite("polynomial_stiffness.k1", k1);
  core::require_finite("polynomial_stiffness.k2", k2);
  core::require_finite("polynomial_stiffness.k3", k3);
  if (k1 == 0.0 && k2 == 0.0 && k3 == 0.0) {
    throw InvalidInput("polynomial_stiffness: k1, k2 and k3 are all zero: give at least one");
  }
}

PolynomialStiffnessElement::PolynomialStiffnessElement(PolynomialStiffnessParameters p) : p_(p) {
  p_.validate();
}

void PolynomialStiffnessElement::periodic_response(const Eigen::MatrixXd& u,
                                                   const Eigen::MatrixXd& /*v*/, bool tangent,
                                                   PeriodicResponse& out) const {
  require_finite_samples(u, "displacement");
  prepare(out, u.rows(), 1, tangent, false);
  for (Eigen::Index i = 0; i < u.rows(); ++i) {
    const double x = u(i, 0);
    out.f(i, 0) = x * (p_.k1 + x * (p_.k2 + x * p_.k3));
    if (tangent) out.du(i, 0) = p_.k1 + x * (2.0 * p_.k2 + 3.0 * x * p_.k3);
  }
}

void PolynomialStiffnessElement::static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                                                 Eigen::MatrixXd& K) const {
  core::require_finite("element displacement", u(0));
  const double x = u(0);
  f = Eigen::VectorXd::Constant(1, x * (p_.k1 + x * (p_.k2 + x * p_.k3)));
  K = Eigen::MatrixXd::Constant(1, 1, p_.k1 + x * (2.0 * p_.k2 + 3.0 * x * p_.k3));
}

Eigen::MatrixXd PolynomialStiffnessElement::initial_stiffness() const {
  return Eigen::MatrixXd::Constant(1, 1, p_.k1);
}

double PolynomialStiffnessElement::slip_force() const {
  return std::numeric_limits<double>::infinity();
}

dynamics::SummaryObject PolynomialStiffnessElement::describe() const {
  return {{"type", "polynomial_stiffness"},
          {"k1_N_per_m", p_.k1},
          {"k2_N_per_m2", p_.k2},
          {"k3_N_per_m3", p_.k3}};
}

void CubicDampingParameters::validate() const {
  core::require_finite("cubic_damping.c3", c3);
  if (c3 == 0.0) throw InvalidInput("cubic_damping.c3 = 0: the element would do nothing");
}

CubicDampingElement::CubicDampingElement(CubicDampingParameters p) : p_(p) {
  p_.validate();
}

void CubicDampingElement::periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v,
                                            bool tangent, PeriodicResponse& out) const {
  require_finite_samples(v, "velocity");
  prepare(out, u.rows(), 1, tangent, true);
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    const double x = v(i, 0);
    out.f(i, 0) = p_.c3 * x * x * x;
    if (tangent) out.dv(i, 0) = 3.0 * p_.c3 * x * x;
  }
}

void CubicDampingElement::static_response(const Eigen::VectorXd& /*u*/, Eigen::VectorXd& f,
                                          Eigen::MatrixXd& K) const {
  f = Eigen::VectorXd::Zero(1);
  K = Eigen::MatrixXd::Zero(1, 1);
}

Eigen::MatrixXd CubicDampingElement::initial_stiffness() const {
  return Eigen::MatrixXd::Zero(1, 1);
}

double CubicDampingElement::slip_force() const {
  return std::numeric_limits<double>::infinity();
}

dynamics::SummaryObject CubicDampingElement::describe() const {
  return {{"type", "cubic_damping"}, {"c3_N_s3_per_m3", p_.c3}};
}

// ---------------------------------------------------------------------------------------
// Factories

std::shared_ptr<const Element> make_jenkins_element(double k_t, double F_s) {
  return std::make_shared<JenkinsElement>(JenkinsParameters{.k_t = k_t, .F_s = F_s});
}

std::shared_ptr<const Element> make_iwan4_element(const dynamics::SegalmanIwanParameters& p) {
  p.validate();
  return std::make_shared<MasingElement>(std::make_shared<dynamics::SegalmanBackbone>(p), "iwan4",
                                         dynamics::SummaryObject{{"type", "iwan4"},
                                                                 {"F_S_N", p.F_S},
                                                                 {"K_T_N_per_m", p.K_T},
                                                                 {"chi", p.chi},
                                                                 {"beta", p.beta}});
}

std::shared_ptr<const Element> make_masing_table_element(std::vector<double> x,
                                                         std::vector<double> Q,
                                                         const std::string& source) {
  const std::size_t n = x.size();
  auto b = std::make_shared<hysteresis::TableBackbone>(std::move(x), std::move(Q), source);
  dynamics::SummaryObject d{{"type", "masing_table"},
                            {"source", source},
                            {"points", n},
                            {"Q_max_N", b->limit()},
                            {"stiffness_N_per_m", b->initial_stiffness()},
                            {"x_last_m", b->x().back()}};
  return std::make_shared<MasingElement>(std::move(b), "masing_table", std::move(d));
}

std::shared_ptr<const Element> make_coulomb_element(double F_s, double k_tan) {
  return std::make_shared<CoulombElement>(CoulombParameters{.F_s = F_s, .k_tan = k_tan});
}

std::shared_ptr<const Element> make_elastic_dry_friction_2d_element(
    const ElasticDryFriction2dParameters& p) {
  return std::make_shared<ElasticDryFriction2dElement>(p);
}

std::shared_ptr<const Element> make_polynomial_stiffness_element(
    const PolynomialStiffnessParameters& p) {
  return std::make_shared<PolynomialStiffnessElement>(p);
}

std::shared_ptr<const Element> make_cubic_damping_element(double c3) {
  return std::make_shared<CubicDampingElement>(CubicDampingParameters{.c3 = c3});
}

std::shared_ptr<const Element> make_rough_flat_element(
    std::shared_ptr<const hysteresis::Backbone> backbone_si, dynamics::SummaryObject parameters) {
  return std::make_shared<MasingElement>(std::move(backbone_si), "rough_flat",
                                         std::move(parameters));
}

}  // namespace asperity::vibration
