#pragma once
// Masing's loop memory on a stack of reversal points (hysteresis::Hysteresis::active_branch,
// SEED_NOTES.md "Masing's rules hold exactly"), shared by the elements that carry it.
#include <cstddef>
#include <vector>

namespace asperity::vibration::detail {

/// The depth of `stack` whose top reversal's branch holds the position x: reversals x lies
/// behind are left (an older branch is active), and a branch that reaches the point where it
/// closes wipes its loop (the reversal and the one before it). `Reversal` has x (the reversal
/// point), direction (+-1: the motion after it) and closes_at; the search stops at a reversal
/// r with permanent(r) true (one no motion wipes).
template <class Reversal, class Permanent>
[[nodiscard]] std::size_t masing_active_depth(const std::vector<Reversal>& stack, double x,
                                              Permanent permanent) {
  std::size_t k = stack.size();
  while (k >= 1) {
    const Reversal& r = stack[k - 1];
    if (permanent(r)) break;
    if ((x - r.x) * r.direction < 0.0) {
      --k;
      continue;
    }
    if ((x - r.closes_at) * r.direction >= 0.0) {
      k = k >= 2 ? k - 2 : 0;
      continue;
    }
    break;
  }
  return k;
}

template <class Reversal>
[[nodiscard]] std::size_t masing_active_depth(const std::vector<Reversal>& stack, double x) {
  return masing_active_depth(stack, x, [](const Reversal&) { return false; });
}

}  // namespace asperity::vibration::detail
