#include "asperity/surface/roughness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "asperity/core/error.hpp"
#include "asperity/core/parallel.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/surface/texture.hpp"
#include "detail/convolution.hpp"

namespace asperity::surface {
namespace {

constexpr double kPi = std::numbers::pi;
// 6 pi sqrt(3): eta = m4 / (6 pi sqrt(3) m2).
const double kEtaFactor = 6.0 * kPi * std::sqrt(3.0);
// Smallest beta with a real asperity-height spread: sqrt(3.717e-4).
constexpr double kSigmaAConstant = 3.717e-4;
// ISO 16610-21: alpha = sqrt(ln 2 / pi).
const double kGaussAlpha = std::sqrt(std::numbers::ln2 / kPi);

std::string source_name(const Profile& p) {
  return p.source.empty() ? "profile" : p.source;
}

}  // namespace

// ---------------------------------------------------------------- moments

void SpectralMoments::validate(std::string_view name) const {
  for (auto [field, v] : {std::pair{"m0", m0}, std::pair{"m2", m2}, std::pair{"m4", m4}}) {
    if (!std::isfinite(v) || v <= 0.0) {
      throw InvalidInput(
          fmt::format("{}: {} = {:.6g} must be a finite number > 0 (a flat or "
                      "constant profile has no roughness parameters)",
                      name, field, v));
    }
  }
}

double SpectralMoments::sigma() const {
  return std::sqrt(m0);
}
double SpectralMoments::eta() const {
  return m4 / (kEtaFactor * m2);
}
double SpectralMoments::R() const {
  return 0.375 * std::sqrt(kPi / m4);
}
double SpectralMoments::alpha() const {
  return m0 * m4 / (m2 * m2);
}
double SpectralMoments::beta() const {
  return sigma() * R() * eta();
}

double SpectralMoments::sigma_a() const {
  const double b = beta();
  const double ratio = 1.0 - kSigmaAConstant / (b * b);
  if (!(ratio > 0.0)) {
    throw InvalidInput(fmt::format(
        "beta = sigma R eta = {:.6g} is too small: the spread of asperity heights "
        "sigma_a = sigma sqrt(1 - 3.717e-4/beta^2) needs beta > 0.01928 (bandwidth alpha > "
        "0.8968)",
        b));
  }
  return sigma() * std::sqrt(ratio);
}

SpectralMoments SpectralMoments::from_parameters(double sigma, double eta, double R) {
  core::require_positive("sigma", sigma);
  core::require_positive("eta", eta);
  core::require_positive("R", R);
  const double m4 = kPi * (0.375 / R) * (0.375 / R);
  return {sigma * sigma, m4 / (kEtaFactor * eta), m4};
}

SpectralMoments combine(const SpectralMoments& a, const SpectralMoments& b) {
  return a + b;
}

IsotropicRule parse_isotropic_rule(std::string_view text, std::string_view field) {
  if (text == "geometric") return IsotropicRule::geometric;
  if (text == "arithmetic") return IsotropicRule::arithmetic;
  throw InvalidInput(
      fmt::format("{} = \"{}\" is not allowed: use geometric or arithmetic", field, text));
}

std::string_view to_string(IsotropicRule r) {
  return r == IsotropicRule::geometric ? "geometric" : "arithmetic";
}

SpectralMoments equivalent_isotropic(const SpectralMoments& max_slope,
                                     const SpectralMoments& min_slope, IsotropicRule rule) {
  max_slope.validate("max-slope scan");
  min_slope.validate("min-slope scan");
  SpectralMoments e;
  e.m0 = 0.5 * (max_slope.m0 + min_slope.m0);  // Eq. 5.1
  if (rule == IsotropicRule::geometric) {
    e.m2 = std::sqrt(max_slope.m2 * min_slope.m2);
    e.m4 = std::sqrt(max_slope.m4 * min_slope.m4);
  } else {
    e.m2 = 0.5 * (max_slope.m2 + min_slope.m2);
    e.m4 = 0.5 * (max_slope.m4 + min_slope.m4);
  }
  return e;
}

SpectralMoments average_moments(const std::vector<SpectralMoments>& moments,
                                const std::vector<double>& weights) {
  if (moments.empty()) throw InvalidInput("no profile to average the spectral moments over");
  if (weights.size() != moments.size()) {
    throw InvalidInput(
        fmt::format("{} weights for {} sets of moments", weights.size(), moments.size()));
  }
  SpectralMoments sum;
  double w = 0.0;
  for (std::size_t i = 0; i < moments.size(); ++i) {
    core::require_positive("weight", weights[i]);
    sum.m0 += weights[i] * moments[i].m0;
    sum.m2 += weights[i] * moments[i].m2;
    sum.m4 += weights[i] * moments[i].m4;
    w += weights[i];
  }
  return {sum.m0 / w, sum.m2 / w, sum.m4 / w};
}

double plasticity_index(const contact::ContactPair& pair, const SpectralMoments& moments) {
  core::require_positive("E_star", pair.E_star);
  core::require_positive("H", pair.H);
  moments.validate();
  const double K = pair.K();
  return 2.0 * pair.E_star / (kPi * K * pair.H) * std::sqrt(moments.sigma_a() / moments.R());
}

// ---------------------------------------------------------------- filter

EndEffects parse_end_effects(std::string_view text, std::string_view field) {
  if (text == "discard") return EndEffects::discard;
  if (text == "regression") return EndEffects::regression;
  throw InvalidInput(
      fmt::format("{} = \"{}\" is not allowed: use discard or regression", field, text));
}

std::string_view to_string(EndEffects e) {
  return e == EndEffects::discard ? "discard" : "regression";
}

void GaussianFilter::validate() const {
  core::require_non_negative("lc", lc);
  core::require_non_negative("ls", ls);
  core::require_in_closed("truncation (ct)", truncation, 0.5, 3.0);
  if (lc > 0.0 && ls > 0.0 && !(ls < lc)) {
    throw InvalidInput(fmt::format(
        "ls = {:.6g} m must be smaller than lc = {:.6g} m: the band between them is what the "
        "filter keeps",
        ls, lc));
  }
}

double GaussianFilter::transmission(double lambda) const {
  double t = 1.0;
  if (lc > 0.0) {
    const double u = kGaussAlpha * lc / lambda;
    t *= 1.0 - std::exp(-kPi * u * u);
  }
  if (ls > 0.0) {
    const double u = kGaussAlpha * ls / lambda;
    t *= std::exp(-kPi * u * u);
  }
  return t;
}

namespace {

std::size_t half_width(double cutoff, double truncation, double dx) {
  const double h = std::floor(truncation * cutoff / dx + 1e-9);
  // Callers have checked the profile length, so h fits in the data.
  return h > 1e9 ? static_cast<std::size_t>(1e9) : static_cast<std::size_t>(h);
}

std::vector<double> gaussian_weights(double cutoff, double dx, std::size_t h) {
  std::vector<double> w(2 * h + 1);
  const double scale = 1.0 / (kGaussAlpha * cutoff);
  for (std::size_t k = 0; k <= 2 * h; ++k) {
    const double x = (static_cast<double>(k) - static_cast<double>(h)) * dx * scale;
    w[k] = std::exp(-kPi * x * x);
  }
  return w;
}

}  // namespace

namespace {

// Mean line by direct summation: the reference path (O(n h)).
void mean_line_direct(const std::vector<double>& z, const std::vector<double>& w, std::size_t h,
                      EndEffects end, std::vector<double>& out) {
  const std::size_t n = z.size();
  if (end == EndEffects::discard) {
    double wsum = 0.0;
    for (double v : w) wsum += v;
    out.resize(n - 2 * h);
    for (std::size_t i = h; i + h < n; ++i) {
      double s = 0.0;
      const double* zi = z.data() + (i - h);
      for (std::size_t k = 0; k <= 2 * h; ++k) s += w[k] * zi[k];
      out[i - h] = s / wsum;
    }
    return;
  }
  // Regression: Gaussian-weighted least-squares line through the points within the
  // window, evaluated at the centre (equals the weighted mean where the window is
  // symmetric).
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t lo = i >= h ? i - h : 0;
    const std::size_t hi = std::min(n - 1, i + h);
    double S = 0, Sx = 0, Sxx = 0, Sz = 0, Sxz = 0;
    for (std::size_t j = lo; j <= hi; ++j) {
      const double wj = w[j + h - i];
      const double x = static_cast<double>(j) - static_cast<double>(i);
      S += wj;
      Sx += wj * x;
      Sxx += wj * x * x;
      Sz += wj * z[j];
      Sxz += wj * x * z[j];
    }
    const double det = S * Sxx - Sx * Sx;
    out[i] = det > 1e-12 * S * Sxx ? (Sxx * Sz - Sx * Sxz) / det : Sz / S;
  }
}

// The same by FFT correlation (O(n log h)). With regression, the window sums of the
// weights S, Sx, Sxx for a window k = -a..b come from suffix sums A_p[m] = sum_{k=m}^{h}
// w_k k^p without cancellation; Sz = sum w_k z[i+k] is the zero-padded correlation of
// the whole profile, Sxz = sum k w_k z[i+k] is needed only where the window is cut
// (Sx = 0 elsewhere, where the line's value is the weighted mean Sz / S).
void mean_line_fft(const std::vector<double>& z, const std::vector<double>& w, std::size_t h,
                   EndEffects end, std::vector<double>& out) {
  const std::size_t n = z.size();
  if (end == EndEffects::discard) {
    double wsum = 0.0;
    for (double v : w) wsum += v;
    out.resize(n - 2 * h);
    detail::correlate_fft(z.data(), n, w, h, n - h, out.data());
    for (double& v : out) v /= wsum;
    return;
  }
  std::vector<double> A0(h + 2, 0.0), A1(h + 2, 0.0), A2(h + 2, 0.0);
  for (std::size_t m = h + 1; m-- > 0;) {
    const double k = static_cast<double>(m);
    const double wk = w[h + m];
    A0[m] = A0[m + 1] + wk;
    A1[m] = A1[m + 1] + wk * k;
    A2[m] = A2[m + 1] + wk * k * k;
  }
  out.resize(n);
  detail::correlate_fft(z.data(), n, w, 0, n, out.data());  // Sz
  std::vector<double> kw(w.size());
  for (std::size_t q = 0; q < w.size(); ++q) {
    kw[q] = (static_cast<double>(q) - static_cast<double>(h)) * w[q];
  }
  // Points whose window is cut: [0, min(h, n)) and [max(n - h, min(h, n)), n).
  const std::size_t left_end = std::min(h, n);
  const std::size_t right_begin = n > h ? std::max(n - h, left_end) : left_end;
  std::vector<double> Sxz(left_end + (n - right_begin));
  detail::correlate_fft(z.data(), n, kw, 0, left_end, Sxz.data());
  detail::correlate_fft(z.data(), n, kw, right_begin, n, Sxz.data() + left_end);
  auto cut = [&](std::size_t i, double Sxz_i) {
    const std::size_t a = std::min(i, h), b = std::min(n - 1 - i, h);
    const double S = (A0[0] - A0[b + 1]) + (A0[1] - A0[a + 1]);
    const double Sx = A1[a + 1] - A1[b + 1];
    const double Sxx = (A2[0] - A2[b + 1]) + (A2[1] - A2[a + 1]);
    const double Sz = out[i];
    const double det = S * Sxx - Sx * Sx;
    return det > 1e-12 * S * Sxx ? (Sxx * Sz - Sx * Sxz_i) / det : Sz / S;
  };
  double S_full = 0.0;
  for (double v : w) S_full += v;
  for (std::size_t i = left_end; i < right_begin; ++i) out[i] /= S_full;
  for (std::size_t i = 0; i < left_end; ++i) out[i] = cut(i, Sxz[i]);
  for (std::size_t i = right_begin; i < n; ++i) out[i] = cut(i, Sxz[left_end + i - right_begin]);
}

}  // namespace

