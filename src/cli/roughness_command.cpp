// asperity roughness: roughness parameters of the two joint halves from measured
// profiles (or given parameters), combined as in Eq. 5.1 (thesis ch. 5-6).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <numbers>
#include <sstream>
#include <tuple>

#include "asperity/contact/material.hpp"
#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/roughness.hpp"
#include "asperity/surface/scan_set.hpp"
#include "asperity/surface/summits.hpp"
#include "asperity/surface/texture.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace dim = core::dim;
using surface::GaussianFilter;
using surface::HeightMap;
using surface::Levelling;
using surface::SpectralMoments;

namespace {

struct RoughnessOptions {
  std::vector<std::string> surfaces;  // comma-separated file lists
  std::vector<std::string> params;    // sigma=..,eta=..,R=..
  std::string lc = "0.8mm";
  std::string ls = "20um";
  std::string filter = "gaussian";
  std::string level = "line";
  std::string end = "discard";
  std::string truncation = "1";
  std::string rule = "geometric";
  std::optional<std::string> dx;
  std::optional<std::string> spikes;
  std::size_t spike_window = 2;
  std::optional<std::string> psd, psd_plot;
  std::optional<std::string> summits;
  std::size_t summit_bins = 0;
  std::optional<std::string> E, nu, E1, nu1, E2, nu2, H, H1, H2;
  bool json = false;
  std::optional<std::string> plot;
  // Order in which --surface and --params were given (true = --surface).
  std::vector<bool> order;
};

using Scan = surface::ScanMoments;

struct PlotTrace {
  std::string label;
  surface::Profile raw, levelled, filtered;
  std::vector<double> heights;  // filtered heights of every scan of the surface
  std::string heights_from;     // what `heights` holds, for the legend
};

struct AnalysedSurface {
  bool from_files = false;
  std::vector<std::string> files;
  std::vector<Scan> scans;
  SpectralMoments moments;
  std::optional<HeightMap> areal;  // metadata of an areal file (z cleared)
  double Sq = 0.0;
  std::size_t invalid_points = 0;
  std::optional<PlotTrace> trace;
  std::optional<surface::ArealParameters> areal_parameters;
  std::string areal_parameters_note;
  std::vector<surface::PowerSpectrum> psd;
  std::size_t spikes_removed = 0;
  std::optional<HeightMap> scale_limited;  // with --summits
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep)) out.push_back(cur);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// A length as the user wrote it: "20um" is 20 x 1e-6 = 1.9999999999999998e-05 m after
// the unit's scaling; rounded to 15 significant digits (any decimal of up to 15 digits
// survives the trip through a double, DBL_DIG) it is the decimal 2e-05 m again, which
// the JSON echoes. The change is below 1e-15 relative.
double as_typed(double v) {
  return std::strtod(fmt::format("{:.15g}", v).c_str(), nullptr);
}

// "none" or a length.
double cutoff(const std::string& text, const std::string& flag) {
  if (text == "none" || text == "0") return 0.0;
  const double v = as_typed(core::parse_quantity(text, dim::length, flag));
  if (!(v > 0.0)) throw InvalidInput(fmt::format("{} = \"{}\" must be > 0 (or none)", flag, text));
  return v;
}

// Before anything is read or computed: an output must not be a directory, must not
// overwrite an input file (a --surface file), and outputs must not share a file.
void check_output_paths(const RoughnessOptions& o) {
  std::vector<std::pair<std::string, std::string>> outputs;
  for (const auto& [flag, path, example] :
       {std::tuple{"--plot", o.plot, "roughness.png"}, std::tuple{"--psd", o.psd, "psd.csv"},
        std::tuple{"--psd-plot", o.psd_plot, "psd.png"},
        std::tuple{"--summits", o.summits, "summits.csv"}}) {
    if (!path) continue;
    const bool table = std::string_view(flag) == "--psd" || std::string_view(flag) == "--summits";
    if (is_standard_output(*path) && !table)
      throw InvalidInput(
          fmt::format("{} - is not allowed: a PNG goes to a file, give its name", flag));
    if (is_standard_output(*path)) {
      if (o.json)
        throw InvalidInput(fmt::format(
            "{0} - and --json both write to standard output: give {0} a file name", flag));
      continue;
    }
    std::error_code ec;
    if (std::filesystem::is_directory(*path, ec)) {
      throw InvalidInput(
          fmt::format("{} = \"{}\" is a directory: give the file to write, e.g. {} {}", flag, *path,
                      flag, example));
    }
    if (std::filesystem::path(*path).filename().empty()) {
      throw InvalidInput(
          fmt::format("{} = \"{}\" names no file: give the file to write, e.g. {} {}", flag, *path,
                      flag, example));
    }
    outputs.emplace_back(flag, *path);
  }
  if (is_standard_output(o.psd) && is_standard_output(o.summits))
    throw InvalidInput(
        "--psd - and --summits - both write to standard output: give one of them a file name");
  if (outputs.empty()) return;
  require_distinct_outputs(outputs);
  for (std::size_t k = 0; k < o.surfaces.size(); ++k) {
    for (auto f : split(o.surfaces[k], ',')) {
      f = trim(f);
      for (const std::string tag : {"@max", "@min"}) {
        if (f.size() > tag.size() && f.ends_with(tag)) f.resize(f.size() - tag.size());
      }
      for (const auto& out : outputs) {
        try {
          require_distinct_outputs({{fmt::format("--surface #{}", k + 1), f}, out});
        } catch (const InvalidInput& e) {
          throw InvalidInput(
              fmt::format("{} ({} would overwrite an input file)", e.what(), out.first));
        }
      }
    }
  }
}

