#include "asperity/surface/scan_set.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "asperity/core/error.hpp"

namespace asperity::surface {

ScanFile parse_scan_file(std::string_view text) {
  ScanFile out{std::string(text), ""};
  for (std::string_view tag : {"@max", "@min"}) {
    if (text.size() > tag.size() && text.ends_with(tag)) {
      out.path = std::string(text.substr(0, text.size() - tag.size()));
      out.tag = std::string(tag.substr(1));
      return out;
    }
  }
  // FILE@word that names no file: an unknown tag, not part of the file name.
  const auto at = text.rfind('@');
  if (at != std::string_view::npos && at > 0 && at + 1 < text.size() &&
      text.find('/', at) == std::string_view::npos) {
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::path(out.path), ec)) {
      throw InvalidInput(
          fmt::format("\"{}\": unknown tag \"{}\" (allowed: @max, @min; no file is named \"{}\")",
                      text, text.substr(at), text));
    }
  }
  return out;
}

namespace {

// The profile of a profile file (ny = 1), its heights moved out of the map when every
// point is valid (no copy), else the longest valid run (HeightMap::as_profile); the
// map's heights are freed either way.
Profile take_profile(HeightMap& map, std::size_t invalid) {
  Profile p;
  if (map.ny == 1 && map.nx >= 2 && invalid == 0) {
    p.z = std::move(map.z);
    p.dx = map.dx;
    p.x0 = map.x0;
    p.source = map.source;
  } else {
    p = map.as_profile();
  }
  std::vector<double>().swap(map.z);
  return p;
}

}  // namespace