Profile gaussian_mean_line(const Profile& profile, double cutoff, double truncation, EndEffects end,
                           Convolution convolution) {
  profile.validate();
  core::require_positive("cut-off", cutoff);
  const std::size_t n = profile.z.size();
  const std::size_t h = half_width(cutoff, truncation, profile.dx);
  if (end == EndEffects::discard && n <= 2 * h) {
    throw InvalidInput(fmt::format(
        "{}: the profile ({} points, {:.6g} mm) is shorter than the Gaussian filter with "
        "cut-off {:.6g} mm needs ({} points): use a longer scan, a shorter cut-off or --end "
        "regression",
        source_name(profile), n, profile.length() * 1e3, cutoff * 1e3, 2 * h + 1));
  }
  const auto w = gaussian_weights(cutoff, profile.dx, h);
  Profile out;
  out.dx = profile.dx;
  out.source = profile.source;
  out.x0 = profile.x0 + (end == EndEffects::discard ? static_cast<double>(h) * profile.dx : 0.0);
  if (convolution == Convolution::direct) {
    mean_line_direct(profile.z, w, h, end, out.z);
  } else {
    mean_line_fft(profile.z, w, h, end, out.z);
  }
  return out;
}

std::size_t GaussianFilter::min_points(double dx) const {
  std::size_t n = 3;
  if (lc > 0.0) {
    const auto lc_points = static_cast<std::size_t>(std::ceil(lc / dx)) + 1;
    n = std::max(n, lc_points);
    if (end == EndEffects::discard) n += 2 * half_width(lc, truncation, dx);
  }
  if (ls > 0.0 && end == EndEffects::discard) n += 2 * half_width(ls, truncation, dx);
  return n;
}