SpectralMoments parse_params(const std::string& text, std::size_t index) {
  std::optional<double> sigma, eta, R;
  const std::string flag = fmt::format("--params #{}", index + 1);
  for (const auto& item : split(text, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) {
      throw InvalidInput(
          fmt::format("{}: \"{}\" is not key=value (expected sigma=..,eta=..,R=..)", flag, item));
    }
    const std::string key = trim(item.substr(0, eq));
    const std::string value = trim(item.substr(eq + 1));
    // Each value must be > 0; the message names the flag occurrence and echoes the text.
    auto positive = [&](core::Dimension d) {
      const double v = core::parse_quantity(value, d, fmt::format("{} {}", flag, key));
      if (!(std::isfinite(v) && v > 0.0)) {
        throw InvalidInput(
            fmt::format("{}: {} = \"{}\" is not allowed: it must be > 0", flag, key, value));
      }
      return v;
    };
    if (key == "sigma") {
      sigma = positive(dim::length);
    } else if (key == "eta") {
      eta = positive(dim::inverse_area);
    } else if (key == "R") {
      R = positive(dim::length);
    } else {
      throw InvalidInput(fmt::format("{}: unknown key \"{}\": use sigma, eta and R", flag, key));
    }
  }
  if (!sigma || !eta || !R) {
    throw InvalidInput(fmt::format(
        "{}: give all of sigma, eta and R, e.g. sigma=1.763um,eta=3.34e-4um^-2,R=40.76um", flag));
  }
  return SpectralMoments::from_parameters(*sigma, *eta, *R);
}

struct Settings {
  Levelling level = Levelling::line;
  GaussianFilter filter;
  surface::IsotropicRule rule = surface::IsotropicRule::geometric;
  surface::TextReadOptions text;
  surface::SpikeRemoval spikes;
  bool plot = false;
  bool psd = false;
  bool summits = false;
};

AnalysedSurface analyse_files(const std::string& list, std::size_t index, const Settings& s) {
  AnalysedSurface out;
  out.from_files = true;
  surface::IsotropicSurface r;
  std::vector<surface::ScanFile> files;
  try {
    for (auto f : split(list, ',')) {
      f = trim(f);
      if (f.empty()) throw InvalidInput(fmt::format("empty file name in \"{}\"", list));
      files.push_back(surface::parse_scan_file(f));
      out.files.push_back(files.back().path);
    }
    // Which scan is which direction, averaging, areal files: the library's (scan_set.hpp).
    r = surface::equivalent_isotropic_surface(files, {.level = s.level,
                                                      .filter = s.filter,
                                                      .rule = s.rule,
                                                      .text = s.text,
                                                      .keep_processed = s.plot,
                                                      .spikes = s.spikes,
                                                      .psd = s.psd,
                                                      .keep_scale_limited = s.summits});
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("--surface #{}: {}", index + 1, e.what()));
  }
  out.scans = r.scans;
  out.moments = r.moments;
  out.areal = r.areal;
  out.Sq = r.Sq;
  out.invalid_points = r.invalid_points;
  out.areal_parameters = r.areal_parameters;
  out.areal_parameters_note = r.areal_parameters_note;
  out.psd = r.psd;
  out.spikes_removed = r.spikes_removed;
  out.scale_limited = std::move(r.scale_limited);
  if (s.psd && out.psd.empty()) {
    throw InvalidInput(fmt::format("--psd: surface {}: {}", index + 1, out.areal_parameters_note));
  }
  if (!s.plot) return out;
  if (r.areal) {
    // The first row is drawn; the histogram holds the filtered heights of every row and
    // column used for the moments (the rows and columns share points, so each point
    // counts about twice).
    auto map = surface::read_height_file(files.front().path, s.text);
    (void)surface::remove_spikes(map, s.spikes);
    const std::size_t min_x = s.filter.is_none() ? 3 : s.filter.min_points(map.dx);
    const std::size_t min_y = s.filter.is_none() ? 3 : s.filter.min_points(map.dy);
    for (const auto& [profiles, min_pts] :
         {std::pair{map.rows(min_x), min_x}, std::pair{map.columns(min_y), min_y}}) {
      for (const auto& prof : profiles) {
        if (prof.z.size() < min_pts) continue;
        const auto p = surface::process_profile(prof, s.level, s.filter);
        if (!out.trace) {
          out.trace =
              PlotTrace{prof.source, prof, p.levelled, p.filtered, {}, "filtered rows and columns"};
        }
        out.trace->heights.insert(out.trace->heights.end(), p.filtered.z.begin(),
                                  p.filtered.z.end());
      }
    }
    return out;
  }
  for (std::size_t k = 0; k < r.processed.size(); ++k) {
    const auto& p = r.processed[k];
    if (!out.trace) {
      out.trace =
          PlotTrace{r.raw[k].source,
                    r.raw[k],
                    p.levelled,
                    p.filtered,
                    {},
                    r.processed.size() > 1 ? "filtered heights, all scans" : "filtered heights"};
    }
    out.trace->heights.insert(out.trace->heights.end(), p.filtered.z.begin(), p.filtered.z.end());
  }
  return out;
}

// A number right-aligned in a table column of `width` characters: fixed with
// `digits` decimals (or scientific), scientific when fixed would print a non-zero value
// as 0, with fewer digits when it would not leave one blank before it, so that huge or
// tiny values keep the columns.
std::string cell(double v, std::size_t width, int digits, bool scientific = false) {
  scientific = scientific || (v != 0.0 && std::abs(v) < 0.5 * std::pow(10.0, -digits));
  std::string s =
      scientific ? fmt::format("{:.{}e}", v, digits) : fmt::format("{:.{}f}", v, digits);
  for (int d = digits; s.size() + 1 > width && d >= 0; --d) s = fmt::format("{:.{}e}", v, d);
  return fmt::format("{:>{}}", s, width);
}

Json nullable(std::optional<double> v) {
  return v ? Json(*v) : Json(nullptr);
}

std::optional<double> try_sigma_a(const SpectralMoments& m) {
  try {
    return m.sigma_a();
  } catch (const InvalidInput&) {
    return std::nullopt;
  }
}

Json moments_json(const SpectralMoments& m, const std::optional<contact::ContactPair>& pair) {
  Json j;
  j["sigma"] = m.sigma();
  j["eta"] = m.eta();
  j["R"] = m.R();
  j["beta"] = m.beta();
  j["alpha"] = m.alpha();
  j["m0"] = m.m0;
  j["m2"] = m.m2;
  j["m4"] = m.m4;
  j["sigma_a"] = nullable(try_sigma_a(m));
  if (pair) j["psi"] = surface::plasticity_index(*pair, m);
  return j;
}

std::string base_name(const std::string& path);

Json profile_parameters_json(const surface::ProfileParameters& p) {
  return Json{{"Ra", p.Ra},
              {"Rq", p.Rq},
              {"Rz", p.Rz},
              {"Rsk", p.Rsk},
              {"Rku", p.Rku},
              {"Rdq", p.Rdq},
              {"sections", p.sections},
              {"section_length", p.section_length}};
}

