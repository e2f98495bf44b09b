#pragma once
// Quadrature and root finding: thin wrappers over Boost.Math that return an error
// estimate and throw NumericalError (saying what was tried) instead of returning
// NaN.
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>

#include "asperity/core/error.hpp"

namespace asperity::core {

namespace detail {
// The messages of the failures below, formatted out of line: a public header includes
// no private dependency of the library.
[[noreturn]] void throw_invalid_interval(std::string_view what, double a, double b);
[[noreturn]] void throw_non_finite(std::string_view what, std::string_view method, double a,
                                   double b);
[[noreturn]] void throw_infinite_interval(std::string_view what, double a, double b);
[[noreturn]] void throw_no_sign_change(std::string_view what, double lo, double hi, double flo,
                                       double fhi);
[[noreturn]] void throw_no_convergence(std::string_view what, std::uintmax_t max_iter, double lo,
                                       double hi);
}  // namespace detail

struct Integral {
  double value = 0.0;
  double error = 0.0;  ///< estimate of the absolute error
};

/// Adaptive Gauss-Kronrod (G7/K15) of f over [a, b] (b may be +inf), to relative
/// tolerance `rel_tol`. Use for smooth integrands; split at known kinks first.
template <class F>
Integral integrate(F f, double a, double b, double rel_tol = 1e-12, unsigned max_depth = 18,
                   std::string_view what = "integral") {
  if (!(a <= b)) {
    detail::throw_invalid_interval(what, a, b);
  }
  if (a == b) return {};
  double error = 0.0;
  const double value = boost::math::quadrature::gauss_kronrod<double, 15>::integrate(
      f, a, b, max_depth, rel_tol, &error);
  if (!std::isfinite(value)) {
    detail::throw_non_finite(what, "Gauss-Kronrod", a, b);
  }
  return {value, error};
}

/// tanh-sinh quadrature of f over finite [a, b]; robust to integrable endpoint
/// singularities and derivative singularities such as (1-x)^{1/2}.
template <class F>
Integral integrate_tanh_sinh(F f, double a, double b, double rel_tol = 1e-12,
                             std::string_view what = "integral") {
  if (!(a <= b)) {
    detail::throw_invalid_interval(what, a, b);
  }
  if (a == b) return {};
  // Not const: Boost <= 1.8x declares integrate() as `-> decltype(...) const`, which
  // makes the return type const instead of the member function. thread_local keeps the
  // lazily refined abscissa tables per thread.
  thread_local boost::math::quadrature::tanh_sinh<double> integrator(15);
  if (!std::isfinite(a) || !std::isfinite(b)) {
    detail::throw_infinite_interval(what, a, b);
  }
  // Boost 1.74's one-argument tanh_sinh has a missing `else` for a left end with
  // |a| >= 0.5: the accurate abscissa a - diff*zc is overwritten by avg + diff*z, which
  // can round to a (an assertion in debug builds, f(a) = inf at a singular end in
  // release). Its path for |a| < 0.5 is correct, so shift such intervals to start at 0.
  // The abscissae are also kept strictly inside (a, b): f is never called at an end.
  const double origin = std::abs(a) < 0.5 ? 0.0 : a;
  const auto inside = [&f, a, b, origin](double s) {
    double x = origin + s;
    if (x <= a) x = std::nextafter(a, b);
    if (x >= b) x = std::nextafter(b, a);
    return f(x);
  };
  double error = 0.0;
  double l1 = 0.0;
  const double value = integrator.integrate(inside, a - origin, b - origin, rel_tol, &error, &l1);
  if (!std::isfinite(value)) {
    detail::throw_non_finite(what, "tanh-sinh", a, b);
  }
  return {value, error * std::max(1.0, l1)};
}

/// Root of f in [lo, hi] by TOMS 748; f(lo) and f(hi) must bracket a sign change.
/// Converges to about `bits` binary digits of the root.
template <class F>
double find_root(F f, double lo, double hi, std::string_view what = "root", int bits = 50,
                 std::uintmax_t max_iter = 200) {
  double flo = f(lo);
  double fhi = f(hi);
  if (flo == 0.0) return lo;
  if (fhi == 0.0) return hi;
  if (!std::isfinite(flo) || !std::isfinite(fhi) || (flo > 0) == (fhi > 0)) {
    detail::throw_no_sign_change(what, lo, hi, flo, fhi);
  }
  std::uintmax_t iters = max_iter;
  const auto [a, b] = boost::math::tools::toms748_solve(
      f, lo, hi, flo, fhi, boost::math::tools::eps_tolerance<double>(bits), iters);
  if (iters >= max_iter) {
    detail::throw_no_convergence(what, max_iter, lo, hi);
  }
  return 0.5 * (a + b);
}

}  // namespace asperity::core