double GaussianFilter::longest_lc(std::size_t n, double dx) const {
  if (n < 2 || !(dx > 0.0)) return 0.0;
  // min_points() = ceil(lc/dx) + 1 [+ 2 floor(ct lc/dx) + 2 floor(ct ls/dx) with discard]
  // <= n: solved for lc with one point to spare for the ceiling, then rounded down to 3
  // significant digits (a value to type) and checked.
  GaussianFilter f = *this;
  const double hs = (end == EndEffects::discard && ls > 0.0)
                        ? static_cast<double>(half_width(ls, truncation, dx))
                        : 0.0;
  const double per_lc = end == EndEffects::discard ? 1.0 + 2.0 * truncation : 1.0;
  const double room = (static_cast<double>(n) - 2.0 - 2.0 * hs) * dx;
  if (!(room > 0.0)) return 0.0;
  const double estimate = room / per_lc;
  const double step = std::pow(10.0, std::floor(std::log10(estimate)) - 2.0);
  // Checked a hair above the value, so that the decimal a user types back fits too.
  for (auto digits = static_cast<long>(std::floor(estimate / step)); digits > 0; --digits) {
    const double v = static_cast<double>(digits) * step;
    if (!(v > ls)) return 0.0;  // no lc above ls fits (ls < lc is required)
    f.lc = v * (1.0 + 1e-9);
    if (f.min_points(dx) <= n) return v;
  }
  return 0.0;
}