Json areal_parameters_json(const surface::ArealParameters& a) {
  return Json{{"Sa", a.Sa},   {"Sq", a.Sq}, {"Ssk", a.Ssk}, {"Sku", a.Sku},
              {"Sdq", a.Sdq}, {"nx", a.nx}, {"ny", a.ny}};
}

// A spectrum's label: "surface 1 file.csv" or "surface 1 x (rows)".
std::string psd_label(std::size_t k, const AnalysedSurface& a, std::size_t j) {
  const auto& sp = a.psd[j];
  if (sp.direction == "profile" && j < a.scans.size())
    return fmt::format("surface {} {}", k + 1, base_name(a.scans[j].file));
  return fmt::format("surface {} {}", k + 1, sp.direction);
}

// The PSD table: one row per frequency of each spectrum (one-sided; texture.hpp states the
// normalisation: the sum of psd * df is the mean-square height).
std::string psd_csv(const std::vector<AnalysedSurface>& surfaces) {
  std::string t = "surface,spectrum,profiles,f[1/m],psd[m^3]\n";
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    for (std::size_t j = 0; j < surfaces[k].psd.size(); ++j) {
      const auto& sp = surfaces[k].psd[j];
      std::string label = psd_label(k, surfaces[k], j);
      std::replace(label.begin(), label.end(), '"', '\'');
      for (std::size_t i = 0; i < sp.f.size(); ++i)
        t += fmt::format("{},\"{}\",{},{:.12g},{:.12g}\n", k + 1, label, sp.profiles, sp.f[i],
                         sp.psd[i]);
    }
  }
  return t;
}

void draw_psd_plot(const std::string& path, const std::vector<AnalysedSurface>& surfaces) {
  PlotSpec spec{.title = "Power spectral density (one-sided, sum of PSD df = mean square height)",
                .xlabel = "spatial frequency f [1/mm]",
                .ylabel = "PSD [µm^2 mm]",
                .logx = true,
                .logy = true};
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    for (std::size_t j = 0; j < surfaces[k].psd.size(); ++j) {
      const auto& sp = surfaces[k].psd[j];
      Series se{.title = psd_label(k, surfaces[k], j)};
      for (std::size_t i = 1; i < sp.f.size(); ++i) {  // f = 0 has no place on a log axis
        if (!(sp.psd[i] > 0.0)) continue;
        se.x.push_back(sp.f[i] * 1e-3);          // 1/m -> 1/mm
        se.y.push_back(sp.psd[i] * 1e12 * 1e3);  // m^3 -> um^2 mm
      }
      if (!se.x.empty()) spec.series.push_back(std::move(se));
    }
  }
  if (spec.series.empty())
    throw InvalidInput("--psd-plot: no spectrum has a positive value to draw");
  plot_png(path, spec);
}

Json filter_json(const Settings& s) {
  Json f;
  f["lc"] = s.filter.lc > 0.0 ? Json(s.filter.lc) : Json(nullptr);
  f["ls"] = s.filter.ls > 0.0 ? Json(s.filter.ls) : Json(nullptr);
  f["type"] = s.filter.is_none() ? "none" : "gaussian (ISO 16610-21)";
  f["truncation"] = s.filter.truncation;
  f["end"] = surface::to_string(s.filter.end);
  f["level"] = surface::to_string(s.level);
  f["spikes"] = s.spikes.is_off() ? Json(nullptr)
                                  : Json{{"threshold", s.spikes.threshold},
                                         {"half_window", s.spikes.half_window}};
  return f;
}

std::optional<contact::ContactPair> material_pair(const RoughnessOptions& o) {
  const bool any = o.E || o.nu || o.E1 || o.nu1 || o.E2 || o.nu2 || o.H || o.H1 || o.H2;
  if (!any) return std::nullopt;
  if ((o.E || o.nu) && (o.E1 || o.nu1 || o.E2 || o.nu2)) {
    throw InvalidInput("give either --E/--nu (both halves alike) or --E1/--nu1/--E2/--nu2");
  }
  contact::Material b1, b2;
  if (o.E || o.nu) {
    b1.E = b2.E = required_quantity(o.E, dim::pressure, "--E");
    b1.nu = b2.nu = required_quantity(o.nu, dim::dimensionless, "--nu");
  } else {
    b1.E = required_quantity(o.E1, dim::pressure, "--E1");
    b1.nu = required_quantity(o.nu1, dim::dimensionless, "--nu1");
    b2.E = required_quantity(o.E2, dim::pressure, "--E2");
    b2.nu = required_quantity(o.nu2, dim::dimensionless, "--nu2");
  }
  if (o.H) {
    if (o.H1 || o.H2)
      throw InvalidInput("give either --H (softer material) or --H1/--H2, not both");
    if (b1.nu != b2.nu) {
      throw InvalidInput(
          "--H does not say which half is softer and the Poisson's ratios differ: "
          "give --H1 and --H2");
    }
    b1.H = b2.H = required_quantity(o.H, dim::pressure, "--H");
  } else {
    b1.H = quantity(o.H1, dim::pressure, "--H1").value_or(0.0);
    b2.H = quantity(o.H2, dim::pressure, "--H2").value_or(0.0);
  }
  if (b1.H == 0.0 && b2.H == 0.0) {
    throw InvalidInput("the plasticity index needs the hardness: give --H (or --H1/--H2)");
  }
  b1.validate("half 1");
  b2.validate("half 2");
  return contact::ContactPair::combine(b1, b2, 1.0);
}

// A gnuplot string in single quotes (no escape sequences there; a quote is doubled),
// for the fixed labels of the extra panels. Control characters are dropped.
std::string gp_single(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (static_cast<unsigned char>(c) < 0x20) continue;
    if (c == '\'') out += '\'';
    out += c;
  }
  return out + "'";
}

std::string base_name(const std::string& path) {
  const auto p = path.find_last_of("/\\");
  return p == std::string::npos ? path : path.substr(p + 1);
}