IsotropicSurface equivalent_isotropic_surface(const std::vector<ScanFile>& files,
                                              const ScanSettings& s) {
  if (files.empty()) throw InvalidInput("no scan file given");
  const bool tagged =
      std::any_of(files.begin(), files.end(), [](const ScanFile& f) { return !f.tag.empty(); });
  if (tagged &&
      !std::all_of(files.begin(), files.end(), [](const ScanFile& f) { return !f.tag.empty(); })) {
    throw InvalidInput("tag every scan with @max or @min, or none of them");
  }
  IsotropicSurface out;
  std::vector<HeightMap> maps;
  for (const auto& f : files) maps.push_back(read_height_file(f.path, s.text));
  const bool any_areal =
      std::any_of(maps.begin(), maps.end(), [](const HeightMap& m) { return !m.is_profile(); });

  if (any_areal) {
    if (maps.size() != 1) {
      throw InvalidInput(
          "an areal file must be the only file of its surface (its rows and columns give both "
          "directions)");
    }
    auto& map = maps.front();
    out.spikes_removed = remove_spikes(map, s.spikes);
    const auto d = areal_moments(map, s.level, s.filter);
    const bool x_is_max = d.x.m2 >= d.y.m2;
    const double len_x = map.dx * static_cast<double>(map.nx - 1);
    const double len_y = map.dy * static_cast<double>(map.ny - 1);
    out.scans.push_back({map.source, x_is_max ? "x (max_slope)" : "x (min_slope)", 0, d.x_profiles,
                         map.dx, len_x, 0.0, d.x, std::nullopt});
    out.scans.push_back({map.source, x_is_max ? "y (min_slope)" : "y (max_slope)", 0, d.y_profiles,
                         map.dy, len_y, 0.0, d.y, std::nullopt});
    if (map.invalid_count() > 0) {
      out.areal_parameters_note = fmt::format(
          "no ISO 25178-2 parameters: the areal filter needs every point, and {} of the {} "
          "points are invalid",
          map.invalid_count(), map.z.size());
    } else {
      auto sl = scale_limited_surface(map, s.level, s.filter);
      out.areal_parameters = areal_parameters(sl);
      if (s.psd) {
        out.psd.push_back(power_spectrum(sl, true));
        out.psd.push_back(power_spectrum(sl, false));
      }
      if (s.keep_scale_limited) out.scale_limited = std::move(sl);
    }
    out.moments =
        x_is_max ? equivalent_isotropic(d.x, d.y, s.rule) : equivalent_isotropic(d.y, d.x, s.rule);
    out.Sq = map.rms_height_about_plane();
    out.invalid_points = map.invalid_count();
    HeightMap meta = map;
    meta.z.clear();
    meta.valid.clear();
    out.areal = std::move(meta);
    return out;
  }

  for (auto& map : maps) {
    const std::size_t invalid = map.invalid_count();
    const std::size_t total = map.z.size();
    out.invalid_points += invalid;
    auto profile = take_profile(map, invalid);
    out.spikes_removed += remove_spikes(profile, s.spikes);
    const std::string source = profile.source;
    const double dx = profile.dx, length = profile.length();
    std::optional<ProfileParameters> params;
    auto inspect = [&](const Profile& filtered) {
      params = profile_parameters(filtered, s.filter.lc);
      if (s.psd) out.psd.push_back(power_spectrum(filtered));
    };
    const std::size_t run = profile.z.size();
    // With invalid points the profile is their longest valid run: say so when it is too
    // short, not only that "the profile" is.
    auto processed = [&](auto&& process) {
      try {
        return process();
      } catch (const InvalidInput& e) {
        if (invalid == 0) throw;
        if (2 * run < total - invalid) {
          // The gaps, not the scan's length, are the cause (every third point NaN: runs of 2).
          throw InvalidInput(fmt::format(
              "{}: {} of the file's {} points are invalid (NaN or masked) and scattered: the "
              "longest run of consecutive valid points, which is what gets processed, has {} "
              "points; fill the gaps (interpolate the invalid points) or use a scan with fewer of "
              "them ({})",
              source, invalid, total, run, e.what()));
        }
        throw InvalidInput(fmt::format(
            "{} ({} of the file's {} points are invalid (NaN or masked); the profile is their "
            "longest run of consecutive valid points, {} points)",
            e.what(), invalid, total, run));
      }
    };
    if (!s.keep_processed) {
      // Only the moments: the profile is levelled in place and freed once filtered.
      const auto m = processed(
          [&] { return profile_moments(std::move(profile), s.level, s.filter, inspect); });
      out.scans.push_back(
          {source, "isotropic", m.points, 1, dx, length, m.length, m.moments, params});
      continue;
    }
    auto p = processed([&] { return process_profile(profile, s.level, s.filter); });
    inspect(p.filtered);
    out.scans.push_back({source, "isotropic", p.filtered.z.size(), 1, dx, length,
                         p.filtered.length(), p.moments, params});
    out.raw.push_back(std::move(profile));
    out.processed.push_back(std::move(p));
  }
  if (out.scans.size() == 1) {
    out.moments = out.scans.front().moments;
    out.scans.front().direction = "isotropic (one scan)";
  } else if (!tagged) {
    if (out.scans.size() != 2) {
      throw InvalidInput(fmt::format(
          "{} scans without direction: give two scans (the max- and min-slope directions are "
          "found from their m2), or tag each file with @max or @min",
          out.scans.size()));
    }
    const bool first_is_max = out.scans[0].moments.m2 >= out.scans[1].moments.m2;
    out.scans[0].direction = first_is_max ? "max_slope" : "min_slope";
    out.scans[1].direction = first_is_max ? "min_slope" : "max_slope";
    out.moments = equivalent_isotropic(out.scans[first_is_max ? 0 : 1].moments,
                                       out.scans[first_is_max ? 1 : 0].moments, s.rule);
  } else {
    std::vector<SpectralMoments> mx, mn;
    std::vector<double> wx, wn;
    for (std::size_t k = 0; k < files.size(); ++k) {
      auto& scan = out.scans[k];
      const bool is_max = files[k].tag == "max";
      scan.direction = is_max ? "max_slope" : "min_slope";
      (is_max ? mx : mn).push_back(scan.moments);
      (is_max ? wx : wn).push_back(static_cast<double>(scan.points));
    }
    if (mx.empty() || mn.empty()) throw InvalidInput("need at least one @max and one @min scan");
    out.moments = equivalent_isotropic(average_moments(mx, wx), average_moments(mn, wn), s.rule);
  }
  return out;
}

}  // namespace asperity::surface