std::string GaussianFilter::shorter_lc_advice(std::size_t n, double dx) const {
  // The ISO 3274 / ISO 4288 series of cut-off wavelengths.
  constexpr double kStandard[] = {8e-3, 2.5e-3, 0.8e-3, 0.25e-3, 0.08e-3};
  const double best = longest_lc(n, dx);
  std::string advice;
  if (best > 0.0) {
    advice = fmt::format("a shorter lc (--lc): this profile allows up to {:.3g} mm", best * 1e3);
    for (double c : kStandard) {
      if (c <= best && c > ls) {
        advice += fmt::format(" (the largest standard cut-off below it: {:.3g} mm)", c * 1e3);
        break;
      }
    }
  } else {
    advice = fmt::format("a shorter ls (--ls): no lc above ls = {:.6g} um fits in this profile",
                         ls * 1e6);
  }
  if (end == EndEffects::discard) {
    GaussianFilter r = *this;
    r.end = EndEffects::regression;
    const double reg = r.longest_lc(n, dx);
    if (reg > 0.0) {
      advice +=
          fmt::format("; or --end regression (no run-in/run-out: lc up to {:.3g} mm)", reg * 1e3);
    }
  }
  return advice;
}

Profile GaussianFilter::apply(const Profile& profile) const {
  validate();
  profile.validate();
  const std::string name = source_name(profile);
  // Relative tolerance: a dx fitted to printed x (1.0000000000000008e-06 m for a 1 um
  // step) must not refuse ls = 5 dx exactly.
  if (ls > 0.0 && ls < 5.0 * profile.dx * (1.0 - 1e-9)) {
    throw InvalidInput(fmt::format(
        "{}: the short-wave cut-off ls = {:.6g} um is below 5 sample spacings (dx = {:.6g} um): "
        "the sampled Gaussian would not filter as specified; use ls >= {:.6g} um or no "
        "short-wave filter; {}",
        name, ls * 1e6, profile.dx * 1e6, 5.0 * profile.dx * 1e6,
        cutoff_pair_advice(*this, profile.z.size(), profile.dx)));
  }
  const std::size_t need = min_points(profile.dx);
  if (profile.z.size() < need) {
    throw InvalidInput(fmt::format(
        "{}: the profile ({} points, {:.6g} mm) is shorter than the filter needs ({} points, "
        "{:.6g} mm for lc = {:.6g} mm, ls = {:.6g} um, end effects '{}'): use a longer scan or {}; "
        "{}",
        name, profile.z.size(), profile.length() * 1e3, need,
        static_cast<double>(need - 1) * profile.dx * 1e3, lc * 1e3, ls * 1e6, to_string(end),
        shorter_lc_advice(profile.z.size(), profile.dx),
        cutoff_pair_advice(*this, profile.z.size(), profile.dx)));
  }
  // The roughness profile is written over the mean line (memory: the input, the mean
  // line and, with ls, the smoothed profile).
  Profile r;
  if (lc > 0.0) {
    r = gaussian_mean_line(profile, lc, truncation, end, convolution);
    const std::size_t off =
        static_cast<std::size_t>(std::llround((r.x0 - profile.x0) / profile.dx));
    for (std::size_t i = 0; i < r.z.size(); ++i) r.z[i] = profile.z[i + off] - r.z[i];
  } else {
    r = profile;
  }
  if (ls > 0.0) r = gaussian_mean_line(r, ls, truncation, end, convolution);
  return r;
}

