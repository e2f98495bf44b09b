#pragma once
// Roughness parameters from measured profiles (thesis ch. 5-6, Eq. 5.1; McCool 1986):
// ISO 16610-21 Gaussian band-pass filter, spectral moments, the Greenwood-Williamson
// parameters sigma, eta, R, the equivalent isotropic surface of an anisotropic scan
// pair, the combination of two surfaces, and the plasticity index.
// All quantities in SI units.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "asperity/contact/material.hpp"
#include "asperity/surface/profile.hpp"

namespace asperity::surface {

/// Spectral moments of a profile: m0 = <y^2>, m2 = <y'^2>, m4 = <y''^2> (Eq. 5.1;
/// McCool). They add when two surfaces are combined, and every Greenwood-Williamson
/// parameter follows from them (SEED_NOTES.md "Roughness").
struct SpectralMoments {
  double m0 = 0.0;  ///< mean-square height [m^2]
  double m2 = 0.0;  ///< mean-square slope [-]
  double m4 = 0.0;  ///< mean-square curvature [m^-2]

  /// Throws InvalidInput unless all three are finite and > 0.
  void validate(std::string_view name = "spectral moments") const;

  /// rms height sigma = sqrt(m0) [m].
  [[nodiscard]] double sigma() const;
  /// Areal density of asperities eta = m4 / (6 pi sqrt(3) m2) [m^-2].
  [[nodiscard]] double eta() const;
  /// Mean asperity-tip radius R = 0.375 sqrt(pi / m4) [m].
  [[nodiscard]] double R() const;
  /// Bandwidth parameter alpha = m0 m4 / m2^2 (>= 1 for any real profile).
  [[nodiscard]] double alpha() const;
  /// beta = sigma R eta = 0.02036 sqrt(alpha).
  [[nodiscard]] double beta() const;
  /// Standard deviation of asperity-tip heights, sigma sqrt(1 - 3.717e-4 / beta^2)
  /// [m]. Throws InvalidInput when beta <= 0.01928 (no real asperity spread).
  [[nodiscard]] double sigma_a() const;

  /// The moments that give sigma, eta and R: m0 = sigma^2, m4 = pi (0.375/R)^2,
  /// m2 = m4 / (6 pi sqrt(3) eta). Throws InvalidInput unless all three are > 0.
  [[nodiscard]] static SpectralMoments from_parameters(double sigma, double eta, double R);

