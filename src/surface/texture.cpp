#include "asperity/surface/texture.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <kissfft/kissfft.hh>
#include <optional>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::surface {
namespace {

std::string name_of(const std::string& source, const char* fallback) {
  return source.empty() ? std::string(fallback) : source;
}

// Moments about zero of the heights: mean |z|, z^2, z^3, z^4.
struct HeightSums {
  double a = 0, q = 0, s = 0, k = 0;
  std::size_t n = 0;
  void add(double v) {
    const double v2 = v * v;
    a += std::abs(v);
    q += v2;
    s += v2 * v;
    k += v2 * v2;
    ++n;
  }
};

double median_of(std::vector<double>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  double m = *mid;
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), mid));
  return m;
}

// Heights minus their least-squares line (for spike detection only).
std::vector<double> detrended(const double* z, std::size_t n) {
  double sx = 0, sz = 0, sxx = 0, sxz = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto x = static_cast<double>(i);
    sx += x;
    sz += z[i];
    sxx += x * x;
    sxz += x * z[i];
  }
  const auto dn = static_cast<double>(n);
  const double det = dn * sxx - sx * sx;
  const double b = det > 0.0 ? (dn * sxz - sx * sz) / det : 0.0;
  const double a = (sz - b * sx) / dn;
  std::vector<double> r(n);
  for (std::size_t i = 0; i < n; ++i) r[i] = z[i] - (a + b * static_cast<double>(i));
  return r;
}

// Hampel identifier on z[0..n) (stride 1), replacing spikes by linear interpolation.
std::size_t despike_run(double* z, std::size_t n, const SpikeRemoval& s) {
  const std::size_t w = s.half_window;
  if (n < 2 * w + 1) return 0;
  const auto r = detrended(z, n);
  std::vector<double> tmp(r);
  const double med = median_of(tmp);
  for (auto& v : tmp) v = std::abs(v - med);
  const double sigma_r = 1.4826 * median_of(tmp);
  std::vector<char> spike(n, 0);
  std::size_t count = 0;
  std::vector<double> win;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t lo = i >= w ? i - w : 0;
    const std::size_t hi = std::min(n - 1, i + w);
    win.assign(r.begin() + static_cast<std::ptrdiff_t>(lo),
               r.begin() + static_cast<std::ptrdiff_t>(hi + 1));
    const double local = median_of(win);
    if (std::abs(r[i] - local) > s.threshold * sigma_r) {
      spike[i] = 1;
      ++count;
    }
  }
  // Nothing to replace, or nothing to replace it with (every point flagged: no scale).
  if (count == 0 || count == n) return 0;
  std::size_t i = 0;
  while (i < n) {
    if (!spike[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < n && spike[j]) ++j;
    // Spikes i..j-1 between the good points i-1 and j.
    const bool left = i > 0, right = j < n;
    for (std::size_t k = i; k < j; ++k) {
      if (left && right) {
        const double t = static_cast<double>(k - i + 1) / static_cast<double>(j - i + 1);
        z[k] = z[i - 1] + t * (z[j] - z[i - 1]);
      } else {
        z[k] = left ? z[i - 1] : z[j];
      }
    }
    i = j;
  }
  return count;
}