// ---------------------------------------------------------------- pipeline

SpectralMoments spectral_moments(const Profile& profile) {
  profile.validate();
  const auto& y = profile.z;
  const std::size_t n = y.size();
  if (n < 3) {
    throw InvalidInput(
        fmt::format("{}: spectral moments need at least 3 points, the profile has {}",
                    source_name(profile), n));
  }
  double s0 = 0, s2 = 0, s4 = 0;
  for (std::size_t i = 0; i < n; ++i) s0 += y[i] * y[i];
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double d = y[i + 1] - y[i];
    s2 += d * d;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double d = y[i + 1] - 2.0 * y[i] + y[i - 1];
    s4 += d * d;
  }
  const double dx = profile.dx;
  return {s0 / static_cast<double>(n), s2 / (static_cast<double>(n - 1) * dx * dx),
          s4 / (static_cast<double>(n - 2) * dx * dx * dx * dx)};
}

namespace {

// Refuses a processed profile whose heights, slopes or curvatures are at round-off
// level. Levelling and filtering compute each height from sums of the raw heights, so
// a height left over carries an error of a few eps |z| (eps = 2.2e-16), growing like
// sqrt(n) eps for the sums over n points (2e-13 at 1e6 points); the differences behind
// m2 and m4 carry the same. The rms of the raw heights about zero, S, is the scale of
// that error: a straight line or a constant levelled away leaves only it, and m0, m2, m4
// of round-off give absurd parameters (R = 4.6e17 um for z = 0.001 x). Measured heights
// resolve at best ~1e-9 of their magnitude (24-bit converters; float32 storage: 6e-8),
// so rms heights, differences (m2 dx^2) and second differences (m4 dx^4) below 1e-12 S
// are taken as round-off: three orders of magnitude from either side.
constexpr double kRoundOffLevel = 1e-12;

// The rms of the raw heights about zero, scaled by the largest height so that heights
// near the double range do not overflow the sum of squares (which made +-1e300 heights
// look flat); heights above a metre are refused (a wrong unit, not a surface).
double rms_about_zero(const std::vector<double>& z, const std::string& name) {
  double zmax = 0.0;
  for (double v : z) zmax = std::max(zmax, std::abs(v));
  if (zmax > 1.0) {
    throw InvalidInput(fmt::format(
        "{}: heights up to {:.3g} m: a surface profile's heights are micrometres to millimetres "
        "(a profilometer's range), not more than a metre; check the unit of the height column",
        name, zmax));
  }
  double ss = 0.0;
  if (zmax > 0.0) {
    for (double v : z) ss += (v / zmax) * (v / zmax);
  }
  return zmax * std::sqrt(ss / static_cast<double>(z.size()));
}

void refuse_round_off(const std::string& name, double scale, double dx,
                      const SpectralMoments& moments, Levelling levelling,
                      const GaussianFilter& filter) {
  const struct {
    const char* what;
    double rms;
  } left[] = {{"rms height", std::sqrt(moments.m0)},
              {"rms difference of neighbouring heights (m2)", std::sqrt(moments.m2) * dx},
              {"rms second difference of the heights (m4)", std::sqrt(moments.m4) * dx * dx}};
  for (const auto& l : left) {
    if (!(l.rms <= kRoundOffLevel * scale)) continue;  // NaN is left to validate()
    std::string steps;
    if (levelling != Levelling::none) steps = fmt::format("levelling ({})", to_string(levelling));
    if (!filter.is_none()) steps += steps.empty() ? "filtering" : " and filtering";
    throw InvalidInput(fmt::format(
        "{}: the profile is flat{}: its {} is {:.3g} m, at round-off level (below {:g} of the "
        "raw heights' rms {:.6g} m), so there is no roughness to analyse (a straight line or a "
        "constant?)",
        name, steps.empty() ? "" : " after " + steps, l.what, l.rms, kRoundOffLevel, scale));
  }
}

}  // namespace