// Length and height units of a panel: um or nm for heights (nm when all are below
// 1 um), mm or um along x (um below 1 mm).
struct Unit {
  double factor;
  const char* name;
};
Unit height_unit(double max_abs) {
  return max_abs < 1e-6 ? Unit{1e9, "nm"} : Unit{1e6, "µm"};
}
Unit length_unit(double max_x) {
  return max_x < 1e-3 ? Unit{1e6, "µm"} : Unit{1e3, "mm"};
}

double max_abs(const std::vector<double>& z) {
  double m = 0;
  for (double v : z) m = std::max(m, std::abs(v));
  return m;
}

// One trace of a profile panel, at most ~6000 points.
Series profile_series(const surface::Profile& p, Unit ux, Unit uz, std::string title,
                      std::string style = "lines") {
  Series s{.title = std::move(title), .style = std::move(style)};
  const std::size_t stride = std::max<std::size_t>(1, p.z.size() / 6000);
  for (std::size_t i = 0; i < p.z.size(); i += stride) {
    s.x.push_back((p.x0 + static_cast<double>(i) * p.dx) * ux.factor);
    s.y.push_back(p.z[i] * uz.factor);
  }
  return s;
}

// Gnuplot commands drawing one panel of a multiplot with inline data.
std::string panel(const std::string& title, const std::string& xlabel, const std::string& ylabel,
                  const std::vector<Series>& series, bool set_labels = true) {
  std::string gp;
  if (set_labels) {
    gp += "set title " + gp_single(title) + " noenhanced\n";
    gp += "set xlabel " + gp_single(xlabel) + "\nset ylabel " + gp_single(ylabel) + "\n";
  }
  gp += "plot ";
  for (std::size_t i = 0; i < series.size(); ++i) {
    gp += (i ? ", " : "");
    gp += "'-' using 1:2 with " + series[i].style + " lw 1.5 title " + gp_single(series[i].title);
  }
  gp += "\n";
  for (const auto& s : series) {
    for (std::size_t j = 0; j < s.x.size(); ++j)
      gp += fmt::format("{:.10g} {:.10g}\n", s.x[j], s.y[j]);
    gp += "e\n";
  }
  return gp;
}

void draw_plot(const std::string& path, const std::vector<AnalysedSurface>& surfaces,
               const Settings& settings) {
  // Four panels, each with its own height scale (a 16 um tilt and 8 nm of roughness
  // cannot share an axis): the raw profile (first scan or row of each measured half),
  // the levelled profile, the filtered (roughness) profile, and the histogram of the
  // filtered heights against the Gaussian of the same mean and rms.
  std::vector<std::pair<std::size_t, const PlotTrace*>> traces;
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    if (surfaces[k].trace) traces.emplace_back(k + 1, &*surfaces[k].trace);
  }
  if (traces.empty()) {
    throw InvalidInput("--plot needs at least one surface given by profile files (not --params)");
  }
  double xmax = 0, raw_max = 0, lev_max = 0, fil_max = 0, hist_max = 0;
  for (const auto& [k, t] : traces) {
    xmax = std::max({xmax, std::abs(t->raw.x0), std::abs(t->raw.x0 + t->raw.length())});
    raw_max = std::max(raw_max, max_abs(t->raw.z));
    lev_max = std::max(lev_max, max_abs(t->levelled.z));
    fil_max = std::max(fil_max, max_abs(t->filtered.z));
    hist_max = std::max(hist_max, max_abs(t->heights));
  }
  const Unit ux = length_unit(xmax);
  const Unit u_raw = height_unit(raw_max), u_lev = height_unit(lev_max),
             u_fil = height_unit(fil_max), u_hist = height_unit(hist_max);
  const std::string xlabel = fmt::format("x [{}]", ux.name);
  // One colour per surface in every panel; the Gaussian dashed.
  auto colour = [](std::size_t k) {
    return std::string(k == 1 ? "lc rgb '#1f5fbf'" : "lc rgb '#d9530f'");
  };

  std::vector<Series> raw, levelled, filtered;
  std::string files;
  for (const auto& [k, t] : traces) {
    const std::string tag = fmt::format("surface {}", k);
    const std::string style = "lines " + colour(k);
    raw.push_back(profile_series(t->raw, ux, u_raw, tag, style));
    levelled.push_back(profile_series(t->levelled, ux, u_lev, tag, style));
    filtered.push_back(profile_series(t->filtered, ux, u_fil, tag, style));
    files += fmt::format("{}{}: {}", files.empty() ? "" : ", ", tag, base_name(t->label));
  }
  const std::string level_name = settings.level == Levelling::line   ? "least-squares line removed"
                                 : settings.level == Levelling::mean ? "mean removed"
                                                                     : "not levelled";
  const std::string filter_name =
      settings.filter.is_none()
          ? std::string("no filter")
          : fmt::format("Gaussian, lc = {}, ls = {}",
                        settings.filter.lc > 0 ? fmt::format("{:.4g} mm", settings.filter.lc * 1e3)
                                               : "none",
                        settings.filter.ls > 0 ? fmt::format("{:.4g} µm", settings.filter.ls * 1e6)
                                               : "none");

  // Histogram panel: the PlotSpec's own series.
  PlotSpec hist{.title = "Raw profile (" + files + ")",  // title of the first panel
                .xlabel = xlabel,
                .ylabel = fmt::format("z [{}]", u_raw.name)};
  for (const auto& [k, t] : traces) {
    const auto& z = t->heights;
    if (z.size() < 2) continue;
    double mean = 0, ms = 0, lo = z.front(), hi = z.front();
    for (double v : z) {
      mean += v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    mean /= static_cast<double>(z.size());
    for (double v : z) ms += (v - mean) * (v - mean);
    const double sd = std::sqrt(ms / static_cast<double>(z.size()));
    if (!(hi > lo) || !(sd > 0.0)) continue;
    // Bins of about sd/5 (fine enough to show the shape near the mean even when a few
    // spikes stretch the range), at least 10 and at most 200, and about 20 points a bin.
    const auto bins = static_cast<std::size_t>(std::clamp(
        std::min((hi - lo) / (0.2 * sd), static_cast<double>(z.size()) / 20.0), 10.0, 200.0));
    const double w = (hi - lo) / static_cast<double>(bins);
    std::vector<double> count(bins, 0.0);
    for (double v : z) {
      auto b = static_cast<std::size_t>((v - lo) / w);
      count[std::min(b, bins - 1)] += 1.0;
    }
    const double f = u_hist.factor;
    Series h{.title = fmt::format("surface {}: {} ({} points)", k, t->heights_from, z.size()),
             .style = "steps " + colour(k)};
    Series g{.title = fmt::format("surface {}: Gaussian, same mean and rms", k),
             .style = "lines dt 2 " + colour(k)};
    for (std::size_t b = 0; b < bins; ++b) {
      h.x.push_back((lo + w * static_cast<double>(b)) * f);
      h.y.push_back(count[b] / (static_cast<double>(z.size()) * w * f));
    }
    h.x.push_back(hi * f);
    h.y.push_back(h.y.back());
    for (int j = 0; j <= 200; ++j) {
      const double v = lo + (hi - lo) * j / 200.0;
      const double u = (v - mean) / sd;
      g.x.push_back(v * f);
      g.y.push_back(std::exp(-0.5 * u * u) / (sd * f * std::sqrt(2 * std::numbers::pi)));
    }
    hist.series.push_back(std::move(h));
    hist.series.push_back(std::move(g));
  }
  if (hist.series.empty()) {
    throw InvalidInput("--plot: the filtered heights have no spread to draw a histogram of");
  }
  std::string gp;
  gp += "set terminal pngcairo size 1400,1000 enhanced font 'DejaVu Sans,11'\n";
  gp += "set multiplot layout 2,2\nset key inside top left horizontal noenhanced box opaque\n";
  // Head room above the traces for the key.
  gp +=
      "set autoscale xfix\nset format x '%g'\nset format y '%g'\nset offsets 0, 0, graph 0.15, 0\n";
  gp += panel("", "", "", raw, false);  // title and labels from the PlotSpec
  gp += panel("Levelled profile (" + level_name + ")", xlabel, fmt::format("z [{}]", u_lev.name),
              levelled);
  gp += panel("Roughness profile (" + filter_name + ")", xlabel, fmt::format("z [{}]", u_fil.name),
              filtered);
  gp += "set autoscale x\nset key inside top left vertical\nset offsets 0, 0, graph 0.45, 0\n";
  gp += "set title " + gp_single("Height distribution of the filtered profiles") + " noenhanced\n";
  gp += "set xlabel " + gp_single(fmt::format("z [{}]", u_hist.name)) + "\n";
  gp += "set ylabel " + gp_single(fmt::format("probability density [1/{}]", u_hist.name)) + "\n";
  hist.extra = gp;
  plot_png(path, hist);
}