  /// Combination of two surfaces in contact: the moments add.
  friend SpectralMoments operator+(const SpectralMoments& a, const SpectralMoments& b) {
    return {a.m0 + b.m0, a.m2 + b.m2, a.m4 + b.m4};
  }
};

/// Moments of the rough surface equivalent to two surfaces in contact (moments add;
/// Eq. 5.1 "combined spectral moments").
[[nodiscard]] SpectralMoments combine(const SpectralMoments& a, const SpectralMoments& b);

/// How m2 and m4 of the equivalent isotropic surface follow from scans in the
/// directions of maximum and minimum slope. m0 is always the arithmetic mean
/// (m0_max + m0_min)/2 (Eq. 5.1).
enum class IsotropicRule {
  geometric,   ///< m2e = sqrt(m2_max m2_min), m4e = sqrt(m4_max m4_min) (McCool; default)
  arithmetic,  ///< m2e = (m2_max + m2_min)/2, m4e = (m4_max + m4_min)/2
};
IsotropicRule parse_isotropic_rule(std::string_view text, std::string_view field = "rule");
std::string_view to_string(IsotropicRule r);

/// Equivalent isotropic moments from the two principal directions (Eq. 5.1).
/// Which argument is the max-slope one does not matter for either rule.
[[nodiscard]] SpectralMoments equivalent_isotropic(const SpectralMoments& max_slope,
                                                   const SpectralMoments& min_slope,
                                                   IsotropicRule rule = IsotropicRule::geometric);

/// Weighted mean of the moments of several scans along one direction (weights are
/// typically the numbers of points). Throws InvalidInput when empty.
[[nodiscard]] SpectralMoments average_moments(const std::vector<SpectralMoments>& moments,
                                              const std::vector<double>& weights);

/// Plasticity index psi = (2 E* / (pi K H)) sqrt(sigma_a / R) with the spread of
/// asperity heights sigma_a (SEED_NOTES.md "Rough flat"; reproduces Table 5.4 with
/// H = 5.8 GPa). Uses E*, H and nu (for K) of `pair`; its radius is not used.
[[nodiscard]] double plasticity_index(const contact::ContactPair& pair,
                                      const SpectralMoments& moments);

/// How the ends of a profile are treated by the Gaussian filter.
enum class EndEffects {
  /// Leave out the ends where the truncated weighting function does not fit in the
  /// data (ct * cut-off at each end, the ISO "run-in/run-out"). The filtered profile
  /// is shorter than the input. Default.
  discard,
  /// Keep every point: near the ends the mean line is the Gaussian-weighted
  /// least-squares straight line (a Gaussian regression filter of degree 1, ISO
  /// 16610-28 style). In the interior it equals the plain Gaussian filter.
  regression,
};
/// How the Gaussian filter's convolution is computed. Both give the same profile to
/// round-off (tested to 1e-12 of the profile's rms on the shipped profiles).
enum class Convolution {
  fft,     ///< FFT overlap-save (KISS FFT, double), O(n log h) for h = ct cut-off / dx
  direct,  ///< direct summation, O(n h): the reference
};

EndEffects parse_end_effects(std::string_view text, std::string_view field = "end");
std::string_view to_string(EndEffects e);

/// ISO 16610-21 Gaussian profile filter used as a band-pass (thesis: lc = 0.8 mm,
/// ls = 0.02 mm). Weighting function s(x) = exp(-pi (x/(a c))^2) / (a c) with
/// a = sqrt(ln 2 / pi) and c the cut-off; it passes 50 % of the amplitude of a
/// sinusoid of wavelength c. The roughness profile is r = z - s_lc * z (long-wave
/// cut-off lc removes waviness), smoothed by s_ls (short-wave cut-off ls removes
/// noise and stylus effects). The filter is a convolution in double
/// precision (by FFT overlap-save, or directly: `convolution`), with the weights truncated at
/// +-ct*cut-off and renormalised to unit sum on the grid. With the default ct = 1 the neglected
/// weight is 1e-7 and the transmission at the cut-offs is 50 % to 1e-7; the shorter ct = 0.5 often
/// used with ISO 16610-21 neglects 0.76 % and passes 51.1 % (low-pass) / 48.9 % (roughness) at the
/// cut-off.
struct GaussianFilter {
  double lc = 0.8e-3;       ///< long-wave cut-off [m]; 0 = no long-wave filter
  double ls = 20e-6;        ///< short-wave cut-off [m]; 0 = no short-wave filter
  double truncation = 1.0;  ///< ct: weights kept for |x| <= ct * cut-off, in [0.5, 3]
  EndEffects end = EndEffects::discard;
  Convolution convolution = Convolution::fft;

  /// No filtering at all.
  static GaussianFilter none() { return {.lc = 0.0, .ls = 0.0}; }
  [[nodiscard]] bool is_none() const { return lc == 0.0 && ls == 0.0; }