// The Gaussian low-pass of every row (along_x) or column of a complete map.
HeightMap lowpass_map(const HeightMap& m, double cutoff, const GaussianFilter& f, bool along_x) {
  const std::size_t nlines = along_x ? m.ny : m.nx;
  const std::size_t len = along_x ? m.nx : m.ny;
  const double step = along_x ? m.dx : m.dy;
  std::vector<Profile> out(nlines);
  Profile p;
  p.dx = step;
  p.x0 = along_x ? m.x0 : m.y0;
  p.source = m.source;
  p.z.resize(len);
  for (std::size_t l = 0; l < nlines; ++l) {
    for (std::size_t i = 0; i < len; ++i) p.z[i] = along_x ? m.z[i + m.nx * l] : m.z[l + m.nx * i];
    out[l] = gaussian_mean_line(p, cutoff, f.truncation, f.end, f.convolution);
  }
  HeightMap r = m;
  r.valid.clear();
  const std::size_t newlen = out.front().z.size();
  if (along_x) {
    r.nx = newlen;
    r.x0 = out.front().x0;
  } else {
    r.ny = newlen;
    r.y0 = out.front().x0;
  }
  r.z.assign(r.nx * r.ny, 0.0);
  for (std::size_t l = 0; l < nlines; ++l) {
    for (std::size_t i = 0; i < newlen; ++i) {
      (along_x ? r.z[i + r.nx * l] : r.z[l + r.nx * i]) = out[l].z[i];
    }
  }
  return r;
}

HeightMap lowpass_areal(const HeightMap& m, double cutoff, const GaussianFilter& f) {
  return lowpass_map(lowpass_map(m, cutoff, f, true), cutoff, f, false);
}

// z - L(z) on the points of L (which may be a cropped window of z).
HeightMap subtract_lowpass(const HeightMap& z, const HeightMap& low) {
  HeightMap r = low;
  const auto ox = static_cast<std::size_t>(std::llround((low.x0 - z.x0) / z.dx));
  const auto oy = static_cast<std::size_t>(std::llround((low.y0 - z.y0) / z.dy));
  for (std::size_t iy = 0; iy < low.ny; ++iy) {
    for (std::size_t ix = 0; ix < low.nx; ++ix) {
      r.z[ix + r.nx * iy] = z.z[(ix + ox) + z.nx * (iy + oy)] - low.z[ix + low.nx * iy];
    }
  }
  return r;
}

void level_map(HeightMap& m, Levelling how) {
  if (how == Levelling::none) return;
  const std::size_t n = m.z.size();
  if (how == Levelling::mean) {
    double s = 0;
    for (double v : m.z) s += v;
    const double mean = s / static_cast<double>(n);
    for (double& v : m.z) v -= mean;
    return;
  }
  // Least-squares plane z = a + b x + c y on centred coordinates (x and y uncorrelated on
  // a full grid, so the normal equations are diagonal).
  const double cx = 0.5 * static_cast<double>(m.nx - 1), cy = 0.5 * static_cast<double>(m.ny - 1);
  double sz = 0, sxz = 0, syz = 0, sxx = 0, syy = 0;
  for (std::size_t iy = 0; iy < m.ny; ++iy) {
    for (std::size_t ix = 0; ix < m.nx; ++ix) {
      const double x = static_cast<double>(ix) - cx, y = static_cast<double>(iy) - cy;
      const double v = m.z[ix + m.nx * iy];
      sz += v;
      sxz += x * v;
      syz += y * v;
      sxx += x * x;
      syy += y * y;
    }
  }
  const double a = sz / static_cast<double>(n);
  const double b = sxx > 0 ? sxz / sxx : 0.0, c = syy > 0 ? syz / syy : 0.0;
  for (std::size_t iy = 0; iy < m.ny; ++iy) {
    for (std::size_t ix = 0; ix < m.nx; ++ix) {
      m.z[ix + m.nx * iy] -=
          a + b * (static_cast<double>(ix) - cx) + c * (static_cast<double>(iy) - cy);
    }
  }
}

// The periodogram of z[0..n) with stride, accumulated into psd (size n/2 + 1).
void add_periodogram(const kissfft<double>& fft, std::vector<std::complex<double>>& in,
                     std::vector<std::complex<double>>& out, double dx, std::vector<double>& psd) {
  const std::size_t n = in.size();
  fft.transform(in.data(), out.data());
  for (std::size_t k = 0; k < psd.size(); ++k) {
    const double c = (k == 0 || (n % 2 == 0 && k == n / 2)) ? 1.0 : 2.0;
    psd[k] += c * std::norm(out[k]) * dx / static_cast<double>(n);
  }
}