// The summits that --summits tabulates: those of one areal half given alone, or of the sum
// of two areal halves on one grid (the composite surface whose moments Eq. 5.1 adds).
struct SummitResult {
  std::string surface;      // "1" or "1+2"
  std::string source;       // what the map is, for the CSV's comment
  SpectralMoments moments;  // of that surface: the spectral estimates beside the counts
  surface::SummitSet set;
  surface::SummitHistogram histogram;
  double table_sigma = 0.0;  // standard deviation of the table (histogram + h^2/6)
};

SummitResult find_surface_summits(const std::vector<AnalysedSurface>& surfaces,
                                  const SpectralMoments& combined, std::size_t bins) {
  const auto what = [](const AnalysedSurface& a) -> std::string {
    if (!a.from_files) return "given by --params";
    if (!a.areal) return "profile scans";
    return "an areal map";
  };
  for (std::size_t k = 0; k < surfaces.size(); ++k)
    if (surfaces[k].areal && !surfaces[k].scale_limited)
      throw InvalidInput(fmt::format(
          "--summits: surface {}: {} of the map's {} points are invalid, and its S-L surface "
          "(the areal filter) and the summits need every point",
          k + 1, surfaces[k].invalid_points, surfaces[k].areal->nx * surfaces[k].areal->ny));
  SummitResult r;
  HeightMap map;
  if (surfaces.size() == 1 && surfaces[0].scale_limited) {
    map = *surfaces[0].scale_limited;
    r.surface = "1";
    r.source = fmt::format("surface 1 ({})", surfaces[0].files.front());
    r.moments = surfaces[0].moments;
  } else if (surfaces.size() == 2 && surfaces[0].scale_limited && surfaces[1].scale_limited) {
    const HeightMap& a = *surfaces[0].scale_limited;
    const HeightMap& b = *surfaces[1].scale_limited;
    if (a.nx != b.nx || a.ny != b.ny || a.dx != b.dx || a.dy != b.dy)
      throw InvalidInput(fmt::format(
          "--summits: the sum surface of two halves needs their S-L surfaces on one grid: "
          "surface 1 has {} x {} points at {:.6g} x {:.6g} um, surface 2 {} x {} at {:.6g} x "
          "{:.6g} um (give one --surface alone for one half's summits)",
          a.nx, a.ny, a.dx * 1e6, a.dy * 1e6, b.nx, b.ny, b.dx * 1e6, b.dy * 1e6));
    map = a;
    for (std::size_t i = 0; i < map.z.size(); ++i) map.z[i] += b.z[i];
    map.source = fmt::format("the sum of the S-L surfaces of {} and {}", surfaces[0].files.front(),
                             surfaces[1].files.front());
    r.surface = "1+2";
    r.source = map.source;
    r.moments = combined;
  } else {
    std::string which;
    for (std::size_t k = 0; k < surfaces.size(); ++k)
      which += fmt::format("{}surface {} is {}", k ? ", " : "", k + 1, what(surfaces[k]));
    throw InvalidInput(fmt::format(
        "--summits: summits are found on the S-L surface of areal maps: one half given as an "
        "areal file (its summits), or both halves (the summits of their sum surface, whose "
        "moments Eq. 5.1 adds); here {}",
        which));
  }
  try {
    r.set = surface::find_summits(map);
    r.histogram = surface::summit_histogram(r.set, bins);
    r.table_sigma = surface::summit_height_table(r.histogram, "of --summits").standard_deviation();
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("--summits: {}", e.what()));
  }
  return r;
}