ProcessedProfile process_profile(const Profile& raw, Levelling levelling,
                                 const GaussianFilter& filter) {
  ProcessedProfile p;
  p.levelled = level(raw, levelling);
  p.filtered = filter.is_none() ? p.levelled : filter.apply(p.levelled);
  p.moments = spectral_moments(p.filtered);
  refuse_round_off(source_name(raw), rms_about_zero(raw.z, source_name(raw)), p.filtered.dx,
                   p.moments, levelling, filter);
  p.moments.validate(source_name(raw));
  return p;
}

ProfileMoments profile_moments(Profile raw, Levelling levelling, const GaussianFilter& filter,
                               const std::function<void(const Profile& filtered)>& inspect) {
  const std::string name = source_name(raw);
  raw.validate();
  const double scale = rms_about_zero(raw.z, name);
  const double dx = raw.dx;
  level_in_place(raw, levelling);
  ProfileMoments out;
  if (filter.is_none()) {
    out.moments = spectral_moments(raw);
    out.points = raw.z.size();
    out.length = raw.length();
    refuse_round_off(name, scale, dx, out.moments, levelling, filter);
    if (inspect) inspect(raw);
  } else {
    Profile filtered = filter.apply(raw);
    raw = Profile{};  // freed before the moments' pass
    out.moments = spectral_moments(filtered);
    out.points = filtered.z.size();
    out.length = filtered.length();
    refuse_round_off(name, scale, dx, out.moments, levelling, filter);
    if (inspect) inspect(filtered);
  }
  out.moments.validate(name);
  return out;
}

