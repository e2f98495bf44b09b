// surface/: roughness parameters from measured profiles (thesis ch. 5-6, Eq. 5.1).
// Profiles are numpy arrays of heights [m] with a spacing dx [m]; areal maps are 2-D
// arrays z[iy, ix] (x fastest, as in X3P) with NaN for invalid points. Choices are
// strings: levelling "none" | "mean" | "line"; filter end effects "discard" |
// "regression"; anisotropy rule "geometric" | "arithmetic"; X3P data types "I", "L",
// "F", "D".
#include <fmt/format.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/string_view.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <asperity/core/error.hpp>
#include <asperity/surface/profile.hpp>
#include <asperity/surface/profile_io.hpp>
#include <asperity/surface/roughness.hpp>
#include <asperity/surface/scan_set.hpp>
#include <asperity/surface/summits.hpp>
#include <asperity/surface/texture.hpp>
#include <cmath>
#include <string>

#include "bindings.hpp"
#include "vectorize.hpp"

namespace asperity::python {

namespace {

using namespace nb::literals;
using namespace surface;

using Array1 = nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
using Array2 = nb::ndarray<const double, nb::ndim<2>, nb::c_contig, nb::device::cpu>;

Profile to_profile(const Array1& z, double dx, double x0 = 0.0) {
  Profile p;
  p.z.assign(z.data(), z.data() + z.shape(0));
  p.dx = dx;
  p.x0 = x0;
  p.source = "array";
  return p;
}

HeightMap to_map(const Array2& z, double dx, double dy) {
  HeightMap m;
  m.ny = z.shape(0);
  m.nx = z.shape(1);
  m.dx = dx;
  m.dy = m.ny > 1 ? dy : dx;
  m.source = "array";
  m.z.assign(z.data(), z.data() + m.nx * m.ny);
  bool any_invalid = false;
  for (double v : m.z) any_invalid = any_invalid || std::isnan(v);
  if (any_invalid) {
    m.valid.resize(m.z.size());
    for (std::size_t k = 0; k < m.z.size(); ++k) m.valid[k] = std::isnan(m.z[k]) ? 0 : 1;
  }
  return m;
}

nb::object map_array(const HeightMap& m) {
  auto data = std::make_unique<double[]>(m.z.size());
  for (std::size_t k = 0; k < m.z.size(); ++k) {
    data[k] = (m.valid.empty() || m.valid[k]) ? m.z[k] : std::nan("");
  }
  return detail::make_array(std::move(data), {m.ny, m.nx});
}

GaussianFilter make_filter(std::optional<double> lc, std::optional<double> ls, double truncation,
                           const std::string& end) {
  GaussianFilter f{.lc = lc.value_or(0.0),
                   .ls = ls.value_or(0.0),
                   .truncation = truncation,
                   .end = parse_end_effects(end, "end")};
  f.validate();
  return f;
}

X3pDataType parse_type(const std::string& t) {
  if (t == "I") return X3pDataType::int16;
  if (t == "L") return X3pDataType::int32;
  if (t == "F") return X3pDataType::float32;
  if (t == "D") return X3pDataType::float64;
  throw InvalidInput(fmt::format("type = \"{}\" is not allowed: use I, L, F or D", t));
}

nb::dict profile_dict(const Profile& p) {
  nb::dict d;
  std::vector<double> x(p.z.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = p.x0 + static_cast<double>(i) * p.dx;
  d["x"] = array_of(x);
  d["z"] = array_of(p.z);
  d["dx"] = p.dx;
  d["x0"] = p.x0;
  d["source"] = p.source;
  return d;
}

nb::dict parameters_dict(const ProfileParameters& p) {
  nb::dict d;
  d["Ra"] = p.Ra;
  d["Rq"] = p.Rq;
  d["Rz"] = p.Rz;
  d["Rsk"] = p.Rsk;
  d["Rku"] = p.Rku;
  d["Rdq"] = p.Rdq;
  d["sections"] = p.sections;
  d["section_length"] = p.section_length;
  return d;
}

nb::dict parameters_dict(const ArealParameters& a) {
  nb::dict d;
  d["Sa"] = a.Sa;
  d["Sq"] = a.Sq;
  d["Ssk"] = a.Ssk;
  d["Sku"] = a.Sku;
  d["Sdq"] = a.Sdq;
  d["nx"] = a.nx;
  d["ny"] = a.ny;
  return d;
}

SpikeRemoval make_spikes(std::optional<double> threshold, std::size_t window) {
  SpikeRemoval s{.threshold = threshold.value_or(0.0), .half_window = window};
  s.validate();
  return s;
}

nb::dict spectrum_dict(const PowerSpectrum& s) {
  nb::dict d;
  d["f"] = array_of(s.f);
  d["psd"] = array_of(s.psd);
  d["df"] = s.df;
  d["profiles"] = s.profiles;
  d["direction"] = s.direction;
  return d;
}

}  // namespace

void bind_surface(nb::module_& m) {
  nb::class_<SpectralMoments>(
      m, "SpectralMoments",
      "Spectral moments of a profile, m0 = <y^2> [m^2], m2 = <y'^2>, m4 = <y''^2> [m^-2]\n"
      "(Eq. 5.1, McCool). Two surfaces in contact combine by adding their moments (`+`).\n"
      "sigma = sqrt(m0), eta = m4/(6 pi sqrt(3) m2), R = 0.375 sqrt(pi/m4),\n"
      "alpha = m0 m4/m2^2, beta = sigma R eta = 0.02036 sqrt(alpha),\n"
      "sigma_a = sigma sqrt(1 - 3.717e-4/beta^2).")
      .def(nb::init<>())
      .def(
          "__init__",
          [](SpectralMoments* self, double m0, double m2, double m4) {
            new (self) SpectralMoments{m0, m2, m4};
          },
          "m0"_a, "m2"_a, "m4"_a)
      .def_rw("m0", &SpectralMoments::m0, "mean-square height [m^2]")
      .def_rw("m2", &SpectralMoments::m2, "mean-square slope")
      .def_rw("m4", &SpectralMoments::m4, "mean-square curvature [m^-2]")
      .def_prop_ro("sigma", &SpectralMoments::sigma, "rms height [m]")
      .def_prop_ro("eta", &SpectralMoments::eta, "areal density of asperities [m^-2]")
      .def_prop_ro("R", &SpectralMoments::R, "mean asperity-tip radius [m]")
      .def_prop_ro("alpha", &SpectralMoments::alpha, "bandwidth parameter m0 m4 / m2^2")
      .def_prop_ro("beta", &SpectralMoments::beta, "sigma R eta")
      .def_prop_ro("sigma_a", &SpectralMoments::sigma_a,
                   "spread of asperity heights [m]; raises InvalidInput for beta <= 0.01928")
      .def_static("from_parameters", &SpectralMoments::from_parameters, "sigma"_a, "eta"_a, "R"_a,
                  "The moments of given sigma [m], eta [m^-2] and R [m].")
      .def("validate", [](const SpectralMoments& s) { s.validate(); })
      .def("__add__", [](const SpectralMoments& a, const SpectralMoments& b) { return a + b; })
      .def("__repr__", [](const SpectralMoments& s) {
        return fmt::format("SpectralMoments(m0={:g}, m2={:g}, m4={:g})", s.m0, s.m2, s.m4);
      });

  m.def("combine", &combine, "a"_a, "b"_a,
        "Moments of the equivalent rough surface of two surfaces in contact: they add.");
  m.def(
      "equivalent_isotropic",
      [](const SpectralMoments& max_slope, const SpectralMoments& min_slope,
         const std::string& rule) {
        return equivalent_isotropic(max_slope, min_slope, parse_isotropic_rule(rule));
      },
      "max_slope"_a, "min_slope"_a, "rule"_a = "geometric",
      "Equivalent isotropic moments from scans in the max- and min-slope directions (Eq. 5.1):\n"
      "m0 = arithmetic mean; m2, m4 = geometric (McCool, default) or arithmetic mean.");
  m.def(
      "average_moments",
      [](const std::vector<SpectralMoments>& moments, const std::vector<double>& weights) {
        return average_moments(moments, weights);
      },
      "moments"_a, "weights"_a, "Weighted mean of the moments of several scans of one direction.");
  m.def("plasticity_index", &plasticity_index, "pair"_a, "moments"_a,
        "psi = (2E*/(pi K H)) sqrt(sigma_a/R) with E*, H, nu (for K) of the ContactPair.");

  m.def(
      "gaussian_transmission",
      [](const ArrayLike& wavelength, std::optional<double> lc, std::optional<double> ls) {
        const GaussianFilter f{.lc = lc.value_or(0.0), .ls = ls.value_or(0.0)};
        f.validate();
        return vectorize([&f](double w) { return f.transmission(w); }, wavelength);
      },
      "wavelength"_a, "lc"_a = 0.8e-3, "ls"_a = 20e-6,
      "Amplitude transmission of the ISO 16610-21 Gaussian band-pass (None = no cut-off).");
  m.def(
      "level_profile",
      [](const Array1& z, const std::string& how) {
        return array_of(level(to_profile(z, 1.0), parse_levelling(how)).z);
      },
      "z"_a, "how"_a = "line", "Heights with their mean (\"mean\") or least-squares line removed.");
  m.def(
      "filter_profile",
      [](const Array1& z, double dx, std::optional<double> lc, std::optional<double> ls,
         double truncation, const std::string& end) {
        const auto p = to_profile(z, dx);
        const auto f = make_filter(lc, ls, truncation, end);
        const auto r = f.is_none() ? p : f.apply(p);
        return std::make_pair(array_of(r.z), r.x0);
      },
      "z"_a, "dx"_a, "lc"_a = 0.8e-3, "ls"_a = 20e-6, "truncation"_a = 1.0, "end"_a = "discard",
      "ISO 16610-21 Gaussian band-pass of heights z [m] at spacing dx [m]. Returns (filtered\n"
      "heights, x of the first one); with end=\"discard\" ct*(lc+ls) is dropped at each end.");
  m.def(
      "spectral_moments",
      [](const Array1& z, double dx) { return spectral_moments(to_profile(z, dx)); }, "z"_a, "dx"_a,
      "Moments of heights as given: m0 = <z^2>, m2 from forward differences, m4 from central\n"
      "second differences.");
  m.def(
      "profile_moments",
      [](const Array1& z, double dx, const std::string& level_how, std::optional<double> lc,
         std::optional<double> ls, double truncation, const std::string& end) {
        return process_profile(to_profile(z, dx), parse_levelling(level_how),
                               make_filter(lc, ls, truncation, end))
            .moments;
      },
      "z"_a, "dx"_a, "level"_a = "line", "lc"_a = 0.8e-3, "ls"_a = 20e-6, "truncation"_a = 1.0,
      "end"_a = "discard",
      "The CLI's pipeline for one scan: level, Gaussian band-pass (None = no cut-off), moments.\n"
      "Raises InvalidInput when the scan is too short for the filter (naming the longest lc it\n"
      "allows) or is flat after levelling/filtering (only round-off left, e.g. a straight line).");
  m.def(
      "areal_moments",
      [](const Array2& z, double dx, double dy, const std::string& level_how,
         std::optional<double> lc, std::optional<double> ls, double truncation,
         const std::string& end) {
        const auto d = areal_moments(to_map(z, dx, dy), parse_levelling(level_how),
                                     make_filter(lc, ls, truncation, end));
        return std::make_pair(d.x, d.y);
      },
      "z"_a, "dx"_a, "dy"_a, "level"_a = "line", "lc"_a = 0.8e-3, "ls"_a = 20e-6,
      "truncation"_a = 1.0, "end"_a = "discard",
      "Moments along x (rows of z[iy, ix]) and y (columns), each averaged over its profiles.");
  m.def(
      "profile_parameters",
      [](const Array1& z, double dx, const std::string& level_how, std::optional<double> lc,
         std::optional<double> ls, double truncation, const std::string& end,
         std::optional<double> spikes, std::size_t spike_window) {
        auto p = to_profile(z, dx);
        const auto f = make_filter(lc, ls, truncation, end);
        remove_spikes(p, make_spikes(spikes, spike_window));
        const auto r = process_profile(p, parse_levelling(level_how), f);
        return parameters_dict(profile_parameters(r.filtered, f.lc));
      },
      "z"_a, "dx"_a, "level"_a = "line", "lc"_a = 0.8e-3, "ls"_a = 20e-6, "truncation"_a = 1.0,
      "end"_a = "discard", "spikes"_a = nb::none(), "spike_window"_a = 2,
      "ISO 21920-2 parameters of one scan through the CLI's pipeline (spike removal when\n"
      "`spikes` is a threshold in robust standard deviations, level, Gaussian band-pass):\n"
      "{Ra, Rq, Rz, Rsk, Rku, Rdq, sections, section_length} in SI; Rz over sections of lc,\n"
      "Rdq from forward differences (= sqrt(m2)). lc=None, ls=None: no filter.");
  m.def(
      "texture_parameters",
      [](const Array1& z, double dx, double section_length) {
        return parameters_dict(profile_parameters(to_profile(z, dx), section_length));
      },
      "z"_a, "dx"_a, "section_length"_a = 0.0,
      "ISO 21920-2 parameters of heights z [m] as given (already a roughness profile), with\n"
      "sections of `section_length` [m] for Rz (0: one section).");
  m.def(
      "areal_parameters",
      [](const Array2& z, double dx, double dy, const std::string& level_how,
         std::optional<double> lc, std::optional<double> ls, double truncation,
         const std::string& end, std::optional<double> spikes, std::size_t spike_window) {
        auto map = to_map(z, dx, dy);
        remove_spikes(map, make_spikes(spikes, spike_window));
        const auto sl = scale_limited_surface(map, parse_levelling(level_how),
                                              make_filter(lc, ls, truncation, end));
        return parameters_dict(areal_parameters(sl));
      },
      "z"_a, "dx"_a, "dy"_a, "level"_a = "line", "lc"_a = 0.8e-3, "ls"_a = 20e-6,
      "truncation"_a = 1.0, "end"_a = "discard", "spikes"_a = nb::none(), "spike_window"_a = 2,
      "ISO 25178-2 parameters {Sa, Sq, Ssk, Sku, Sdq, nx, ny} of the S-L surface of z[iy, ix]:\n"
      "least-squares plane (level=\"line\"), then the areal Gaussian filter (ISO 16610-61,\n"
      "separable: the profile filter along x, then y). Needs every point valid (no NaN).");
  m.def(
      "scale_limited_surface",
      [](const Array2& z, double dx, double dy, const std::string& level_how,
         std::optional<double> lc, std::optional<double> ls, double truncation,
         const std::string& end) {
        const auto sl = scale_limited_surface(to_map(z, dx, dy), parse_levelling(level_how),
                                              make_filter(lc, ls, truncation, end));
        return std::make_tuple(map_array(sl), sl.x0, sl.y0);
      },
      "z"_a, "dx"_a, "dy"_a, "level"_a = "line", "lc"_a = 0.8e-3, "ls"_a = 20e-6,
      "truncation"_a = 1.0, "end"_a = "discard",
      "The S-L surface of areal_parameters: (z[iy, ix], x of the first column, y of the\n"
      "first row); with end=\"discard\" ct*(lc+ls) is cropped at each edge.");
  m.def(
      "find_summits",
      [](const Array2& z, double dx, double dy, double x0, double y0, std::size_t bins) {
        auto map = to_map(z, dx, dy);
        map.x0 = x0;
        map.y0 = y0;
        const auto set = find_summits(map);
        const auto hist = summit_histogram(set, bins);
        std::vector<double> x, y, h, k;
        for (const auto& p : set.summits) {
          x.push_back(p.x);
          y.push_back(p.y);
          h.push_back(p.z);
          k.push_back(p.curvature);
        }
        auto table = std::make_unique<double[]>(2 * hist.height.size());
        for (std::size_t i = 0; i < hist.height.size(); ++i) {
          table[2 * i] = hist.height[i];
          table[2 * i + 1] = hist.density[i];
        }
        nb::dict d;
        d["x"] = array_of(x);
        d["y"] = array_of(y);
        d["z"] = array_of(h);
        d["curvature"] = array_of(k);
        d["area"] = set.area;
        d["points"] = set.points;
        d["eta"] = set.density();
        d["mean_height"] = set.mean_height();
        d["sigma"] = set.height_standard_deviation();
        d["R"] = set.radius();
        d["table"] = detail::make_array(std::move(table), {hist.height.size(), 2});
        d["bin_width"] = hist.bin_width;
        return d;
      },
      "z"_a, "dx"_a, "dy"_a, "x0"_a = 0.0, "y0"_a = 0.0, "bins"_a = 0,
      "Summits of a complete map z[iy, ix] (normally an S-L surface from\n"
      "scale_limited_surface): interior points higher than their 8 neighbours (an equal\n"
      "neighbour earlier in raster order counts as higher). Returns {x, y, z, curvature\n"
      "(mean, -(z_xx + z_yy)/2 by central differences) [1/m], area, points, eta [1/m^2],\n"
      "mean_height, sigma (of the summit heights), R = 1/<curvature>, table, bin_width}:\n"
      "table (n x 2: height [m], density [1/m]) is the heights' frequency polygon over `bins`\n"
      "bins (0: Rice's rule), the summit_heights of RoughContactSurface and of a structure\n"
      "case (docs/roughness.md).");
  m.def(
      "profile_power_spectrum",
      [](const Array1& z, double dx) { return spectrum_dict(power_spectrum(to_profile(z, dx))); },
      "z"_a, "dx"_a,
      "One-sided PSD of heights z [m] as given: {f [1/m], psd [m^3], df, profiles, direction},\n"
      "psd_k = c |Z_k|^2 dx/n (c = 2, 1 at f = 0 and Nyquist), so sum(psd) * df = mean(z**2).");
  m.def(
      "areal_power_spectrum",
      [](const Array2& z, double dx, double dy, const std::string& axis) {
        if (axis != "x" && axis != "y")
          throw InvalidInput(fmt::format("axis = \"{}\" is not allowed: use x or y", axis));
        return spectrum_dict(power_spectrum(to_map(z, dx, dy), axis == "x"));
      },
      "z"_a, "dx"_a, "dy"_a, "axis"_a = "x",
      "Mean one-sided PSD of the rows (axis=\"x\") or columns of z[iy, ix] as given.");
  m.def(
      "remove_spikes",
      [](const Array1& z, double threshold, std::size_t window) {
        auto p = to_profile(z, 1.0);
        const std::size_t n = remove_spikes(p, make_spikes(threshold, window));
        return std::make_pair(array_of(p.z), n);
      },
      "z"_a, "threshold"_a, "window"_a = 2,
      "Hampel spike removal: points farther than `threshold` robust standard deviations\n"
      "(1.4826 MAD about the least-squares line) from the median of their 2w+1 neighbours\n"
      "are replaced by the chord of their neighbours. Returns (heights, points replaced).");
  m.def(
      "equivalent_isotropic_surface",
      [](const std::vector<std::string>& files, const std::string& level_how,
         std::optional<double> lc, std::optional<double> ls, double truncation,
         const std::string& end, const std::string& rule, std::optional<double> dx,
         std::optional<double> spikes, std::size_t spike_window, bool psd) {
        std::vector<ScanFile> scans;
        for (const auto& f : files) scans.push_back(parse_scan_file(f));
        const ScanSettings settings{.level = parse_levelling(level_how),
                                    .filter = make_filter(lc, ls, truncation, end),
                                    .rule = parse_isotropic_rule(rule),
                                    .text = {.dx = dx},
                                    .spikes = make_spikes(spikes, spike_window),
                                    .psd = psd};
        IsotropicSurface r;
        {
          nb::gil_scoped_release release;  // reading and filtering: C++ only
          r = equivalent_isotropic_surface(scans, settings);
        }
        nb::list per_scan;
        for (const auto& sc : r.scans) {
          nb::dict d;
          d["file"] = sc.file;
          d["direction"] = sc.direction;
          d["points"] = sc.points;
          d["profiles"] = sc.profiles;
          d["dx"] = sc.dx;
          d["moments"] = sc.moments;
          d["parameters"] =
              sc.parameters ? nb::object(parameters_dict(*sc.parameters)) : nb::none();
          per_scan.append(d);
        }
        nb::dict out;
        out["moments"] = r.moments;
        out["scans"] = per_scan;
        out["invalid_points"] = r.invalid_points;
        out["areal_parameters"] =
            r.areal_parameters ? nb::object(parameters_dict(*r.areal_parameters)) : nb::none();
        if (r.areal && !r.areal_parameters) out["areal_parameters_note"] = r.areal_parameters_note;
        if (r.areal) out["Sq_about_plane"] = r.Sq;
        out["spikes_removed"] = r.spikes_removed;
        nb::list spectra;
        for (const auto& sp : r.psd) spectra.append(spectrum_dict(sp));
        if (psd) out["psd"] = spectra;
        return out;
      },
      "files"_a, "level"_a = "line", "lc"_a = 0.8e-3, "ls"_a = 20e-6, "truncation"_a = 1.0,
      "end"_a = "discard", "rule"_a = "geometric", "dx"_a = nb::none(), "spikes"_a = nb::none(),
      "spike_window"_a = 2, "psd"_a = false,
      "The equivalent isotropic surface of scan files (\"FILE\", \"FILE@max\", \"FILE@min\", or\n"
      "one areal file), by the function `asperity roughness --surface` and the case files use:\n"
      "{moments, scans: [{file, direction, points, profiles, dx, moments, parameters}],\n"
      "invalid_points, areal_parameters (an areal file's ISO 25178-2 parameters or None),\n"
      "spikes_removed, psd (with psd=True: per scan, or x and y of an areal file)}.");
  m.def(
      "rms_height_about_plane",
      [](const Array2& z, double dx, double dy) {
        return to_map(z, dx, dy).rms_height_about_plane();
      },
      "z"_a, "dx"_a = 1.0, "dy"_a = 1.0, "Areal Sq about the least-squares plane (NaN = invalid).");

  m.def(
      "read_profile",
      [](const std::string& path, std::optional<double> dx) {
        TextReadOptions o;
        o.dx = dx;
        return profile_dict(read_profile_text(path, o));
      },
      "path"_a, "dx"_a = nb::none(),
      "Reads a text/CSV profile (units in the header). Returns {x, z, dx, x0, source} in SI.");
  m.def(
      "read_x3p",
      [](const std::string& path) {
        const auto map = read_x3p(path);
        nb::dict d;
        d["z"] = map_array(map);
        d["dx"] = map.dx;
        d["dy"] = map.dy;
        d["x0"] = map.x0;
        d["y0"] = map.y0;
        d["invalid_points"] = map.invalid_count();
        d["source"] = map.source;
        return d;
      },
      "path"_a,
      "Reads an ISO 5436-2 X3P file. Returns {z (ny x nx, NaN = invalid), dx, dy, x0, y0,\n"
      "invalid_points, source} in SI; checks the MD5 checksums.");
  m.def(
      "write_x3p",
      [](const std::string& path, const Array2& z, double dx, double dy, const std::string& type,
         bool inline_data) {
        write_x3p(path, to_map(z, dx, dy), {.type = parse_type(type), .inline_data = inline_data});
      },
      "path"_a, "z"_a, "dx"_a, "dy"_a = 0.0, "type"_a = "D", "inline_data"_a = false,
      "Writes z[iy, ix] (one row = a profile, PRF) as X3P; NaN marks invalid points.");
}

}  // namespace asperity::python
