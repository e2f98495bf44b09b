#pragma once
// Correlation of a sampled profile with a short kernel, c[i] = sum_k u[k] z[i + k]
// (k = -h..h, z = 0 outside [0, n)), directly or by FFT overlap-save (KISS FFT,
// double precision): the Gaussian filter of ISO 16610-21 in O(n log h) instead of
// O(n h).
#include <cstddef>
#include <vector>

namespace asperity::surface::detail {

/// c[i] for i in [begin, end) into out[i - begin], by direct summation in ascending k.
void correlate_direct(const double* z, std::size_t n, const std::vector<double>& u,
                      std::size_t begin, std::size_t end, double* out);

/// The same by FFT overlap-save. Blocks of N = 2^a 3^b 5^c points (about 8 kernel
/// lengths) are transformed two at a time, one in the real and one in the imaginary
/// part (the kernel is real, so the two correlations do not mix). Round-off is that of
/// the FFT, a few eps log2(N) times the largest |u| sum |z| in a window.
void correlate_fft(const double* z, std::size_t n, const std::vector<double>& u, std::size_t begin,
                   std::size_t end, double* out);

/// The smallest 2^a 3^b 5^c >= n.
std::size_t next_fast_size(std::size_t n);

}  // namespace asperity::surface::detail
