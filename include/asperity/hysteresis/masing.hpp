#pragma once
// Masing hysteresis over any backbone: a stack of reversal points with loop closing
// follows an arbitrary displacement (or force) history (SEED_NOTES.md, "Masing's rules
// hold exactly"). Independent of where the backbone comes from: a rough flat, one
// asperity, or a test function.
//
// Branch rules, for a backbone (virgin curve) Q_l(x), odd, non-decreasing, bounded:
//  - virgin motion from the origin: Q = Q_l(x);
//  - after a reversal at (x_r, Q_r), moving in direction s = +-1:
//    Q = Q_r + s 2 Q_l(|x - x_r| / 2);
//  - loop closing (Masing memory): when a branch reaches the reversal point where the
//    branch it reversed began, the inner loop is forgotten and the path continues on
//    the older branch; a path that passes the mirror image of the first reversal
//    rejoins the virgin curve.
// The thesis's Eq. 7.10 rule (reset u_max at every velocity reversal) is available as
// MemoryRule::reset_at_reversal: every branch starts at the last reversal and nothing
// is remembered before it.
#include <cmath>
#include <memory>
#include <span>
#include <vector>

namespace asperity::hysteresis {

/// The virgin loading curve Q_l(x) for x >= 0 (extended as an odd function):
/// continuous, non-decreasing, Q_l(0) = 0, bounded by limit().
class Backbone {
 public:
  virtual ~Backbone() = default;
  /// Q_l(x) for x >= 0.
  [[nodiscard]] virtual double force(double x) const = 0;
  /// Inverse: the x >= 0 with Q_l(x) = Q for 0 <= Q < limit(). Throws InvalidInput
  /// for Q >= limit() (the contact slides: no finite displacement).
  [[nodiscard]] virtual double displacement(double Q) const = 0;
  /// sup Q_l: the static friction force.
  [[nodiscard]] virtual double limit() const = 0;
  /// dQ_l/dx at x = 0: the stiffness at every reversal.
  [[nodiscard]] virtual double initial_stiffness() const = 0;
  /// Integral of Q_l from 0 to x (x >= 0), for energy per cycle. Default: adaptive
  /// quadrature of force().
  [[nodiscard]] virtual double integral(double x) const;
};

enum class MemoryRule {
  masing,             ///< reversal stack with loop closing (default)
  reset_at_reversal,  ///< thesis Eq. 7.10: branch from the last reversal only
};

/// A remembered reversal: the branch that starts here moves in `direction` (+1 or -1)
/// and, under Masing's rules, closes when it reaches `closes_at` (the previous
/// reversal's x, or the mirror -x of the first one).
struct ReversalPoint {
  double x = 0.0;
  double Q = 0.0;
  double direction = 0.0;
  double closes_at = 0.0;
};

/// Energy dissipated per symmetric cycle of amplitude x_max on any Masing backbone:
/// W = 8 Int_0^{x_max} Q_l dx - 4 x_max Q_l(x_max) (SEED_NOTES.md).
[[nodiscard]] double energy_per_cycle(const Backbone& backbone, double x_max);

/// Follows a history with Masing's rules. Not thread-safe to mutate; copy one per
/// thread (copies share the immutable backbone).
class Hysteresis {
 public:
  explicit Hysteresis(std::shared_ptr<const Backbone> backbone,
                      MemoryRule rule = MemoryRule::masing);

  [[nodiscard]] const Backbone& backbone() const { return *backbone_; }
  [[nodiscard]] MemoryRule rule() const { return rule_; }

  /// Displacement-driven step: moves to x, detecting a reversal when the direction of
  /// motion changes, and returns the force there. O(1) amortized; inline fast paths for
  /// motion along the newest branch short of its closing point, and for a reversal whose
  /// fresh branch does not close within the step.
  double update(double x) {
    const double dx = x - x_;
    const int d = (dx > 0.0) - (dx < 0.0);
    // NaN and +-inf always leave through update_general (NaN gives d = 0; an infinite x
    // passes every closing point), which rejects them.
    if (d == direction_ && d != 0 && (x - top_.closes_at) * top_.direction < 0.0) {
      Q_ = top_.Q + top_.direction * 2.0 * backbone_->force(std::abs(x - top_.x) * 0.5);
      x_ = x;
      return Q_;
    }
    if (d == -direction_ && d != 0 && rule_ == MemoryRule::masing && std::isfinite(x)) {
      // A reversal at the current point whose fresh branch does not close at once: the
      // stack is already pruned to the active branch, so push and follow the new branch.
      const double closes_at = stack_.empty() ? -x_ : stack_.back().x;
      if ((x - closes_at) * d < 0.0) {
        stack_.push_back({x_, Q_, static_cast<double>(d), closes_at});
        top_ = stack_.back();
        direction_ = d;
        Q_ = top_.Q + top_.direction * 2.0 * backbone_->force(std::abs(x - top_.x) * 0.5);
        x_ = x;
        return Q_;
      }
    }
    return update_general(x);
  }
  /// Force-driven step: moves to force Q, returns the displacement. Throws
  /// InvalidInput if a branch would need |Q| beyond the static limit (gross slip
  /// under force control has no finite displacement).
  double update_force(double Q);

  /// Force at x reached from the last committed state by monotone motion (no reversal
  /// in between); loop closing along the way is taken into account. Does not change
  /// the state: the right-hand side of an ODE between events.
  [[nodiscard]] double force(double x) const;
  /// dQ/dx at x under the same assumption as force().
  [[nodiscard]] double tangent_stiffness(double x) const;
  /// Commits a reversal of the motion at x (an event: velocity = 0). The state moves
  /// to x along the current branch, then the direction flips.
  void commit_reversal(double x);

  /// Forgets the history: back at the origin on the virgin curve.
  void reset();

  /// Current position and force.
  [[nodiscard]] double x() const { return x_; }
  [[nodiscard]] double Q() const { return Q_; }
  /// Reversal points still remembered, oldest first.
  [[nodiscard]] const std::vector<ReversalPoint>& reversals() const { return stack_; }

  /// Forces along a displacement history, starting from the current state, without
  /// changing this object. Thread-safe (const).
  [[nodiscard]] std::vector<double> forces(std::span<const double> x_history) const;
  /// Displacements along a force history, starting from the current state.
  [[nodiscard]] std::vector<double> displacements(std::span<const double> Q_history) const;

 private:
  double update_general(double x);
  // Index of the active branch for motion to x: the number of stack entries that stay
  // after loop closing. Branch k >= 1 starts at stack_[k-1]; 0 is the virgin curve.
  [[nodiscard]] std::size_t active_branch(double x) const;
  [[nodiscard]] std::size_t active_branch_force(double Q) const;
  [[nodiscard]] double branch_force(std::size_t k, double x) const;
  [[nodiscard]] double branch_displacement(std::size_t k, double Q) const;
  void move_to(std::size_t k, double x, double Q);

  std::shared_ptr<const Backbone> backbone_;
  MemoryRule rule_;
  void push_reversal(double x, double Q, int direction);

  // Copy of the newest reversal for the inline fast path, its closing point moved to
  // infinity under the Eq. 7.10 rule (no loop closing) and direction 0 when the stack is
  // empty (the fast path then never applies). Kept by refresh_top() after every change.
  void refresh_top();
  ReversalPoint top_{};

  std::vector<ReversalPoint> stack_;
  double x_ = 0.0;
  double Q_ = 0.0;
  int direction_ = 0;  // +1, -1, or 0 before the first motion
};

}  // namespace asperity::hysteresis
