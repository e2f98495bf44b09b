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
// MemoryRule::reset_at_reversal: at a reversal x_r the force restarts from Q_l(x_r) and
// the history is replaced by a virgin loading to x_r. Moving towards the origin the
// branch is the unloading from u_max = |x_r| (Eq. 4.12/4.13, which is what Eq. 7.10
// writes), rejoining the virgin curve past -x_r; moving away from the origin the path
// follows the virgin curve. (Eq. 7.10 in print defines the branch on [-u_max, u_max]
// only; this completion keeps |Q| <= Q_max.) For steady symmetric cycles it equals
// Masing's rules; for transients it does not (SEED_NOTES.md).
#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include "asperity/hysteresis/backbone.hpp"
#include "asperity/hysteresis/tabulated_backbone.hpp"

namespace asperity::hysteresis {

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
    // NaN and +-inf always leave through update_slow (NaN fails every comparison; an
    // infinite x passes every closing point), which rejects them.
    if ((x - x_) * direction_ > 0.0 && (x - top_.closes_at) * top_.direction < 0.0) {
      Q_ = top_.Q + top_.direction * 2.0 * backbone_force(std::abs(x - top_.x) * 0.5);
      x_ = x;
      return Q_;
    }
    return update_slow(x);
  }
  /// update() along a history: Q[k] = update(x[k]) for k < n, bit for bit, with byte
  /// strides (any sign; the arrays need no alignment). The fast path's state stays in
  /// registers between points instead of being reloaded after every store.
  void update_strided(const char* x, std::ptrdiff_t x_stride, char* Q, std::ptrdiff_t Q_stride,
                      std::size_t n);
  /// update_strided's leading run on the current branch, without changing the state:
  /// writes Q[k] for the points k < m that continue the newest branch short of its
  /// closing point (update()'s inline fast path, the same doubles) and returns m. The
  /// state after them is update(x[m-1]) from this one (monotone motion along one branch).
  [[nodiscard]] std::size_t peek_strided(const char* x, std::ptrdiff_t x_stride, char* Q,
                                         std::ptrdiff_t Q_stride, std::size_t n) const;
  /// Force-driven step: moves to force Q, returns the displacement. Throws
  /// InvalidInput if a branch would need |Q| beyond the static limit (gross slip
  /// under force control has no finite displacement).
  double update_force(double Q);
  /// What update(x) would return, bit for bit, without changing or copying the state
  /// (inline when x continues the current branch: the fast path of update()).
  [[nodiscard]] double peek(double x) const {
    if ((x - x_) * direction_ > 0.0 && (x - top_.closes_at) * top_.direction < 0.0) {
      return top_.Q + top_.direction * 2.0 * backbone_force(std::abs(x - top_.x) * 0.5);
    }
    return peek_slow(x);
  }

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

  /// Makes this object a copy of `other` that borrows its backbone: no reference is
  /// taken and, once the stack has the room, nothing is allocated. For a scratch state
  /// reused across calls; it must not be used once `other`'s backbone is gone (assign
  /// again first). Destroying it never touches the backbone.
  void assign_borrowing(const Hysteresis& other);

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
  double update_slow(double x);
  double update_general(double x);
  // update_slow(x) evaluated on the unchanged state: the same operations on the same
  // doubles, with a reversal's fresh stack entry held in a local instead of pushed.
  [[nodiscard]] double peek_slow(double x) const;
  // Index of the active branch for motion to x: the number of stack entries that stay
  // after loop closing. Branch k >= 1 starts at stack_[k-1]; 0 is the virgin curve.
  [[nodiscard]] std::size_t active_branch(double x) const {
    return active_branch(x, stack_.size());
  }
  // The same search over stack_[0, k) only (the entries above k already dropped).
  [[nodiscard]] std::size_t active_branch(double x, std::size_t k) const;
  // Branch force from a reversal point r: Q_r + s 2 Q_l(|x - x_r| / 2).
  [[nodiscard]] double branch_force(const ReversalPoint& r, double x) const {
    return r.Q + r.direction * 2.0 * backbone_force(std::abs(x - r.x) * 0.5);
  }
  [[nodiscard]] std::size_t active_branch_force(double Q) const;
  [[nodiscard]] double branch_force(std::size_t k, double x) const;
  [[nodiscard]] double branch_displacement(std::size_t k, double Q) const;
  void move_to(std::size_t k, double x, double Q);

  // Q_l(x) for finite x >= 0, inline when the backbone is a table (possibly scaled to SI).
  [[nodiscard]] double backbone_force(double x) const {
    if (table_) {
      return table_scaled_ ? table_Q_scale_ * table_->evaluate_non_negative(x / table_x_scale_)
                           : table_->evaluate_non_negative(x);
    }
    return backbone_->force(x);
  }

  // Members: assign_borrowing() copies each one by name; a new member goes there too.
  std::shared_ptr<const Backbone> backbone_;
  MemoryRule rule_;
  const TabulatedBackbone* table_ = nullptr;  // backbone_ (or its inner one) when tabulated
  bool table_scaled_ = false;  // a ScaledBackbone over a table: same arithmetic as its force()
  double table_Q_scale_ = 1.0;
  double table_x_scale_ = 1.0;
  void push_reversal(double x, double Q, int direction);

  // Copy of the newest reversal for the inline fast path; direction 0 when the stack is
  // empty (the fast path then never applies). Kept by refresh_top() after every change.
  void refresh_top();
  ReversalPoint top_{};

  std::vector<ReversalPoint> stack_;
  double x_ = 0.0;
  double Q_ = 0.0;
  double direction_ = 0.0;  // +1, -1, or 0 before the first motion
};

}  // namespace asperity::hysteresis