std::string summits_csv(const SummitResult& r, const Settings& s) {
  const auto& set = r.set;
  std::string t = fmt::format(
      "# summits (points higher than their 8 neighbours) of {}, S-L surface: {} level, lc = {}, "
      "ls = {}\n",
      r.source, surface::to_string(s.level),
      s.filter.lc > 0 ? fmt::format("{:.6g} m", s.filter.lc) : "none",
      s.filter.ls > 0 ? fmt::format("{:.6g} m", s.filter.ls) : "none");
  t += fmt::format(
      "# {} summits in {:.6g} m^2: density {:.6g} m^-2, mean height {:.6g} m, standard deviation "
      "{:.6g} m, radius 1/<curvature> {:.6g} m\n",
      set.summits.size(), set.area, set.density(), set.mean_height(),
      set.height_standard_deviation(), set.radius());
  t += fmt::format(
      "# frequency polygon of the heights: {} bins of {:.6g} m, linear between rows (standard "
      "deviation {:.6g} m); a structure case reads it as [rough_contact] summit_heights\n",
      r.histogram.height.size() - 2, r.histogram.bin_width, r.table_sigma);
  t += core::csv_text({"height[m]", "density[1/m]"}, {r.histogram.height, r.histogram.density});
  return t;
}

Json summits_json(const SummitResult& r, const std::optional<std::string>& file) {
  const auto& set = r.set;
  return Json{{"surface", r.surface},
              {"count", set.summits.size()},
              {"points", set.points},
              {"area", set.area},
              {"eta", set.density()},
              {"mean_height", set.mean_height()},
              {"sigma", set.height_standard_deviation()},
              {"R", set.radius()},
              {"bins", r.histogram.height.size() - 2},
              {"bin_width", r.histogram.bin_width},
              {"table_sigma", r.table_sigma},
              {"spectral",
               {{"eta", r.moments.eta()},
                {"sigma_a", nullable(try_sigma_a(r.moments))},
                {"R", r.moments.R()}}},
              {"file", file && !is_standard_output(*file) ? Json(*file) : Json(nullptr)}};
}

