#include "asperity/surface/profile.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "asperity/core/error.hpp"

namespace asperity::surface {

void Profile::validate() const {
  const std::string_view name = source.empty() ? std::string_view("profile") : source;
  if (z.size() < 2) {
    throw InvalidInput(
        fmt::format("{}: a profile needs at least 2 points, it has {}", name, z.size()));
  }
  if (!std::isfinite(dx) || dx <= 0.0) {
    throw InvalidInput(
        fmt::format("{}: the sampling interval dx = {:.6g} m must be > 0", name, dx));
  }
  if (!std::isfinite(x0)) throw InvalidInput(fmt::format("{}: x0 is not finite", name));
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (!std::isfinite(z[i])) {
      throw InvalidInput(
          fmt::format("{}: height {} (point {}) is not a finite number", name, z[i], i));
    }
  }
}

double Profile::length() const {
  return z.empty() ? 0.0 : dx * static_cast<double>(z.size() - 1);
}

bool HeightMap::is_valid(std::size_t ix, std::size_t iy) const {
  const std::size_t k = ix + nx * iy;
  return (valid.empty() || valid[k] != 0) && std::isfinite(z[k]);
}

std::size_t HeightMap::invalid_count() const {
  std::size_t n = 0;
  for (std::size_t iy = 0; iy < ny; ++iy) {
    for (std::size_t ix = 0; ix < nx; ++ix) n += is_valid(ix, iy) ? 0 : 1;
  }
  return n;
}

void HeightMap::validate() const {
  const std::string_view name = source.empty() ? std::string_view("height map") : source;
  if (nx == 0 || ny == 0) throw InvalidInput(fmt::format("{}: the height map is empty", name));
  if (nx > std::numeric_limits<std::size_t>::max() / ny || z.size() != nx * ny) {
    throw InvalidInput(fmt::format("{}: {} heights for a {} x {} map", name, z.size(), nx, ny));
  }
  if (!valid.empty() && valid.size() != z.size()) {
    throw InvalidInput(
        fmt::format("{}: {} validity flags for {} heights", name, valid.size(), z.size()));
  }
  if (!std::isfinite(dx) || dx <= 0.0) {
    throw InvalidInput(fmt::format("{}: the x spacing dx = {:.6g} m must be > 0", name, dx));
  }
  if (ny > 1 && (!std::isfinite(dy) || dy <= 0.0)) {
    throw InvalidInput(fmt::format("{}: the y spacing dy = {:.6g} m must be > 0", name, dy));
  }
  for (std::size_t k = 0; k < z.size(); ++k) {
    if ((valid.empty() || valid[k]) && std::isinf(z[k])) {
      throw InvalidInput(fmt::format("{}: height {} is infinite", name, k));
    }
  }
}

namespace {

// Longest run of valid points along a line of the map.
template <class Valid, class Height>
Profile longest_run(std::size_t n, double spacing, double origin, Valid is_valid, Height height,
                    std::string source) {
  std::size_t best_start = 0, best_len = 0, start = 0, len = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (is_valid(i)) {
      if (len == 0) start = i;
      ++len;
      if (len > best_len) {
        best_len = len;
        best_start = start;
      }
    } else {
      len = 0;
    }
  }
  Profile p;
  p.dx = spacing;
  p.x0 = origin + spacing * static_cast<double>(best_start);
  p.source = std::move(source);
  p.z.reserve(best_len);
  for (std::size_t i = best_start; i < best_start + best_len; ++i) p.z.push_back(height(i));
  return p;
}

}  // namespace

std::vector<Profile> HeightMap::rows(std::size_t min_points) const {
  std::vector<Profile> out;
  for (std::size_t iy = 0; iy < ny; ++iy) {
    auto p = longest_run(
        nx, dx, x0, [&](std::size_t i) { return is_valid(i, iy); },
        [&](std::size_t i) { return z[i + nx * iy]; },
        ny == 1 ? source : fmt::format("{} row {}", source, iy));
    if (p.z.size() >= std::max<std::size_t>(min_points, 2)) out.push_back(std::move(p));
  }
  return out;
}

std::vector<Profile> HeightMap::columns(std::size_t min_points) const {
  std::vector<Profile> out;
  if (ny < 2) return out;
  for (std::size_t ix = 0; ix < nx; ++ix) {
    auto p = longest_run(
        ny, dy, y0, [&](std::size_t i) { return is_valid(ix, i); },
        [&](std::size_t i) { return z[ix + nx * i]; }, fmt::format("{} column {}", source, ix));
    if (p.z.size() >= std::max<std::size_t>(min_points, 2)) out.push_back(std::move(p));
  }
  return out;
}