PowerSpectrum spectrum_of_lines(const std::vector<const double*>& lines, std::size_t stride,
                                std::size_t n, double dx, const std::string& direction) {
  if (n < 2) throw InvalidInput(fmt::format("a PSD needs at least 2 points, {} given", n));
  PowerSpectrum s;
  s.direction = direction;
  s.profiles = lines.size();
  s.df = 1.0 / (static_cast<double>(n) * dx);
  s.psd.assign(n / 2 + 1, 0.0);
  const kissfft<double> fft(n, false);
  std::vector<std::complex<double>> in(n), out(n);
  for (const double* z : lines) {
    for (std::size_t i = 0; i < n; ++i) in[i] = {z[i * stride], 0.0};
    add_periodogram(fft, in, out, dx, s.psd);
  }
  for (auto& p : s.psd) p /= static_cast<double>(lines.size());
  for (std::size_t k = 0; k < s.psd.size(); ++k) s.f.push_back(static_cast<double>(k) * s.df);
  return s;
}

void require_complete(const HeightMap& m, const char* what) {
  m.validate();
  const std::size_t invalid = m.invalid_count();
  if (invalid > 0) {
    throw InvalidInput(
        fmt::format("{}: {} needs every point of the map, and {} of its {} x {} points are invalid",
                    name_of(m.source, "map"), what, invalid, m.nx, m.ny));
  }
  if (m.nx < 2 || m.ny < 2) {
    throw InvalidInput(fmt::format("{}: {} needs at least 2 x 2 points, the map has {} x {}",
                                   name_of(m.source, "map"), what, m.nx, m.ny));
  }
}

// 5 spacings rounded up to 2 significant digits.
double round_up_2(double v) {
  const double step = std::pow(10.0, std::floor(std::log10(v)) - 1.0);
  return std::ceil(v / step * (1.0 - 1e-12)) * step;
}

bool pair_fits(const GaussianFilter& f, std::size_t n, double dx) {
  return f.ls >= 5.0 * dx * (1.0 - 1e-9) && f.min_points(dx) <= n;
}

std::string length_text(double v) {
  return v >= 1e-3 ? fmt::format("{:.3g}mm", v * 1e3) : fmt::format("{:.3g}um", v * 1e6);
}

}  // namespace

ProfileParameters profile_parameters(const Profile& roughness, double section_length) {
  roughness.validate();
  const auto& z = roughness.z;
  const std::size_t n = z.size();
  const std::string name = name_of(roughness.source, "profile");
  if (n < 3) {
    throw InvalidInput(
        fmt::format("{}: the ISO 21920-2 parameters need at least 3 points, {} given", name, n));
  }
  core::require_non_negative("section_length", section_length);
  HeightSums h;
  for (double v : z) h.add(v);
  const auto dn = static_cast<double>(n);
  ProfileParameters p;
  p.Ra = h.a / dn;
  p.Rq = std::sqrt(h.q / dn);
  if (!(p.Rq > 0.0)) {
    throw InvalidInput(
        fmt::format("{}: the profile is flat (Rq = 0): no texture parameters", name));
  }
  p.Rsk = (h.s / dn) / (p.Rq * p.Rq * p.Rq);
  p.Rku = (h.k / dn) / (p.Rq * p.Rq * p.Rq * p.Rq);
  double s2 = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double d = (z[i + 1] - z[i]) / roughness.dx;
    s2 += d * d;
  }
  p.Rdq = std::sqrt(s2 / static_cast<double>(n - 1));
  std::size_t per = n;
  if (section_length > 0.0) {
    per = static_cast<std::size_t>(std::llround(section_length / roughness.dx));
    if (per < 2 || per > n) per = n;
  }
  p.sections = n / per;
  p.section_length = static_cast<double>(per) * roughness.dx;
  double sum = 0.0;
  for (std::size_t s = 0; s < p.sections; ++s) {
    const auto b = z.begin() + static_cast<std::ptrdiff_t>(s * per);
    const auto [lo, hi] = std::minmax_element(b, b + static_cast<std::ptrdiff_t>(per));
    sum += *hi - *lo;
  }
  p.Rz = sum / static_cast<double>(p.sections);
  return p;
}