void run_roughness(const RoughnessOptions& o, std::string& out) {
  Settings s;
  s.level = surface::parse_levelling(lowercase(o.level), "--level");
  s.rule = surface::parse_isotropic_rule(lowercase(o.rule), "--rule");
  if (lowercase(o.filter) == "none") {
    s.filter = GaussianFilter::none();
  } else if (lowercase(o.filter) == "gaussian") {
    s.filter.lc = cutoff(o.lc, "--lc");
    s.filter.ls = cutoff(o.ls, "--ls");
    s.filter.end = surface::parse_end_effects(lowercase(o.end), "--end");
    s.filter.truncation = core::parse_quantity(o.truncation, dim::dimensionless, "--truncation");
  } else {
    throw InvalidInput(
        fmt::format("--filter = \"{}\" is not allowed: use gaussian or none", o.filter));
  }
  s.filter.validate();
  check_output_paths(o);
  if (o.dx) {
    s.text.dx = as_typed(core::parse_quantity(*o.dx, dim::length, "--dx"));
    if (!(*s.text.dx > 0.0)) throw InvalidInput(fmt::format("--dx = \"{}\" must be > 0", *o.dx));
  }
  const auto pair = material_pair(o);
  s.plot = o.plot.has_value();
  s.psd = o.psd.has_value() || o.psd_plot.has_value();
  s.summits = o.summits.has_value();
  if (o.summit_bins > 10000 || (o.summit_bins > 0 && !o.summits))
    throw InvalidInput(
        fmt::format("--summit-bins = {}: allowed are 1 to 10000 with --summits (0 = Rice's rule)",
                    o.summit_bins));
  if (o.spikes && lowercase(*o.spikes) != "off") {
    s.spikes.threshold = core::parse_quantity(*o.spikes, dim::dimensionless, "--spikes");
  }
  s.spikes.half_window = o.spike_window;
  try {
    s.spikes.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("--spikes / --spike-window: {}", e.what()));
  }

  const std::size_t n = o.surfaces.size() + o.params.size();
  if (n == 0) {
    throw InvalidInput(
        "give the surfaces: --surface FILE[,FILE...] or --params sigma=..,eta=..,R=.. "
        "(once per joint half)");
  }
  if (n > 2) throw InvalidInput(fmt::format("{} surfaces given: a joint has one or two halves", n));
  std::vector<bool> order = o.order;
  if (order.size() != n) {  // should not happen; keep files first, then parameters
    order.assign(o.surfaces.size(), true);
    order.insert(order.end(), o.params.size(), false);
  }
  std::vector<AnalysedSurface> surfaces;
  std::size_t next_file = 0, next_param = 0;
  for (bool is_file : order) {
    if (is_file) {
      surfaces.push_back(analyse_files(o.surfaces[next_file++], surfaces.size(), s));
    } else {
      AnalysedSurface a;
      a.moments = parse_params(o.params[next_param++], surfaces.size());
      surfaces.push_back(std::move(a));
    }
  }
  for (std::size_t k = 0; k < surfaces.size(); ++k)
    surfaces[k].moments.validate(fmt::format("surface {}", k + 1));
  SpectralMoments combined = surfaces.front().moments;
  for (std::size_t k = 1; k < surfaces.size(); ++k)
    combined = surface::combine(combined, surfaces[k].moments);
  const bool any_files =
      std::any_of(surfaces.begin(), surfaces.end(), [](const auto& a) { return a.from_files; });
  std::optional<SummitResult> summits;
  if (o.summits) summits = find_surface_summits(surfaces, combined, o.summit_bins);

  if (o.json) {
    Json j;
    Json arr = Json::array();
    for (const auto& a : surfaces) {
      Json js;
      js["source"] = a.from_files ? "files" : "params";
      if (a.from_files) js["files"] = a.files;
      Json mj = moments_json(a.moments, pair);
      for (auto it = mj.begin(); it != mj.end(); ++it) js[it.key()] = it.value();
      js["filter"] = a.from_files ? filter_json(s) : Json(nullptr);
      if (a.from_files) {
        js["rule"] = a.scans.size() > 1 ? Json(surface::to_string(s.rule)) : Json(nullptr);
        Json scans = Json::array();
        for (const auto& sc : a.scans) {
          Json x;
          x["file"] = sc.file;
          x["direction"] = sc.direction;
          x["profiles"] = sc.profiles;
          if (sc.profiles == 1) x["points"] = sc.points;
          x["dx"] = sc.dx;
          x["length"] = sc.length;
          if (sc.profiles == 1) x["evaluation_length"] = sc.evaluation_length;
          x["m0"] = sc.moments.m0;
          x["m2"] = sc.moments.m2;
          x["m4"] = sc.moments.m4;
          x["parameters"] = sc.parameters ? profile_parameters_json(*sc.parameters) : Json(nullptr);
          scans.push_back(x);
        }
        js["scans"] = scans;
        js["invalid_points"] = a.invalid_points;
        js["spikes_removed"] = a.spikes_removed;
      }
      if (a.areal) {
        js["size"] = {{"nx", a.areal->nx},
                      {"ny", a.areal->ny},
                      {"x", a.areal->dx * static_cast<double>(a.areal->nx - 1)},
                      {"y", a.areal->dy * static_cast<double>(a.areal->ny - 1)}};
        js["spacing"] = {{"dx", a.areal->dx}, {"dy", a.areal->dy}};
        js["Sq"] = a.Sq;
        js["areal_parameters"] =
            a.areal_parameters ? areal_parameters_json(*a.areal_parameters) : Json(nullptr);
        if (!a.areal_parameters) js["areal_parameters_note"] = a.areal_parameters_note;
      }
      arr.push_back(js);
    }
    j["surfaces"] = arr;
    Json c = moments_json(combined, pair);
    c["filter"] = any_files ? filter_json(s) : Json(nullptr);
    j["combined"] = c;
    if (summits) j["summits"] = summits_json(*summits, o.summits);
    if (pair) {
      j["material"] = {
          {"E_star", pair->E_star}, {"H", pair->H}, {"nu", pair->nu}, {"K", pair->K()}};
    }
    out += json_output(j);
  } else {
    if (any_files) {
      out += s.filter.is_none()
                 ? fmt::format("filter: none; levelling: {}\n", surface::to_string(s.level))
                 : fmt::format(
                       "filter: ISO 16610-21 Gaussian, lc = {}, ls = {} (ct = {:.3g}, ends: {}); "
                       "levelling: {}; anisotropy rule: {}\n",
                       s.filter.lc > 0 ? fmt::format("{:.4g} mm", s.filter.lc * 1e3) : "none",
                       s.filter.ls > 0 ? fmt::format("{:.4g} um", s.filter.ls * 1e6) : "none",
                       s.filter.truncation, surface::to_string(s.filter.end),
                       surface::to_string(s.level), surface::to_string(s.rule));
    }
    out +=
        fmt::format("{:<12}{:>11}{:>14}{:>11}{:>8}{:>8}{:>13}{}\n", "surface", "sigma[um]",
                    "eta[um^-2]", "R[um]", "beta", "alpha", "sigma_a[um]", pair ? "      psi" : "");
    auto row = [&](const std::string& name, const SpectralMoments& m) {
      const auto sa = try_sigma_a(m);
      out += fmt::format("{:<12}{}{}{}{}{}{}{}\n", name, cell(m.sigma() * 1e6, 11, 4),
                         cell(m.eta() * 1e-12, 14, 4, true), cell(m.R() * 1e6, 11, 4),
                         cell(m.beta(), 8, 4), cell(m.alpha(), 8, 3),
                         sa ? cell(*sa * 1e6, 13, 4) : fmt::format("{:>13}", "-"),
                         pair ? cell(surface::plasticity_index(*pair, m), 9, 4) : "");
    };
    for (std::size_t k = 0; k < surfaces.size(); ++k)
      row(fmt::format("{}", k + 1), surfaces[k].moments);
    row("combined", combined);
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
      for (const auto& sc : surfaces[k].scans) {
        out += fmt::format(
            "  surface {} scan {} [{}]: m0 = {:.4g} m^2, m2 = {:.4g}, m4 = {:.4g} m^-2\n", k + 1,
            sc.file, sc.direction, sc.moments.m0, sc.moments.m2, sc.moments.m4);
        if (sc.parameters) {
          const auto& p = *sc.parameters;
          out += fmt::format(
              "    ISO 21920-2: Ra = {:.4g} um, Rq = {:.4g} um, Rz = {:.4g} um ({} section{} of "
              "{:.4g} mm), Rsk = {:.4g}, Rku = {:.4g}, Rdq = {:.4g}\n",
              p.Ra * 1e6, p.Rq * 1e6, p.Rz * 1e6, p.sections, p.sections == 1 ? "" : "s",
              p.section_length * 1e3, p.Rsk, p.Rku, p.Rdq);
        }
      }
      if (surfaces[k].spikes_removed > 0) {
        out += fmt::format("  surface {}: {} spike points replaced (--spikes)\n", k + 1,
                           surfaces[k].spikes_removed);
      }
      if (surfaces[k].areal) {
        const auto& a = *surfaces[k].areal;
        out += fmt::format(
            "  surface {}: areal {} x {} points, dx = {:.4g} um, dy = {:.4g} um, "
            "Sq = {:.4g} um\n",
            k + 1, a.nx, a.ny, a.dx * 1e6, a.dy * 1e6, surfaces[k].Sq * 1e6);
        if (const auto& ap = surfaces[k].areal_parameters) {
          out += fmt::format(
              "    ISO 25178-2 (S-L surface, {} x {} points): Sa = {:.4g} um, Sq = {:.4g} um, "
              "Ssk = {:.4g}, Sku = {:.4g}, Sdq = {:.4g}\n",
              ap->nx, ap->ny, ap->Sa * 1e6, ap->Sq * 1e6, ap->Ssk, ap->Sku, ap->Sdq);
        } else {
          out += fmt::format("    {}\n", surfaces[k].areal_parameters_note);
        }
      }
    }
    if (summits) {
      const auto& set = summits->set;
      const auto sa = try_sigma_a(summits->moments);
      out += fmt::format(
          "summits of surface {} (8-neighbour maxima of the S-L surface): {} in {:.4g} mm^2; "
          "eta = {:.4g} um^-2 (spectral {:.4g}), sigma_s = {:.4g} um (spectral sigma_a {}), "
          "R = {:.4g} um (spectral {:.4g}); table: {} bins of {:.4g} um\n",
          summits->surface, set.summits.size(), set.area * 1e6, set.density() * 1e-12,
          summits->moments.eta() * 1e-12, set.height_standard_deviation() * 1e6,
          sa ? fmt::format("{:.4g}", *sa * 1e6) : "-", set.radius() * 1e6,
          summits->moments.R() * 1e6, summits->histogram.height.size() - 2,
          summits->histogram.bin_width * 1e6);
    }
  }
  std::vector<std::string> written;
  if (o.plot) {
    draw_plot(*o.plot, surfaces, s);
    written.push_back(*o.plot);
  }
  if (s.psd) {
    if (o.psd) {
      write_output(*o.psd, psd_csv(surfaces), out);
      if (!is_standard_output(*o.psd)) written.push_back(*o.psd);
    }
    if (o.psd_plot) {
      draw_psd_plot(*o.psd_plot, surfaces);
      written.push_back(*o.psd_plot);
    }
  }
  if (summits) {
    write_output(*o.summits, summits_csv(*summits, s), out);
    if (!is_standard_output(*o.summits)) written.push_back(*o.summits);
  }
  report_written(written, o.json || is_standard_output(o.psd) || is_standard_output(o.summits),
                 out);
}

}  // namespace