DirectionalMoments areal_moments(const HeightMap& map, Levelling levelling,
                                 const GaussianFilter& filter) {
  map.validate();
  if (map.ny < 2) {
    throw InvalidInput(
        fmt::format("{}: a profile has no second direction; give two scans", map.source));
  }
  filter.validate();
  const std::size_t invalid = map.invalid_count();
  if (invalid == map.z.size()) {
    throw InvalidInput(fmt::format("{}: the file holds no valid points (all {} x {} are invalid)",
                                   map.source, map.nx, map.ny));
  }
  const double coarser = std::max(map.dx, map.dy);
  if (filter.ls > 0.0 && filter.ls < 5.0 * coarser * (1.0 - 1e-9)) {
    throw InvalidInput(fmt::format(
        "{}: the short-wave cut-off ls = {:.6g} um is below 5 sample spacings of the map (dx = "
        "{:.6g} um, dy = {:.6g} um): the sampled Gaussian would not filter as specified; {}",
        map.source, filter.ls * 1e6, map.dx * 1e6, map.dy * 1e6,
        cutoff_pair_advice(filter, map.nx, map.dx, map.ny, map.dy)));
  }
  DirectionalMoments out;
  auto run = [&](const std::vector<Profile>& profiles, double spacing, const char* axis,
                 std::size_t& count) {
    const std::size_t min_pts = filter.is_none() ? 3 : filter.min_points(spacing);
    std::vector<SpectralMoments> m;
    std::vector<double> w;
    std::size_t longest = 0;
    // The rows (columns) are independent: spread over the cores, each into its own slot,
    // averaged in order afterwards (the same sums whatever the number of threads).
    std::vector<std::size_t> used;
    for (std::size_t k = 0; k < profiles.size(); ++k) {
      longest = std::max(longest, profiles[k].z.size());
      if (profiles[k].z.size() >= min_pts) used.push_back(k);
    }
    std::vector<ProfileMoments> results(used.size());
    core::parallel_for(used.size(), [&](std::size_t k) {
      results[k] = profile_moments(profiles[used[k]], levelling, filter);
    });
    for (const auto& r : results) {
      m.push_back(r.moments);
      w.push_back(static_cast<double>(r.points));
    }
    if (m.empty()) {
      const std::string cut =
          invalid > 0 ? fmt::format(" ({} of the {} points are invalid)", invalid, map.z.size())
                      : std::string();
      const std::string runs = longest >= 2 ? fmt::format("the longest run has {}", longest)
                                            : std::string("no 2 neighbours are valid");
      if (filter.is_none()) {
        throw InvalidInput(fmt::format(
            "{}: no profile along {} has {} consecutive valid points, the least for the moments "
            "({}){}",
            map.source, axis, min_pts, runs, cut));
      }
      throw InvalidInput(fmt::format(
          "{}: no profile along {} is long enough for the filter: {} consecutive valid points "
          "({:.6g} mm at {:.6g} um) needed, {}{}; use {}{}",
          map.source, axis, min_pts, static_cast<double>(min_pts - 1) * spacing * 1e3,
          spacing * 1e6, runs, cut,
          longest >= 2 ? filter.shorter_lc_advice(longest, spacing) : "another file",
          longest >= 2 && invalid == 0
              ? "; " + cutoff_pair_advice(filter, map.nx, map.dx, map.ny, map.dy)
              : std::string()));
    }
    count = m.size();
    return average_moments(m, w);
  };
  out.x = run(map.rows(), map.dx, "x (rows)", out.x_profiles);
  out.y = run(map.columns(), map.dy, "y (columns)", out.y_profiles);
  return out;
}

}  // namespace asperity::surface