ArealParameters areal_parameters(const HeightMap& m) {
  require_complete(m, "the ISO 25178-2 parameters");
  HeightSums h;
  for (double v : m.z) h.add(v);
  const auto dn = static_cast<double>(m.z.size());
  ArealParameters a;
  a.nx = m.nx;
  a.ny = m.ny;
  a.Sa = h.a / dn;
  a.Sq = std::sqrt(h.q / dn);
  if (!(a.Sq > 0.0)) {
    throw InvalidInput(fmt::format("{}: the surface is flat (Sq = 0): no texture parameters",
                                   name_of(m.source, "map")));
  }
  a.Ssk = (h.s / dn) / (a.Sq * a.Sq * a.Sq);
  a.Sku = (h.k / dn) / (a.Sq * a.Sq * a.Sq * a.Sq);
  double sx = 0.0, sy = 0.0;
  for (std::size_t iy = 0; iy < m.ny; ++iy) {
    for (std::size_t ix = 0; ix + 1 < m.nx; ++ix) {
      const double d = (m.z[ix + 1 + m.nx * iy] - m.z[ix + m.nx * iy]) / m.dx;
      sx += d * d;
    }
  }
  for (std::size_t iy = 0; iy + 1 < m.ny; ++iy) {
    for (std::size_t ix = 0; ix < m.nx; ++ix) {
      const double d = (m.z[ix + m.nx * (iy + 1)] - m.z[ix + m.nx * iy]) / m.dy;
      sy += d * d;
    }
  }
  a.Sdq = std::sqrt(sx / static_cast<double>((m.nx - 1) * m.ny) +
                    sy / static_cast<double>(m.nx * (m.ny - 1)));
  return a;
}

HeightMap scale_limited_surface(const HeightMap& map, Levelling levelling,
                                const GaussianFilter& filter) {
  require_complete(map, "the areal Gaussian filter (ISO 16610-61)");
  filter.validate();
  HeightMap m = map;
  m.valid.clear();
  level_map(m, levelling);
  if (filter.is_none()) return m;
  const double spacing = std::max(m.dx, m.dy);
  const bool ls_ok = filter.ls == 0.0 || filter.ls >= 5.0 * spacing * (1.0 - 1e-9);
  if (!ls_ok || filter.min_points(m.dx) > m.nx || filter.min_points(m.dy) > m.ny) {
    throw InvalidInput(fmt::format(
        "{}: the map ({} x {} points, {:.6g} x {:.6g} mm at {:.6g} x {:.6g} um) does not admit the "
        "filter lc = {:.6g} mm, ls = {:.6g} um ({}): {}",
        name_of(m.source, "map"), m.nx, m.ny, m.dx * static_cast<double>(m.nx - 1) * 1e3,
        m.dy * static_cast<double>(m.ny - 1) * 1e3, m.dx * 1e6, m.dy * 1e6, filter.lc * 1e3,
        filter.ls * 1e6,
        ls_ok ? std::string("the map is too small")
              : fmt::format("ls is below 5 sample spacings, {:.6g} um", 5.0 * spacing * 1e6),
        cutoff_pair_advice(filter, m.nx, m.dx, m.ny, m.dy)));
  }
  HeightMap r = m;
  if (filter.lc > 0.0) r = subtract_lowpass(m, lowpass_areal(m, filter.lc, filter));
  if (filter.ls > 0.0) r = lowpass_areal(r, filter.ls, filter);
  return r;
}

PowerSpectrum power_spectrum(const Profile& profile) {
  profile.validate();
  return spectrum_of_lines({profile.z.data()}, 1, profile.z.size(), profile.dx, "profile");
}

