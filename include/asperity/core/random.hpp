#pragma once
// Normally distributed noise that the same seed reproduces on every platform.
// std::normal_distribution's algorithm is left to the standard library (libstdc++ and
// libc++ give different numbers for the same engine), so the transform is our own:
// std::mt19937_64 (its sequence is fixed by the C++ standard, [rand.predef]), uniforms
// u = (bits >> 11) 2^-53 in [0, 1) from its 53 top bits, and Marsaglia's polar method
// (G. Marsaglia, T. A. Bray, SIAM Review 6 (1964) 260): v1, v2 = 2u - 1 until
// 0 < s = v1^2 + v2^2 < 1, then v1 f and v2 f with f = sqrt(-2 ln(s)/s), in that order.
// Everything up to s is integer or exactly rounded arithmetic; ln is the C library's
// (correctly rounded or within one ulp on glibc, musl, macOS), so a value can differ
// between C libraries by at most about one ulp, never in sequence.
#include <cstdint>
#include <random>

namespace asperity::core {

class StandardNormal {
 public:
  explicit StandardNormal(std::uint64_t seed) : engine_(seed) {}
  /// The next N(0, 1) value.
  double operator()();
  /// The next uniform value in [0, 1) (53 random bits).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace asperity::core
