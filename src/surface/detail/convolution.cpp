#include "convolution.hpp"

#include <kissfft/kissfft.hh>

#include <algorithm>
#include <complex>

namespace asperity::surface::detail {

std::size_t next_fast_size(std::size_t n) {
  for (std::size_t m = std::max<std::size_t>(n, 1);; ++m) {
    std::size_t r = m;
    for (std::size_t f : {2, 3, 5}) {
      while (r % f == 0) r /= f;
    }
    if (r == 1) return m;
  }
}

void correlate_direct(const double* z, std::size_t n, const std::vector<double>& u,
                      std::size_t begin, std::size_t end, double* out) {
  const std::size_t h = u.size() / 2;
  for (std::size_t i = begin; i < end; ++i) {
    // Kernel offsets with i + k in [0, n): k from -min(i, h) to min(n - 1 - i, h).
    const std::size_t k_lo = h - std::min(i, h);
    const std::size_t k_hi = h + std::min(n - 1 - i, h);
    double s = 0.0;
    for (std::size_t k = k_lo; k <= k_hi; ++k) s += u[k] * z[i + k - h];
    out[i - begin] = s;
  }
}

void correlate_fft(const double* z, std::size_t n, const std::vector<double>& u, std::size_t begin,
                   std::size_t end, double* out) {
  using cpx = std::complex<double>;
  if (end <= begin) return;
  const std::size_t L = u.size();  // 2h + 1
  const std::size_t h = L / 2;
  const std::size_t count = end - begin;
  // About 8 kernel lengths per block (the FFT's cost per output is then ~8/7 log2 N),
  // never more than the whole range needs.
  const std::size_t N =
      next_fast_size(std::min(std::max<std::size_t>(8 * (L - 1), 256), count + L - 1));
  const std::size_t B = N - (L - 1);  // outputs per block
  const kissfft<double> forward(N, false);
  const kissfft<double> inverse(N, true);
  // Overlap-save: with x[j] = z[i0 - h + j], c[i0 + m] = (x (*) g)[m + 2h] for the
  // circular convolution with g[q] = u[2h - q] (q = 0..2h), valid for m < B.
  std::vector<cpx> g(N), G(N), x(N), X(N), y(N);
  for (std::size_t q = 0; q < L; ++q) g[q] = cpx(u[L - 1 - q] / static_cast<double>(N), 0.0);
  forward.transform(g.data(), G.data());
  auto at = [&](std::size_t i0, std::size_t j) {
    // z[i0 - h + j], zero outside [0, n); i0 + j may be below h.
    const std::size_t p = i0 + j;
    return (p < h || p - h >= n) ? 0.0 : z[p - h];
  };
  for (std::size_t i0 = begin; i0 < end; i0 += 2 * B) {
    const std::size_t i1 = i0 + B;  // second block, in the imaginary part
    const bool second = i1 < end;
    const bool interior = i0 >= h && i0 + N - h <= n && (!second || i1 + N - h <= n);
    if (interior) {
      const double* a = z + (i0 - h);
      const double* b = second ? z + (i1 - h) : nullptr;
      for (std::size_t j = 0; j < N; ++j) x[j] = cpx(a[j], b != nullptr ? b[j] : 0.0);
    } else {
      for (std::size_t j = 0; j < N; ++j) x[j] = cpx(at(i0, j), second ? at(i1, j) : 0.0);
    }
    forward.transform(x.data(), X.data());
    for (std::size_t j = 0; j < N; ++j) X[j] *= G[j];
    inverse.transform(X.data(), y.data());
    const std::size_t m0 = std::min(B, end - i0);
    for (std::size_t m = 0; m < m0; ++m) out[i0 - begin + m] = y[m + 2 * h].real();
    if (second) {
      const std::size_t m1 = std::min(B, end - i1);
      for (std::size_t m = 0; m < m1; ++m) out[i1 - begin + m] = y[m + 2 * h].imag();
    }
  }
}

}  // namespace asperity::surface::detail
