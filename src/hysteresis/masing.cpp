#include "asperity/hysteresis/masing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "asperity/core/error.hpp"
#include "asperity/core/interrupt.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/hysteresis/backbones.hpp"

namespace asperity::hysteresis {

namespace {

double odd_force(const Backbone& b, double x) {
  return std::copysign(b.force(std::abs(x)), x);
}

int sign_of(double v) {
  return (v > 0.0) - (v < 0.0);
}

}  // namespace

double Backbone::integral(double x) const {
  core::require_non_negative("x", x);
  return core::integrate([this](double s) { return force(s); }, 0.0, x, 1e-13, 20,
                         "backbone integral")
      .value;
}

double Backbone::stiffness(double x) const {
  core::require_non_negative("x", x);
  const double h = 1e-6 * (x + 1e-12 * limit() / initial_stiffness());
  if (x < h) return (force(x + h) - force(x)) / h;
  return (force(x + h) - force(x - h)) / (2.0 * h);
}

double energy_per_cycle(const Backbone& backbone, double x_max) {
  core::require_non_negative("displacement amplitude", x_max);
  const double w = 8.0 * backbone.integral(x_max) - 4.0 * x_max * backbone.force(x_max);
  // W >= 0 for any non-decreasing backbone; clip only round-off of order eps * scale.
  const double scale = 4.0 * x_max * backbone.force(x_max);
  if (w < 0.0 && w > -1e-12 * scale) return 0.0;
  return w;
}

Hysteresis::Hysteresis(std::shared_ptr<const Backbone> backbone, MemoryRule rule)
    : backbone_(std::move(backbone)), rule_(rule) {
  if (!backbone_) throw InvalidInput("Hysteresis needs a backbone");
  if (const auto* table = dynamic_cast<const TabulatedBackbone*>(backbone_.get())) {
    table_ = table;
  } else if (const auto* scaled = dynamic_cast<const ScaledBackbone*>(backbone_.get())) {
    if (const auto* inner = dynamic_cast<const TabulatedBackbone*>(&scaled->inner())) {
      table_ = inner;
      table_scaled_ = true;
      table_Q_scale_ = scaled->Q_scale();
      table_x_scale_ = scaled->x_scale();
    }
  }
  stack_.reserve(64);
}

void Hysteresis::refresh_top() {
  if (stack_.empty()) {
    top_ = ReversalPoint{};
    return;
  }
  top_ = stack_.back();
}

void Hysteresis::reset() {
  stack_.clear();
  refresh_top();
  x_ = 0.0;
  Q_ = 0.0;
  direction_ = 0;
}

void Hysteresis::assign_borrowing(const Hysteresis& other) {
  // Every member of the class: the aliasing constructor makes a shared_ptr that points
  // at the backbone and owns nothing (no count to change, now or on destruction).
  backbone_ =
      std::shared_ptr<const Backbone>(std::shared_ptr<const Backbone>(), other.backbone_.get());
  rule_ = other.rule_;
  table_ = other.table_;
  table_scaled_ = other.table_scaled_;
  table_Q_scale_ = other.table_Q_scale_;
  table_x_scale_ = other.table_x_scale_;
  top_ = other.top_;
  stack_.assign(other.stack_.begin(), other.stack_.end());
  x_ = other.x_;
  Q_ = other.Q_;
  direction_ = other.direction_;
}

void Hysteresis::push_reversal(double x, double Q, int direction) {
  const double closes_at = stack_.empty() ? -x : stack_.back().x;
  stack_.push_back({x, Q, static_cast<double>(direction), closes_at});
  refresh_top();
}

std::size_t Hysteresis::active_branch(double x, std::size_t k) const {
  while (k >= 1) {
    const ReversalPoint& r = stack_[k - 1];
    const double d = r.direction;
    if ((x - r.x) * d < 0.0) {  // moving against branch k: that reversal never happened
      --k;
      continue;
    }
    // Masing: the inner loop closes, continue on the older branch. Eq. 7.10 keeps one
    // branch only; past the mirror of its reversal it rejoins the virgin curve.
    if (rule_ == MemoryRule::masing || k == 1) {
      if ((x - r.closes_at) * d >= 0.0) {
        k = k >= 2 ? k - 2 : 0;
        continue;
      }
    }
    break;
  }
  return k;
}

std::size_t Hysteresis::active_branch_force(double Q) const {
  std::size_t k = stack_.size();
  while (k >= 1) {
    const ReversalPoint& r = stack_[k - 1];
    const double d = r.direction;
    if ((Q - r.Q) * d < 0.0) {
      --k;
      continue;
    }
    if (rule_ == MemoryRule::masing || k == 1) {
      const double target = k >= 2 ? stack_[k - 2].Q : -stack_[0].Q;
      if ((Q - target) * d >= 0.0) {
        k = k >= 2 ? k - 2 : 0;
        continue;
      }
    }
    break;
  }
  return k;
}

double Hysteresis::branch_force(std::size_t k, double x) const {
  if (k == 0) return odd_force(*backbone_, x);
  return branch_force(stack_[k - 1], x);
}

double Hysteresis::branch_displacement(std::size_t k, double Q) const {
  const double limit = backbone_->limit();
  if (k == 0) {
    if (std::abs(Q) >= limit) {
      throw InvalidInput(fmt::format(
          "tangential force {} reaches the static friction limit {}: the contact slides "
          "(gross slip has no finite displacement under force control)",
          core::format_value(Q), core::format_value(limit)));
    }
    return std::copysign(backbone_->displacement(std::abs(Q)), Q);
  }
  const ReversalPoint& r = stack_[k - 1];
  const double half = std::abs(Q - r.Q) * 0.5;
  if (half >= limit) {
    throw InvalidInput(fmt::format(
        "tangential force {} is beyond the static friction limit {} on this branch: the contact "
        "slides (gross slip has no finite displacement under force control)",
        core::format_value(Q), core::format_value(limit)));
  }
  return r.x + r.direction * 2.0 * backbone_->displacement(half);
}

double Hysteresis::force(double x) const {
  core::require_finite("displacement", x);
  return branch_force(active_branch(x), x);
}

double Hysteresis::tangent_stiffness(double x) const {
  core::require_finite("displacement", x);
  const std::size_t k = active_branch(x);
  const double h = 1e-7 * std::max(1e-300, std::abs(x) + (k ? std::abs(stack_[k - 1].x) : 0.0));
  // One-sided in the direction of motion keeps the difference on the active branch.
  const double d = k ? stack_[k - 1].direction : (x >= 0.0 ? 1.0 : -1.0);
  const double x0 = x - d * h;
  if (k == 0 || (x0 - stack_[k - 1].x) * d >= 0.0) {
    return (branch_force(k, x) - branch_force(k, x0)) / (x - x0);
  }
  // Right at the reversal: the tangent of the fresh branch is the backbone's initial one.
  return backbone_->initial_stiffness();
}

void Hysteresis::move_to(std::size_t k, double x, double Q) {
  stack_.resize(k);
  refresh_top();
  x_ = x;
  Q_ = Q;
}

void Hysteresis::commit_reversal(double x) {
  core::require_finite("displacement", x);
  const std::size_t k = active_branch(x);
  const double Q = branch_force(k, x);
  move_to(k, x, Q);
  const int current = k ? static_cast<int>(stack_[k - 1].direction)
                        : (direction_ != 0.0 ? static_cast<int>(direction_) : sign_of(x));
  if (current == 0) return;  // a reversal at the origin before any motion: nothing to remember
  direction_ = -current;
  if (rule_ == MemoryRule::reset_at_reversal) {
    // Eq. 7.10: u_max is reset to the displacement at the reversal and the force restarts
    // from the backbone value there, Q_l(u_max), whatever it was: the history is replaced
    // by a virgin loading to x. Towards the origin the branch is Eq. 4.12/4.13's
    // unloading from u_max, which meets the virgin curve at -u_max (its mirror closing);
    // away from the origin the path is that virgin loading, continued.
    stack_.clear();
    Q_ = odd_force(*backbone_, x);
    if (direction_ * x < 0.0) push_reversal(x, Q_, -current);
    refresh_top();
    return;
  }
  push_reversal(x, Q, -current);
  Q_ = Q;
}

double Hysteresis::update_slow(double x) {
  const double d = (x > x_) ? 1.0 : (x < x_ ? -1.0 : 0.0);
  if (d == -direction_ && d != 0.0 && rule_ == MemoryRule::masing && std::isfinite(x)) {
    // A reversal at the current point whose fresh branch does not close within the step:
    // the stack is already pruned to the active branch, so push and follow the new branch.
    const double closes_at = stack_.empty() ? -x_ : stack_.back().x;
    if ((x - closes_at) * d < 0.0) {
      stack_.push_back({x_, Q_, d, closes_at});
      top_ = stack_.back();
      direction_ = d;
      Q_ = top_.Q + d * 2.0 * backbone_force(std::abs(x - top_.x) * 0.5);
      x_ = x;
      return Q_;
    }
  }
  return update_general(x);
}

double Hysteresis::peek_slow(double x) const {
  // update_slow's reversal whose fresh branch does not close within the step.
  const double d = (x > x_) ? 1.0 : (x < x_ ? -1.0 : 0.0);
  if (d == -direction_ && d != 0.0 && rule_ == MemoryRule::masing && std::isfinite(x)) {
    const ReversalPoint fresh{x_, Q_, d, stack_.empty() ? -x_ : stack_.back().x};
    if ((x - fresh.closes_at) * d < 0.0) return branch_force(fresh, x);
  }
  // update_general.
  core::require_finite("displacement", x);
  const int s = sign_of(x - x_);
  if (s == 0) return Q_;
  const std::size_t n = stack_.size();
  if (direction_ == 0.0 || s == direction_) return branch_force(active_branch(x, n), x);
  if (rule_ == MemoryRule::masing) {
    // push_reversal(x_, Q_, s), then active_branch(x) over the stack with it on top.
    const ReversalPoint fresh{x_, Q_, static_cast<double>(s), n == 0 ? -x_ : stack_.back().x};
    std::size_t k = n;
    if ((x - fresh.x) * fresh.direction >= 0.0) {
      if ((x - fresh.closes_at) * fresh.direction < 0.0) return branch_force(fresh, x);
      k = n >= 1 ? n - 1 : 0;
    }
    return branch_force(active_branch(x, k), x);
  }
  // Eq. 7.10: commit_reversal(x_), then active_branch(x) over what it leaves.
  const std::size_t k = active_branch(x_, n);
  const int current = k ? static_cast<int>(stack_[k - 1].direction)
                        : (direction_ != 0.0 ? static_cast<int>(direction_) : sign_of(x_));
  if (current == 0) return branch_force(active_branch(x, k), x);
  const double turned = -current;
  if (turned * x_ < 0.0) {
    // The one entry left: the unloading from u_max = |x_| towards the origin.
    const ReversalPoint unloading{x_, odd_force(*backbone_, x_), turned, -x_};
    if ((x - unloading.x) * unloading.direction >= 0.0 &&
        (x - unloading.closes_at) * unloading.direction < 0.0) {
      return branch_force(unloading, x);
    }
  }
  return odd_force(*backbone_, x);
}

double Hysteresis::update_general(double x) {
  core::require_finite("displacement", x);
  const int d = sign_of(x - x_);
  if (d == 0) return Q_;
  if (direction_ != 0.0 && d != direction_) {
    // A reversal at the current point: its force Q_ is known and the stack is already
    // pruned to the active branch by the previous step.
    if (rule_ == MemoryRule::reset_at_reversal) {
      commit_reversal(x_);
    } else {
      push_reversal(x_, Q_, d);
    }
  }
  direction_ = d;
  const std::size_t k = active_branch(x);
  const double Q = branch_force(k, x);
  move_to(k, x, Q);
  return Q;
}

double Hysteresis::update_force(double Q) {
  core::require_finite("force", Q);
  const int d = sign_of(Q - Q_);
  if (d == 0) return x_;
  if (direction_ != 0.0 && d != direction_) {
    // Reversal in force at the current point (under Eq. 7.10 as in commit_reversal: the
    // branch restarts from the backbone value at the reversal displacement).
    if (rule_ == MemoryRule::reset_at_reversal) {
      commit_reversal(x_);
    } else {
      push_reversal(x_, Q_, d);
    }
  }
  direction_ = d;
  const std::size_t k = active_branch_force(Q);
  const double x = branch_displacement(k, Q);
  move_to(k, x, Q);
  return x;
}

void Hysteresis::update_strided(const char* x, std::ptrdiff_t x_stride, char* Q,
                                std::ptrdiff_t Q_stride, std::size_t n) {
  // update()'s inline fast path on local copies of x_, direction_ and top_ (stores through
  // char* may alias any member, which would force a reload per point); the members are
  // written back before every slow step and at the end.
  double x_now = x_;
  double Q_now = Q_;
  double direction = direction_;
  ReversalPoint top = top_;
  for (std::size_t k = 0; k < n; ++k) {
    double xk = 0.0;
    std::memcpy(&xk, x + static_cast<std::ptrdiff_t>(k) * x_stride, sizeof xk);
    if ((xk - x_now) * direction > 0.0 && (xk - top.closes_at) * top.direction < 0.0) {
      Q_now = top.Q + top.direction * 2.0 * backbone_force(std::abs(xk - top.x) * 0.5);
      x_now = xk;
    } else {
      x_ = x_now;
      Q_ = Q_now;
      Q_now = update_slow(xk);
      x_now = x_;
      direction = direction_;
      top = top_;
    }
    std::memcpy(Q + static_cast<std::ptrdiff_t>(k) * Q_stride, &Q_now, sizeof Q_now);
  }
  x_ = x_now;
  Q_ = Q_now;
}

std::size_t Hysteresis::peek_strided(const char* x, std::ptrdiff_t x_stride, char* Q,
                                     std::ptrdiff_t Q_stride, std::size_t n) const {
  double x_now = x_;
  for (std::size_t k = 0; k < n; ++k) {
    double xk = 0.0;
    std::memcpy(&xk, x + static_cast<std::ptrdiff_t>(k) * x_stride, sizeof xk);
    if (!((xk - x_now) * direction_ > 0.0 && (xk - top_.closes_at) * top_.direction < 0.0)) {
      return k;
    }
    const double Qk = top_.Q + top_.direction * 2.0 * backbone_force(std::abs(xk - top_.x) * 0.5);
    std::memcpy(Q + static_cast<std::ptrdiff_t>(k) * Q_stride, &Qk, sizeof Qk);
    x_now = xk;
  }
  return n;
}

std::vector<double> Hysteresis::forces(std::span<const double> x_history) const {
  Hysteresis h = *this;
  std::vector<double> out(x_history.size());
  constexpr std::size_t kBlock = 0x1000;  // a pending interrupt is seen every 4096 points
  for (std::size_t i = 0; i < x_history.size(); i += kBlock) {
    core::check_interrupt();
    const std::size_t m = std::min(kBlock, x_history.size() - i);
    h.update_strided(reinterpret_cast<const char*>(x_history.data() + i), sizeof(double),
                     reinterpret_cast<char*>(out.data() + i), sizeof(double), m);
  }
  return out;
}

std::vector<double> Hysteresis::displacements(std::span<const double> Q_history) const {
  Hysteresis h = *this;
  std::vector<double> out;
  out.reserve(Q_history.size());
  for (std::size_t i = 0; i < Q_history.size(); ++i) {
    if ((i & 0xFFF) == 0) core::check_interrupt();
    out.push_back(h.update_force(Q_history[i]));
  }
  return out;
}

}  // namespace asperity::hysteresis
