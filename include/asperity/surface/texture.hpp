#pragma once
// The surface-texture parameters a metrology user checks first, computed on the
// scale-limited (levelled, filtered) profiles and areal maps of roughness.hpp:
// ISO 21920-2:2021 profile parameters Ra, Rq, Rz, Rsk, Rku, Rdq; ISO 25178-2:2012 areal
// parameters Sa, Sq, Ssk, Sku, Sdq on the S-L surface of an areal Gaussian filter
// (ISO 16610-61); the power spectral density of a profile or of the rows and columns of
// a map; and spike removal (a Hampel identifier, off by default). SI units.
#include <cstddef>
#include <string>
#include <vector>

#include "asperity/surface/profile.hpp"
#include "asperity/surface/roughness.hpp"

namespace asperity::surface {

/// ISO 21920-2 parameters of a roughness profile z(x) (the filtered profile: ordinates
/// about its mean line, which is z = 0), over the n points of the evaluation length.
/// Definitions (ISO 21920-2:2021, height and spacing parameters; the same as
/// ISO 4287:1997 4.2.1-4.2.4, 4.4.2 with the sampling length replaced by the
/// evaluation length):
///   Ra  = (1/l) int |z| dx           arithmetic mean height    -> mean |z_i|
///   Rq  = sqrt((1/l) int z^2 dx)     root mean square height   -> sqrt(mean z_i^2)
///   Rsk = (1/Rq^3) (1/l) int z^3 dx  skewness                  -> mean z_i^3 / Rq^3
///   Rku = (1/Rq^4) (1/l) int z^4 dx  kurtosis                  -> mean z_i^4 / Rq^4
///   Rz  = mean over the sections of (max z - min z) in the section   maximum height
///   Rdq = sqrt((1/l) int (dz/dx)^2 dx) root mean square gradient
/// Sections (ISO 21920-3 default: the section length equals lc): consecutive runs of
/// round(lc/dx) points from the first point; a remainder shorter than a section is left
/// out of Rz only. Without a long-wave cut-off the evaluation length is one section
/// (Rz = Rt). The slope of Rdq is the forward difference (z[i+1] - z[i])/dx over the n - 1
/// intervals, the same as m2 of spectral_moments() (Rdq = sqrt(m2), so the
/// Greenwood-Williamson parameters and Rdq describe one slope) and the default of
/// SurfaceTopography's rms_slope_from_profile; for a sinusoid of wavenumber k it reads
/// low by exactly sin(k dx/2)/(k dx/2) (0.4 % at 20 points a wavelength, 0.016 % at 100),
/// an error known in closed form, whereas the 7-point central formula quoted for ISO 4287
/// software is more accurate for band-limited data but amplifies measurement noise.
struct ProfileParameters {
  double Ra = 0.0;              ///< arithmetic mean height [m]
  double Rq = 0.0;              ///< root mean square height [m]
  double Rz = 0.0;              ///< maximum height, mean over the sections [m]
  double Rsk = 0.0;             ///< skewness [-]
  double Rku = 0.0;             ///< kurtosis [-]
  double Rdq = 0.0;             ///< root mean square gradient [-]
  std::size_t sections = 0;     ///< sections averaged for Rz
  double section_length = 0.0;  ///< [m]
};

/// The parameters of a roughness profile (already levelled and filtered), with sections
/// of `section_length` [m] for Rz (0 = one section, the whole profile). Throws
/// InvalidInput for fewer than 3 points or a profile with Rq = 0.
[[nodiscard]] ProfileParameters profile_parameters(const Profile& roughness, double section_length);

/// ISO 25178-2:2012 parameters of a scale-limited surface z(x, y) over its definition
/// area A (ordinates about the reference plane z = 0):
///   Sa  = (1/A) int |z| dA                   arithmetic mean height (4.1.7)
///   Sq  = sqrt((1/A) int z^2 dA)             root mean square height (4.1.1)
///   Ssk = (1/Sq^3) (1/A) int z^3 dA          skewness (4.1.2)
///   Sku = (1/Sq^4) (1/A) int z^4 dA          kurtosis (4.1.3)
///   Sdq = sqrt((1/A) int (dz/dx)^2 + (dz/dy)^2 dA)   root mean square gradient (4.3.1)
/// Sums over the grid points; the gradient by forward differences along x and along y
/// (mean of the squared x-differences plus mean of the squared y-differences), the
/// discretisation of Rdq in each direction (Sdq^2 = m2x + m2y).
struct ArealParameters {
  double Sa = 0.0;     ///< [m]
  double Sq = 0.0;     ///< [m]
  double Ssk = 0.0;    ///< [-]
  double Sku = 0.0;    ///< [-]
  double Sdq = 0.0;    ///< [-]
  std::size_t nx = 0;  ///< points of the S-L surface along x
  std::size_t ny = 0;  ///< points of the S-L surface along y
};

/// The parameters of a complete map (every point valid, nx, ny >= 2) as given.
[[nodiscard]] ArealParameters areal_parameters(const HeightMap& surface);

/// The S-L surface of a map: form removal (Levelling::line = least-squares plane,
/// mean = mean height, none), then the areal Gaussian filter of ISO 16610-61, whose
/// weighting function s(x) s(y) is the product of two ISO 16610-21 profile weights, so it
/// is applied exactly as the profile filter along every row and then along every column
/// (lc removes the waviness, ls smooths; same truncation and end effects: `discard`
/// crops ct (lc + ls) at each edge in both directions; `regression` applies the degree-1
/// regression filter along each direction in turn). Throws InvalidInput for a map with
/// invalid points (the areal filter needs every point; naming how many) or one too small
/// for the filter in either direction (naming a cut-off pair that fits).
[[nodiscard]] HeightMap scale_limited_surface(const HeightMap& map, Levelling levelling,
                                              const GaussianFilter& filter);

/// One-sided power spectral density of profiles, averaged over the profiles given:
/// P(f_k) = c |Z_k|^2 dx / n with Z_k = sum_i z_i exp(-2 pi i j k / n) (no window, no
/// detrending: the profiles are the filtered ones), f_k = k / (n dx), k = 0 .. floor(n/2),
/// c = 2 except c = 1 at k = 0 and, for even n, at the Nyquist frequency. With
/// df = 1/(n dx), Parseval's theorem gives sum_k P(f_k) df = mean z^2 = m0 exactly: the
/// PSD integrates to the mean-square height. Units m^2 per (1/m) = m^3.
struct PowerSpectrum {
  std::vector<double> f;     ///< spatial frequency [1/m]
  std::vector<double> psd;   ///< [m^3]
  double df = 0.0;           ///< frequency step [1/m]
  std::size_t profiles = 0;  ///< profiles averaged
  std::string direction;     ///< "profile", "x (rows)" or "y (columns)"
};

/// The PSD of one profile.
[[nodiscard]] PowerSpectrum power_spectrum(const Profile& profile);
/// The mean PSD of the rows (`along_x`) or columns of a complete map.
[[nodiscard]] PowerSpectrum power_spectrum(const HeightMap& map, bool along_x);

/// Spike (outlier) removal before levelling and filtering, off by default. A point is a
/// spike when it departs from the median of the 2w + 1 points around it by more than
/// `threshold` robust standard deviations of the profile, sigma_r = 1.4826 MAD (the
/// median absolute deviation from the median, of the heights after removing their
/// least-squares line; 1.4826 MAD = sigma for Gaussian heights): Hampel's identifier
/// (Hampel 1974; Pearson 2002) with a global scale. A spike is replaced by the straight
/// line between its nearest non-spike neighbours (at an end: the nearest one), so the
/// grid stays uniform. It removes spikes up to w points wide; steps and waviness wider
/// than the window are kept.
struct SpikeRemoval {
  double threshold = 0.0;       ///< in robust standard deviations; 0 = off, else in [3, 1000]
  std::size_t half_window = 2;  ///< w, in [1, 50]