void add_roughness_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<RoughnessOptions>();
  auto* cmd = app.add_subcommand(
      "roughness",
      "Roughness parameters (sigma, eta, R, beta, alpha, spectral moments) of one or two joint "
      "halves from measured profiles (CSV/text or ISO 5436-2 X3P) or given parameters, combined "
      "as in thesis Eq. 5.1. Example: asperity roughness --surface a_max.csv,a_min.csv "
      "--surface b.x3p --json");
  auto* surf = cmd->add_option(
      "--surface", o->surfaces,
      "profile files of one half, comma-separated: one scan (isotropic), two scans (max- and "
      "min-slope directions found from m2), or scans tagged FILE@max / FILE@min (averaged per "
      "direction); or one areal X3P file (rows and columns give the two directions). Repeat for "
      "the second half.");
  auto* par = cmd->add_option("--params", o->params,
                              "parameters of one half instead of files: "
                              "sigma=1.763um,eta=3.34e-4um^-2,R=40.76um (repeatable)");
  surf->delimiter('\0');
  par->delimiter('\0');
  cmd->add_option("--lc", o->lc, "long-wave cut-off, or none to skip (default: 0.8mm)");
  cmd->add_option("--ls", o->ls, "short-wave cut-off, or none to skip (default: 20um)");
  cmd->add_option("--filter", o->filter, "gaussian (ISO 16610-21) or none (default: gaussian)");
  cmd->add_option("--level", o->level,
                  "form removal before filtering: none, mean or line (default: line)");
  cmd->add_option(
      "--end", o->end,
      "filter end effects: discard (drop ct*cut-off at each end) or regression (keep every "
      "point; Gaussian regression near the ends) (default: discard)");
  cmd->add_option("--truncation", o->truncation,
                  "ct: Gaussian weights kept within +-ct*cut-off, in [0.5, 3] (default: 1)");
  cmd->add_option("--rule", o->rule,
                  "m2, m4 of the equivalent isotropic surface from max/min-slope scans: geometric "
                  "(McCool) or arithmetic mean; m0 is always the arithmetic mean (default: "
                  "geometric)");
  cmd->add_option("--dx", o->dx,
                  "sampling interval of single-column (z only) text files, e.g. 0.5um");
  cmd->add_option("--E", o->E, "Young's modulus of both halves (for the plasticity index psi)");
  cmd->add_option("--nu", o->nu, "Poisson's ratio of both halves");
  cmd->add_option("--E1", o->E1, "Young's modulus of half 1");
  cmd->add_option("--nu1", o->nu1, "Poisson's ratio of half 1");
  cmd->add_option("--E2", o->E2, "Young's modulus of half 2");
  cmd->add_option("--nu2", o->nu2, "Poisson's ratio of half 2");
  cmd->add_option("--H", o->H, "hardness of the softer half (e.g. 5.8GPa)");
  cmd->add_option("--H1", o->H1, "hardness of half 1");
  cmd->add_option("--H2", o->H2, "hardness of half 2");
  cmd->add_option("--spikes", o->spikes,
                  "spike removal before levelling, off by default: replace points farther than "
                  "this many robust standard deviations (1.4826 MAD) from the median of their "
                  "2w+1 neighbours (Hampel), in [3, 1000], e.g. --spikes 6; off to disable");
  cmd->add_option("--spike-window", o->spike_window,
                  "w, the half-width of the spike window in points, in [1, 50] (default: 2)");
  cmd->add_option("--psd", o->psd,
                  "write the power spectral density (one-sided; sum of psd*df = mean square "
                  "height) of each filtered scan, or of an areal file's rows and columns, to this "
                  "CSV file (- for standard output)");
  cmd->add_option("--psd-plot", o->psd_plot, "draw the PSDs into this PNG file (log-log)");
  cmd->add_option(
      "--summits", o->summits,
      "find the summits (points higher than their 8 neighbours) of an areal file's S-L surface "
      "(of the sum of two halves' maps on one grid) and write their height distribution to "
      "this CSV file (height[m],density[1/m], a frequency polygon; - for standard output), the "
      "table a structure case reads as [rough_contact] summit_heights; the summit density, "
      "height spread and radius go to the report beside their spectral estimates");
  cmd->add_option("--summit-bins", o->summit_bins,
                  "bins of the --summits table, 1 to 10000 (default: 0 = Rice's rule, ceil(2 "
                  "n^(1/3)) for n summits)");
  cmd->add_flag("--json", o->json,
                "print JSON (SI units): surfaces[] and combined, each with sigma, eta, R, beta, "
                "alpha, m0, m2, m4, sigma_a (psi with a material), filter {lc, ls}; per scan "
                "the ISO 21920-2 parameters, per areal file the ISO 25178-2 parameters; with "
                "--summits, summits {count, eta, sigma, R, ...} beside their spectral estimates");
  cmd->add_option("--plot", o->plot,
                  "draw into this PNG file four panels: the raw, levelled and filtered profile "
                  "(first scan of each half, each panel with its own height scale) and the "
                  "histogram of the filtered heights against the Gaussian");
  cmd->callback([o, cmd, surf, par, &action] {
    o->order.clear();
    for (const auto* opt : cmd->parse_order()) {
      if (opt == surf) o->order.push_back(true);
      if (opt == par) o->order.push_back(false);
    }
    action = [o] { return run_guarded([o](std::string& out) { run_roughness(*o, out); }); };
  });
}

}  // namespace asperity::cli
