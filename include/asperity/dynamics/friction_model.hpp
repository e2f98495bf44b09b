#pragma once
// Friction-force models for time integration (thesis ch. 7), behind one interface.
//
// A model gives the friction force F_s from its committed state and the current
// displacement u, velocity v and (for Dankowicz) internal states z. Between events the
// force is a smooth (or at least continuous) function of (u, v, z), so an adaptive
// Runge-Kutta method can integrate through it; at every velocity reversal (an event,
// v = 0) the integrator calls commit_reversal(u), which is where hysteretic models
// update their memory.
//
// The models are unit-agnostic: the dynamics layer uses them in the non-dimensional
// variables of section 7.2 (u = x/A, v = du/dtau, F_s = f_s/(k A)); the factories that
// take SI parameters say so. Sign convention: F_s enters Eq. 7.1 as -F_s, so it is
// positive for positive sliding velocity or positive displacement of the contact.
//
// Models:
//  - RegularizedCoulomb: F_max tanh(k_tan v)                      Eq. 7.2-7.3
//  - Dankowicz: z' = v (1 - z/delta sgn v), F = F_max z/delta      Eq. 7.4-7.7
//  - HysteresisFriction: any Masing backbone through hysteresis::Hysteresis; with a
//    rough-flat backbone this is the physics-based (EPB) model of Eq. 7.8-7.10,
//    with a Jenkins backbone the Jenkins element, and with the Segalman backbone the
//    four-parameter Iwan model (an Iwan model obeys Masing's rules exactly).
#include <memory>
#include <span>
#include <string>

#include "asperity/hysteresis/masing.hpp"

namespace asperity::dynamics {

/// Interface of a friction-force model inside a time integration.
class FrictionModel {
 public:
  virtual ~FrictionModel() = default;
  FrictionModel() = default;
  FrictionModel(const FrictionModel&) = default;
  FrictionModel& operator=(const FrictionModel&) = default;

  /// A copy with the same parameters and committed state.
  [[nodiscard]] virtual std::unique_ptr<FrictionModel> clone() const = 0;
  /// Short name ("coulomb", "dankowicz", "hysteresis", ...).
  [[nodiscard]] virtual std::string name() const = 0;

  /// Number of internal ODE states (Dankowicz: 1). They start at zero.
  [[nodiscard]] virtual std::size_t internal_states() const { return 0; }
  /// Friction force at displacement u, velocity v, internal states z (size
  /// internal_states()). Const: does not change the committed state.
  [[nodiscard]] virtual double force(double u, double v, std::span<const double> z) const = 0;
  /// The natural magnitude of internal state i (Dankowicz: delta, the bound of |z|).
  /// A single absolute tolerance given for the integration applies to internal state i
  /// multiplied by this scale, so that the state is resolved relative to its own size.
  [[nodiscard]] virtual double internal_state_scale(std::size_t /*i*/) const { return 1.0; }
  /// Rates of the internal states (size internal_states()).
  virtual void internal_rates(double /*u*/, double /*v*/, std::span<const double> /*z*/,
                              std::span<double> /*dz*/) const {}

  /// True if the model needs the integrator to stop at velocity reversals: its memory
  /// changes there (hysteresis) or its right-hand side has a kink at v = 0 (Dankowicz).
  [[nodiscard]] virtual bool uses_reversal_events() const { return false; }
  /// An event: the motion reverses at displacement u (v = 0). Commits the memory.
  virtual void commit_reversal(double /*u*/) {}
  /// Back to the virgin state (no history).
  virtual void reset() {}

  /// The largest force the model can carry (F_max, or the backbone's limit); +inf if
  /// unbounded.
  [[nodiscard]] virtual double max_force() const = 0;
};

/// No friction (fully lubricated contact): F_s = 0.
class NoFriction final : public FrictionModel {
 public:
  [[nodiscard]] std::unique_ptr<FrictionModel> clone() const override;
  [[nodiscard]] std::string name() const override { return "none"; }
  [[nodiscard]] double force(double, double, std::span<const double>) const override { return 0.0; }
  [[nodiscard]] double max_force() const override { return 0.0; }
};

/// Regularized Coulomb friction, Eq. 7.2/7.3: F_s = F_max tanh(k_tan v).
struct RegularizedCoulombParameters {
  double F_max = 1.5;   ///< sliding force (non-dimensional: F_max/(k A)); > 0
  double k_tan = 6.32;  ///< slope at v = 0 over F_max (non-dimensional: k_tan A sqrt(k/m)); > 0
  void validate() const;
};

class RegularizedCoulomb final : public FrictionModel {
 public:
  explicit RegularizedCoulomb(RegularizedCoulombParameters p);
  [[nodiscard]] std::unique_ptr<FrictionModel> clone() const override;
  [[nodiscard]] std::string name() const override { return "coulomb"; }
  [[nodiscard]] double force(double u, double v, std::span<const double> z) const override;
  [[nodiscard]] double max_force() const override { return p_.F_max; }
  [[nodiscard]] const RegularizedCoulombParameters& parameters() const { return p_; }

