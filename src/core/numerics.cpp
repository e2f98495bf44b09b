// Failure messages of the quadrature and root-finding wrappers (core/numerics.hpp).
#include "asperity/core/numerics.hpp"

#include <fmt/format.h>

namespace asperity::core::detail {

void throw_invalid_interval(std::string_view what, double a, double b) {
  throw NumericalError(fmt::format("{}: invalid interval [{}, {}]", what, a, b));
}

void throw_non_finite(std::string_view what, std::string_view method, double a, double b) {
  throw NumericalError(
      fmt::format("{}: {} on [{}, {}] gave a non-finite value", what, method, a, b));
}

void throw_infinite_interval(std::string_view what, double a, double b) {
  throw NumericalError(
      fmt::format("{}: tanh-sinh needs a finite interval, got [{}, {}]", what, a, b));
}

void throw_no_sign_change(std::string_view what, double lo, double hi, double flo, double fhi) {
  throw NumericalError(fmt::format("{}: no sign change on [{:.6g}, {:.6g}] (f = {:.6g}, {:.6g})",
                                   what, lo, hi, flo, fhi));
}

void throw_no_convergence(std::string_view what, std::uintmax_t max_iter, double lo, double hi) {
  throw NumericalError(
      fmt::format("{}: TOMS 748 did not converge in {} iterations on [{:.6g}, {:.6g}]", what,
                  max_iter, lo, hi));
}

}  // namespace asperity::core::detail
