#pragma once
// Helpers shared by the GoogleTest files.
#include <cmath>
#include <string>

#include "asperity/core/error.hpp"

namespace asperity::testing {

/// |a - b| / |b|: the relative difference against a reference b.
inline double rel(double a, double b) {
  return std::abs(a - b) / std::abs(b);
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