Profile HeightMap::as_profile() const {
  if (ny != 1) {
    throw InvalidInput(
        fmt::format("{}: an areal map ({} x {}) is not a single profile", source, nx, ny));
  }
  auto r = rows(2);
  if (invalid_count() == z.size()) {
    throw InvalidInput(
        fmt::format("{}: the file holds no valid points (all {} are invalid)", source, z.size()));
  }
  if (r.empty()) {
    throw InvalidInput(
        fmt::format("{}: the profile has fewer than 2 consecutive valid points", source));
  }
  return std::move(r.front());
}

double HeightMap::rms_height_about_plane() const {
  // Least-squares plane z = a + b x + c y over the valid points, centred coordinates.
  double n = 0, sx = 0, sy = 0, sz = 0;
  for (std::size_t iy = 0; iy < ny; ++iy) {
    for (std::size_t ix = 0; ix < nx; ++ix) {
      if (!is_valid(ix, iy)) continue;
      n += 1;
      sx += static_cast<double>(ix);
      sy += static_cast<double>(iy);
      sz += z[ix + nx * iy];
    }
  }
  if (n < 3) throw InvalidInput(fmt::format("{}: fewer than 3 valid points for Sq", source));
  const double mx = sx / n, my = sy / n, mz = sz / n;
  double sxx = 0, syy = 0, sxy = 0, sxz = 0, syz = 0;
  for (std::size_t iy = 0; iy < ny; ++iy) {
    for (std::size_t ix = 0; ix < nx; ++ix) {
      if (!is_valid(ix, iy)) continue;
      const double u = static_cast<double>(ix) - mx, v = static_cast<double>(iy) - my;
      const double w = z[ix + nx * iy] - mz;
      sxx += u * u;
      syy += v * v;
      sxy += u * v;
      sxz += u * w;
      syz += v * w;
    }
  }
  const double det = sxx * syy - sxy * sxy;
  double b = 0, c = 0;
  if (det > 0) {
    b = (sxz * syy - syz * sxy) / det;
    c = (syz * sxx - sxz * sxy) / det;
  } else if (sxx > 0) {
    b = sxz / sxx;
  } else if (syy > 0) {
    c = syz / syy;
  }
  double ss = 0;
  for (std::size_t iy = 0; iy < ny; ++iy) {
    for (std::size_t ix = 0; ix < nx; ++ix) {
      if (!is_valid(ix, iy)) continue;
      const double r = z[ix + nx * iy] - mz - b * (static_cast<double>(ix) - mx) -
                       c * (static_cast<double>(iy) - my);
      ss += r * r;
    }
  }
  return std::sqrt(ss / n);
}

Levelling parse_levelling(std::string_view text, std::string_view field) {
  if (text == "none") return Levelling::none;
  if (text == "mean") return Levelling::mean;
  if (text == "line") return Levelling::line;
  throw InvalidInput(
      fmt::format("{} = \"{}\" is not allowed: use none, mean or line", field, text));
}

std::string_view to_string(Levelling l) {
  switch (l) {
    case Levelling::none:
      return "none";
    case Levelling::mean:
      return "mean";
    case Levelling::line:
      return "line";
  }
  return "?";
}

void level_in_place(Profile& profile, Levelling how) {
  profile.validate();
  if (how == Levelling::none) return;
  auto& z = profile.z;
  const double n = static_cast<double>(z.size());
  double mean = 0;
  for (double v : z) mean += v;
  mean /= n;
  if (how == Levelling::mean) {
    for (double& v : z) v -= mean;
    return;
  }
  // Least-squares line in the centred index u = i - (n-1)/2.
  const double c = 0.5 * (n - 1.0);
  double suu = 0, suz = 0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double u = static_cast<double>(i) - c;
    suu += u * u;
    suz += u * (z[i] - mean);
  }
  const double slope = suu > 0 ? suz / suu : 0.0;
  for (std::size_t i = 0; i < z.size(); ++i) z[i] -= mean + slope * (static_cast<double>(i) - c);
}

Profile level(const Profile& profile, Levelling how) {
  profile.validate();
  Profile out = profile;
  level_in_place(out, how);
  return out;
}

}  // namespace asperity::surface