 private:
  RegularizedCoulombParameters p_;
};

/// Dankowicz (1999) friction, Eq. 7.4-7.7: internal state z with
/// z' = v (1 - z/delta sgn v) and F_s = F_max z/delta.
struct DankowiczParameters {
  double F_max = 1.5;    ///< sliding force; > 0
  double delta = 0.011;  ///< largest pre-sliding displacement; > 0
  void validate() const;
};

/// The exact solution keeps |z| <= delta: z' = 0 at z = delta sgn v, and the set
/// |z| <= delta attracts (for |z| > delta, z' = -|v| (|z|/delta - 1) sgn z while v has
/// the sign of z). A numerical solution overshoots delta by the integration error,
/// which that attraction damps out; the model evaluates Eq. 7.6-7.7 as printed, without
/// projecting z back, so the overshoot stays visible (Trajectory::internal records z)
/// instead of being hidden. |F_s| <= F_max (1 + max(|z|/delta - 1)).
class Dankowicz final : public FrictionModel {
 public:
  explicit Dankowicz(DankowiczParameters p);
  [[nodiscard]] std::unique_ptr<FrictionModel> clone() const override;
  [[nodiscard]] std::string name() const override { return "dankowicz"; }
  [[nodiscard]] std::size_t internal_states() const override { return 1; }
  [[nodiscard]] double force(double u, double v, std::span<const double> z) const override;
  void internal_rates(double u, double v, std::span<const double> z,
                      std::span<double> dz) const override;
  /// delta: |z| <= delta, so z needs an absolute tolerance below delta (with one atol
  /// for all states, z gets atol * delta).
  [[nodiscard]] double internal_state_scale(std::size_t) const override { return p_.delta; }
  /// The right-hand side has a kink at v = 0 (|v| appears); stopping there keeps the
  /// high-order method at full order.
  [[nodiscard]] bool uses_reversal_events() const override { return true; }
  [[nodiscard]] double max_force() const override { return p_.F_max; }
  [[nodiscard]] const DankowiczParameters& parameters() const { return p_; }

 private:
  DankowiczParameters p_;
};

/// Any Masing backbone as a friction force: F_s = Hysteresis::force(u) between events,
/// Hysteresis::commit_reversal(u) at each velocity reversal. MemoryRule::masing (the
/// default) is Masing's memory with loop closing; MemoryRule::reset_at_reversal is the
/// thesis's Eq. 7.10 (u_max reset at every reversal).
class HysteresisFriction final : public FrictionModel {
 public:
  HysteresisFriction(std::shared_ptr<const hysteresis::Backbone> backbone,
                     hysteresis::MemoryRule rule = hysteresis::MemoryRule::masing,
                     std::string name = "hysteresis");
  [[nodiscard]] std::unique_ptr<FrictionModel> clone() const override;
  [[nodiscard]] std::string name() const override { return name_; }
  [[nodiscard]] double force(double u, double v, std::span<const double> z) const override;
  [[nodiscard]] bool uses_reversal_events() const override { return true; }
  void commit_reversal(double u) override;
  void reset() override { h_.reset(); }
  [[nodiscard]] double max_force() const override { return h_.backbone().limit(); }
  [[nodiscard]] const hysteresis::Hysteresis& hysteresis() const { return h_; }

 private:
  hysteresis::Hysteresis h_;
  std::string name_;
};

/// Jenkins element (spring k_j in series with a Coulomb slider F_max) as a friction
/// model: HysteresisFriction over a JenkinsBackbone (Masing's rules are exact for it).
[[nodiscard]] std::unique_ptr<FrictionModel> make_jenkins(double stiffness, double F_max);

/// Segalman's four-parameter Iwan model (Segalman 2005, J. Appl. Mech. 72:752): a
/// continuum of Jenkins elements with slip-strength density
///   rho(phi) = R phi^chi [H(phi) - H(phi - phi_max)] + S delta(phi - phi_max).
struct SegalmanIwanParameters {
  double F_S = 1.0;   ///< force at macro-slip; > 0
  double K_T = 1.0;   ///< stiffness at zero load; > 0
  double chi = -0.5;  ///< power of the density; in (-1, 0]
  double beta = 0.1;  ///< ratio of the delta spike to the power-law part; >= 0
  void validate() const;
};

/// The virgin curve of the four-parameter Iwan model:
///   F(u) = R u^{chi+2}/(chi+2) + u [R (phi_max^{chi+1} - u^{chi+1})/(chi+1) + S],  u < phi_max,
///   F(u) = F_S,                                                                    u >= phi_max,
/// with phi_max = F_S (1+beta)/(K_T (beta + (chi+1)/(chi+2))),
///      R = F_S (chi+1)/(phi_max^{chi+2} (beta + (chi+1)/(chi+2))),
///      S = F_S/phi_max * beta/(beta + (chi+1)/(chi+2)).
class SegalmanBackbone final : public hysteresis::Backbone {
 public:
  explicit SegalmanBackbone(SegalmanIwanParameters p);
  [[nodiscard]] double force(double x) const override;
  [[nodiscard]] double displacement(double Q) const override;
  [[nodiscard]] double limit() const override { return p_.F_S; }
  [[nodiscard]] double initial_stiffness() const override { return p_.K_T; }
  [[nodiscard]] double stiffness(double x) const override;
  [[nodiscard]] double integral(double x) const override;
  [[nodiscard]] double phi_max() const { return phi_max_; }
  [[nodiscard]] double R() const { return R_; }
  [[nodiscard]] double S() const { return S_; }

 private:
  SegalmanIwanParameters p_;
  double phi_max_;
  double R_;
  double S_;
};

[[nodiscard]] std::unique_ptr<FrictionModel> make_segalman_iwan(SegalmanIwanParameters p);

/// The physics-based (EPB) model from a backbone in SI units (Q [N] against the
/// tangential displacement [m], e.g. a rough flat's), seen in the non-dimensional
/// variables of section 7.2: F_s(u) = Q(A u)/(k A).
[[nodiscard]] std::unique_ptr<FrictionModel> make_physics_based(
    std::shared_ptr<const hysteresis::Backbone> backbone_si, double k, double A,
    hysteresis::MemoryRule rule = hysteresis::MemoryRule::masing);

}  // namespace asperity::dynamics