PowerSpectrum power_spectrum(const HeightMap& map, bool along_x) {
  require_complete(map, "a PSD of the rows and columns");
  std::vector<const double*> lines;
  if (along_x) {
    for (std::size_t iy = 0; iy < map.ny; ++iy) lines.push_back(map.z.data() + map.nx * iy);
    return spectrum_of_lines(lines, 1, map.nx, map.dx, "x (rows)");
  }
  for (std::size_t ix = 0; ix < map.nx; ++ix) lines.push_back(map.z.data() + ix);
  return spectrum_of_lines(lines, map.nx, map.ny, map.dy, "y (columns)");
}

void SpikeRemoval::validate() const {
  if (threshold != 0.0) core::require_in_closed("spikes.threshold", threshold, 3.0, 1000.0);
  core::require_in_closed("spikes.half_window", static_cast<double>(half_window), 1.0, 50.0);
}

std::size_t remove_spikes(Profile& profile, const SpikeRemoval& spikes) {
  spikes.validate();
  if (spikes.is_off()) return 0;
  profile.validate();
  return despike_run(profile.z.data(), profile.z.size(), spikes);
}

std::size_t remove_spikes(HeightMap& map, const SpikeRemoval& spikes) {
  spikes.validate();
  if (spikes.is_off()) return 0;
  map.validate();
  std::size_t count = 0;
  std::vector<double> run;
  for (std::size_t iy = 0; iy < map.ny; ++iy) {
    std::size_t ix = 0;
    while (ix < map.nx) {
      if (!map.is_valid(ix, iy)) {
        ++ix;
        continue;
      }
      std::size_t end = ix;
      while (end < map.nx && map.is_valid(end, iy)) ++end;
      count += despike_run(map.z.data() + ix + map.nx * iy, end - ix, spikes);
      ix = end;
    }
  }
  return count;
}

GaussianFilter working_cutoff_pair(const GaussianFilter& filter, std::size_t nx, double dx,
                                   std::size_t ny, double dy) {
  constexpr double kPairs[][2] = {
      {8e-3, 25e-6}, {2.5e-3, 8e-6}, {0.8e-3, 2.5e-6}, {0.25e-3, 2.5e-6}, {0.08e-3, 2.5e-6}};
  auto fits = [&](const GaussianFilter& f) {
    return pair_fits(f, nx, dx) && (ny == 0 || pair_fits(f, ny, dy));
  };
  GaussianFilter f = filter;
  for (const auto& p : kPairs) {
    f.lc = p[0];
    f.ls = p[1];
    if (fits(f)) return f;
  }
  f.ls = round_up_2(5.0 * std::max(dx, ny > 0 ? dy : 0.0));
  f.lc = f.longest_lc(nx, dx);
  if (ny > 0) f.lc = std::min(f.lc, f.longest_lc(ny, dy));
  if (f.lc >= 5.0 * f.ls && fits(f)) return f;
  return GaussianFilter::none();
}

std::string cutoff_pair_advice(const GaussianFilter& filter, std::size_t nx, double dx,
                               std::size_t ny, double dy) {
  const auto f = working_cutoff_pair(filter, nx, dx, ny, dy);
  if (f.is_none()) {
    return fmt::format(
        "no cut-off pair with ls >= 5 spacings and lc >= 5 ls fits this {} (end effects '{}'): "
        "use --filter none or a larger scan",
        ny > 0 ? "map" : "profile", to_string(filter.end));
  }
  const bool standard = f.ls == 2.5e-6 || f.ls == 8e-6 || f.ls == 25e-6;
  return fmt::format("a cut-off pair that fits: --lc {} --ls {}{}", length_text(f.lc),
                     length_text(f.ls),
                     standard ? " (ISO 3274 standard pair)" : " (not a standard pair)");
}

}  // namespace asperity::surface
