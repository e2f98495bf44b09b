#pragma once
// Helpers shared by the GoogleTest files.
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "asperity/core/error.hpp"

namespace asperity::testing {

/// |a - b| / |b|: the relative difference against a reference b.
inline double rel(double a, double b) {
  return std::abs(a - b) / std::abs(b);
}

/// Work done on a contact along samples begin..end of a history, Int Q dx by the
/// trapezoidal rule: over a closed cycle, the energy it dissipates.
inline double trapezoid_work(const std::vector<double>& x, const std::vector<double>& Q,
                             std::size_t begin, std::size_t end) {
  double w = 0.0;
  for (std::size_t i = begin + 1; i <= end; ++i) w += 0.5 * (Q[i] + Q[i - 1]) * (x[i] - x[i - 1]);
  return w;
}

/// The message of the InvalidInput thrown by f(), or "" if it did not throw one.
template <class F>
std::string invalid_input_message(F f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

}  // namespace asperity::testing