  /// Throws InvalidInput unless lc, ls >= 0, ls < lc when both are given, and ct in
  /// [0.5, 3].
  void validate() const;
  /// Amplitude transmission of the band-pass for a sinusoid of wavelength `lambda`
  /// (analytic, untruncated weights): (1 - exp(-pi (a lc/lambda)^2)) exp(-pi (a ls/lambda)^2).
  [[nodiscard]] double transmission(double lambda) const;
  /// Shortest profile (number of points) this filter accepts at spacing dx.
  [[nodiscard]] std::size_t min_points(double dx) const;
  /// Longest long-wave cut-off (rounded down to 3 significant digits) that a profile of
  /// n points at spacing dx admits with this filter's ls, ct and end effects; 0 when
  /// none above ls does.
  [[nodiscard]] double longest_lc(std::size_t n, double dx) const;
  /// What to do about a profile of n points that is too short: the longest lc it
  /// allows (and the largest standard cut-off below it), for the error message.
  [[nodiscard]] std::string shorter_lc_advice(std::size_t n, double dx) const;
  /// Filters a profile. Throws InvalidInput (naming the profile's source) when the
  /// profile is shorter than the filter needs (with `discard`: 2 ct (lc + ls) plus
  /// one lc of evaluation length; with `regression`: lc) or when ls < 5 dx (the
  /// sampled weights would no longer be Gaussian).
  [[nodiscard]] Profile apply(const Profile& profile) const;
};

/// Gaussian low-pass (the mean line) of a profile at cut-off `cutoff`, with weights
/// truncated at +-ct*cutoff. With `discard` the result holds the points
/// [h, n-1-h] with h = floor(ct cutoff/dx); with `regression` all n points.
[[nodiscard]] Profile gaussian_mean_line(const Profile& profile, double cutoff,
                                         double truncation = 1.0,
                                         EndEffects end = EndEffects::discard,
                                         Convolution convolution = Convolution::fft);

/// Spectral moments of a (levelled, filtered) profile, Eq. 5.1: m0 = <y^2> about
/// zero (the filtered profile has zero mean; a profile that was neither levelled
/// nor filtered keeps its offset in m0), m2 = <((y[i+1]-y[i])/dx)^2> over the n-1
/// forward differences, m4 = <((y[i+1]-2y[i]+y[i-1])/dx^2)^2> over the n-2 central
/// second differences. For a sinusoid of wavenumber k these underestimate m2 and
/// m4 by the factors (sin(k dx/2)/(k dx/2))^2 and ^4, i.e. relative errors of
/// about (k dx)^2/12 and (k dx)^2/6 (0.8 % and 1.6 % at a wavelength of 20 dx,
/// 0.03 % and 0.07 % at 100 dx): sample densely compared with ls. Needs at least
/// 3 points.
[[nodiscard]] SpectralMoments spectral_moments(const Profile& profile);

/// One profile through the pipeline: level, filter, moments.
struct ProcessedProfile {
  Profile levelled;
  Profile filtered;
  SpectralMoments moments;
};
[[nodiscard]] ProcessedProfile process_profile(const Profile& raw, Levelling levelling,
                                               const GaussianFilter& filter);

/// What process_profile() gives for the moments, without keeping the levelled and
/// filtered profiles: the profile is levelled in place and freed once filtered, so that
/// memory peaks at three profiles (input, mean line, filtered) instead of five.
struct ProfileMoments {
  SpectralMoments moments;
  std::size_t points = 0;  ///< of the filtered profile
  double length = 0.0;     ///< of the filtered profile [m]
};
/// `inspect`, when given, is called with the filtered profile before it is freed (for the
/// texture parameters and the PSD of the same profile).
[[nodiscard]] ProfileMoments profile_moments(
    Profile raw, Levelling levelling, const GaussianFilter& filter,
    const std::function<void(const Profile& filtered)>& inspect = {});

/// Moments of an areal map along its two axes: each row (x) and column (y) is
/// levelled, filtered and analysed as a profile; the moments of each direction are
/// the point-weighted means over its profiles. Profiles too short for the filter
/// (after cutting at invalid points) are left out; throws if none is left in a
/// direction.
struct DirectionalMoments {
  SpectralMoments x;  ///< along the rows
  SpectralMoments y;  ///< along the columns
  std::size_t x_profiles = 0;
  std::size_t y_profiles = 0;
};
[[nodiscard]] DirectionalMoments areal_moments(const HeightMap& map, Levelling levelling,
                                               const GaussianFilter& filter);

}  // namespace asperity::surface