  [[nodiscard]] bool is_off() const { return threshold == 0.0; }
  /// Throws InvalidInput naming the field unless threshold is 0 or in [3, 1000] and w is
  /// in [1, 50].
  void validate() const;
};

/// Removes spikes from `profile` in place; returns how many points were replaced.
std::size_t remove_spikes(Profile& profile, const SpikeRemoval& spikes);
/// The same along each row of `map` (each run of consecutive valid points of at least
/// 2w + 1 points); returns how many points were replaced.
std::size_t remove_spikes(HeightMap& map, const SpikeRemoval& spikes);

/// A cut-off pair (lc, ls) that fits profiles of nx points at dx and, when ny > 0, of ny
/// points at dy, with `filter`'s truncation and end effects: the longest standard pair of
/// ISO 3274 Table 1 (lc, ls) = (0.08 mm, 2.5 um), (0.25 mm, 2.5 um), (0.8 mm, 2.5 um),
/// (2.5 mm, 8 um), (8 mm, 25 um) that fits (ls >= 5 spacings, the scan at least
/// min_points()); else ls = 5 spacings rounded up to 2 significant digits with the longest
/// lc that fits, if that lc is at least 5 ls. Returns GaussianFilter::none() when no pair
/// fits.
[[nodiscard]] GaussianFilter working_cutoff_pair(const GaussianFilter& filter, std::size_t nx,
                                                 double dx, std::size_t ny = 0, double dy = 0.0);
/// "--lc 27 um --ls 0.64 um (a standard pair)" or a sentence saying that no pair fits.
[[nodiscard]] std::string cutoff_pair_advice(const GaussianFilter& filter, std::size_t nx,
                                             double dx, std::size_t ny = 0, double dy = 0.0);

}  // namespace asperity::surface
