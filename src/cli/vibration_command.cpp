// asperity vibration: nonlinear modes (EPMC), forced response curves and the
// quasi-static modal estimate of a structure with joint elements, by harmonic balance,
// from a TOML case file (format: asperity/vibration/case.hpp, which also parses, runs
// and summarises the case; this file writes the outputs and plots).
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>

#include "asperity/core/error.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/vibration/case.hpp"
#include "commands.hpp"
#include "common.hpp"

namespace asperity::cli {

namespace {

using namespace asperity::vibration;

struct VibrationOptions {
  std::string case_file;
  std::optional<std::string> out_dir;
  bool json = false;
  bool no_plots = false;
  bool stability = false;
};

// A CSV cell; NaN (a quantity that does not apply, e.g. a pressure of an element other
// than rough_contact in interface_map.csv) is an empty cell.
std::string num(double x) {
  return std::isnan(x) ? std::string() : fmt::format("{:.12g}", x);
}

// A forced-response curve's legend: its forcing amplitude F in N, the force scale times
// the norm of the table's harmonic force vector over DOFs and harmonics (for one forced
// DOF and one harmonic, that force's amplitude), or of the values given at an output point
// ("F = 0.1 N at tip"); as vibration.force_label in Python.
template <class ForcedTable>
std::string force_legend(const ForcedTable& t, double scale) {
  if (!t.at_point.point.empty())
    return fmt::format("F = {:.4g} N at {}", scale * t.at_point.amplitude, t.at_point.point);
  const double norm = std::sqrt(t.force_cos.squaredNorm() + t.force_sin.squaredNorm());
  if (!(norm > 0.0)) return fmt::format("force x {:.4g}", scale);
  return fmt::format("F = {:.4g} N", scale * norm);
}

std::string force_label(const VibrationCase& c, std::size_t table, double scale) {
  if (table >= c.frequency_responses.size()) return fmt::format("force x {:.4g}", scale);
  return force_legend(c.frequency_responses[table], scale);
}

// One CSV: a header line and one line per row, every value with 12 significant digits.
std::string csv(const std::vector<std::string>& header,
                const std::vector<std::vector<double>>& columns) {
  std::string s;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (i) s += ',';
    s += header[i];
  }
  s += '\n';
  const std::size_t n = columns.empty() ? 0 : columns.front().size();
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (i) s += ',';
      s += num(columns[i][k]);
    }
    s += '\n';
  }
  return s;
}

// The interface map for ParaView: a VTK XML unstructured grid (ASCII) of one vertex cell
// (VTK_VERTEX = 1) per interface element at its centroid, with the element index and area,
// and per backbone point k the quantities as arrays "<quantity> point <k> log10a <x>" (k as
// in interface_map.csv). A quantity with a non-finite value at point k (a pressure of an
// element other than rough_contact) is left out of that point.
std::string interface_map_vtu(const InterfaceMap& m, const std::vector<ElementSite>& sites,
                              const Eigen::VectorXd& log10_amplitude) {
  const std::size_t n = m.elements.size();
  std::string s =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <FieldData>\n";
  s += fmt::format(
      "      <DataArray type=\"Float64\" Name=\"log10_amplitude\" NumberOfTuples=\"{}\" "
      "format=\"ascii\">\n",
      log10_amplitude.size());
  for (Eigen::Index k = 0; k < log10_amplitude.size(); ++k) {
    s += fmt::format("{:.17g}\n", log10_amplitude(k));
  }
  s += "      </DataArray>\n    </FieldData>\n";
  s += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n      <PointData>\n", n,
                   n);
  const auto array = [&](const std::string& type, const std::string& name, auto value) {
    s += fmt::format("        <DataArray type=\"{}\" Name=\"{}\" format=\"ascii\">\n", type, name);
    for (std::size_t j = 0; j < n; ++j) s += fmt::format("{}\n", value(j));
    s += "        </DataArray>\n";
  };
  array("Int32", "interface_element",
        [&](std::size_t j) { return sites[m.elements[j]].interface_element; });
  array("Float64", "area_m2", [&](std::size_t j) { return sites[m.elements[j]].area; });
  const std::size_t width =
      fmt::format("{}", std::max<Eigen::Index>(log10_amplitude.size() - 1, 0)).size();
  const std::pair<const char*, const Eigen::MatrixXd*> quantities[] = {
      {"dissipation_J_per_m2", &m.dissipation},
      {"mean_pressure_Pa", &m.mean_pressure},
      {"slip_fraction", &m.slip_fraction},
      {"open_fraction", &m.open_fraction}};
  for (const auto& [quantity, values] : quantities) {
    for (Eigen::Index k = 0; k < values->rows(); ++k) {
      if (!values->row(k).allFinite()) continue;
      array("Float64",
            fmt::format("{} point {:0{}} log10a {:.2f}", quantity, k, width, log10_amplitude(k)),
            [&](std::size_t j) {
              return fmt::format("{:.12g}", (*values)(k, static_cast<Eigen::Index>(j)));
            });
    }
  }
  s += "      </PointData>\n      <Points>\n"
       "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t j = 0; j < n; ++j) {
    const Eigen::Vector3d& x = sites[m.elements[j]].centroid;
    s += fmt::format("{:.17g} {:.17g} {:.17g}\n", x(0), x(1), x(2));
  }
  s += "        </DataArray>\n      </Points>\n      <Cells>\n"
       "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t j = 0; j < n; ++j) s += fmt::format("{}\n", j);
  s += "        </DataArray>\n"
       "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t j = 0; j < n; ++j) s += fmt::format("{}\n", j + 1);
  s += "        </DataArray>\n"
       "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t j = 0; j < n; ++j) s += "1\n";
  s += "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return s;
}

std::vector<double> vec(const Eigen::VectorXd& v) {
  return {v.data(), v.data() + v.size()};
}

// Series of y against x keeping only points a log axis can show.
Series positive_series(const std::string& title, const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                       bool logy, const std::string& style) {
  Series s{.title = title, .style = style};
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (x(i) > 0.0 && std::isfinite(y(i)) && (!logy || y(i) > 0.0)) {
      s.x.push_back(x(i));
      s.y.push_back(y(i));
    }
  }
  return s;
}

// An output point's name as part of a file or column name: letters, digits, '-' and '_'
// kept, anything else '_'.
std::string file_stem(const std::string& name) {
  std::string out;
  for (const char ch : name) {
    const bool keep = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                      (ch >= '0' && ch <= '9') || ch == '-' || ch == '_';
    out += keep ? ch : '_';
  }
  return out.empty() ? "output" : out;
}

std::vector<std::string> write_files(const VibrationCase& c, const VibrationResult& r,
                                     joint::StagedDirectory& dir, bool plots) {
  std::vector<std::string> written;
  auto write = [&](const std::string& name, const std::string& content) {
    write_file_atomically(dir.file(name), content);
    written.push_back(name);
  };
  write("summary.json", json_output(to_json(SummaryValue(r.summary))));
  if (r.nonlinear_mode) {
    const auto& m = *r.nonlinear_mode;
    std::vector<std::string> h{"log10_amplitude", "amplitude",     "omega_rad_s",
                               "frequency_hz",    "damping_ratio", "xi_per_s"};
    std::vector<std::vector<double>> cols{vec(m.log10_amplitude), vec(m.amplitude),
                                          vec(m.omega),           vec(m.frequency_hz),
                                          vec(m.damping_ratio),   vec(m.xi)};
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      h.push_back(fmt::format("amplitude_dof{}_m", c.output_dofs[o]));
      cols.push_back(vec(m.output_amplitude.col(static_cast<Eigen::Index>(o))));
    }
    for (const auto& op : r.nonlinear_mode_output_points) {
      for (Eigen::Index d = 0; d < 3; ++d) {
        h.push_back(fmt::format("{}_{}_amplitude_m", file_stem(op.name), "xyz"[d]));
        cols.push_back(vec(op.displacement.col(d)));
        h.push_back(fmt::format("{}_{}_acceleration_m_s2", file_stem(op.name), "xyz"[d]));
        cols.push_back(vec(op.acceleration.col(d)));
      }
    }
    write("nonlinear_mode.csv", csv(h, cols));
  }
  if (r.nonlinear_mode && r.nonlinear_mode_interface) {
    // One row per point and interface element (issue 20's interface maps).
    const auto& m = *r.nonlinear_mode_interface;
    std::vector<std::vector<double>> cols(10);
    for (Eigen::Index k = 0; k < m.dissipation.rows(); ++k) {
      for (std::size_t j = 0; j < m.elements.size(); ++j) {
        const auto& site = c.element_sites[m.elements[j]];
        const auto jj = static_cast<Eigen::Index>(j);
        cols[0].push_back(static_cast<double>(k));
        cols[1].push_back(r.nonlinear_mode->log10_amplitude(k));
        cols[2].push_back(static_cast<double>(site.interface_element));
        for (int d = 0; d < 3; ++d)
          cols[3 + static_cast<std::size_t>(d)].push_back(site.centroid(d));
        cols[6].push_back(m.dissipation(k, jj));
        cols[7].push_back(m.mean_pressure(k, jj));
        cols[8].push_back(m.slip_fraction(k, jj));
        cols[9].push_back(m.open_fraction(k, jj));
      }
    }
    write("interface_map.csv",
          csv({"point", "log10_amplitude", "interface_element", "x_m", "y_m", "z_m",
               "dissipation_J_per_m2", "mean_pressure_Pa", "slip_fraction", "open_fraction"},
              cols));
    write("interface_map.vtu",
          interface_map_vtu(m, c.element_sites, r.nonlinear_mode->log10_amplitude));
  }
  const auto& harmonics = c.harmonic_balance.harmonics;
  for (std::size_t k = 0; k < r.frequency_response.size(); ++k) {
    const auto& cv = r.frequency_response[k];
    std::vector<std::string> h{"omega_rad_s", "frequency_hz"};
    std::vector<std::vector<double>> cols{vec(cv.omega), vec(cv.omega / (2.0 * std::numbers::pi))};
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      const auto oi = static_cast<Eigen::Index>(o);
      const auto d = c.output_dofs[o];
      h.push_back(fmt::format("amplitude_dof{}_m", d));
      cols.push_back(vec(cv.output_amplitude.col(oi)));
      h.push_back(fmt::format("max_displacement_dof{}_m", d));
      cols.push_back(vec(cv.max_displacement.col(oi)));
      for (std::size_t hh = 0; hh < harmonics.size(); ++hh) {
        h.push_back(fmt::format("harmonic{}_dof{}_m", harmonics[hh], d));
        cols.push_back(vec(cv.harmonic_amplitude[o].col(static_cast<Eigen::Index>(hh))));
      }
    }
    if (!cv.stability.empty()) {  // Hill's method: 1 stable, 0 unstable
      std::vector<double> stable, max_re;
      for (const PeriodicStability& p : cv.stability) {
        stable.push_back(p.stable ? 1.0 : 0.0);
        max_re.push_back(p.max_real_exponent);
      }
      h.push_back("stable");
      cols.push_back(std::move(stable));
      h.push_back("max_real_exponent_per_s");
      cols.push_back(std::move(max_re));
    }
    write(fmt::format("frequency_response_{}.csv", k + 1), csv(h, cols));
  }
  for (std::size_t k = 0; k < r.force_response.size(); ++k) {
    const auto& cv = r.force_response[k];
    std::vector<std::string> h{"force_scale"};
    std::vector<std::vector<double>> cols{vec(cv.force_scale)};
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      const auto oi = static_cast<Eigen::Index>(o);
      const auto d = c.output_dofs[o];
      h.push_back(fmt::format("amplitude_dof{}_m", d));
      cols.push_back(vec(cv.output_amplitude.col(oi)));
      h.push_back(fmt::format("max_displacement_dof{}_m", d));
      cols.push_back(vec(cv.max_displacement.col(oi)));
      for (std::size_t hh = 0; hh < harmonics.size(); ++hh) {
        h.push_back(fmt::format("harmonic{}_dof{}_m", harmonics[hh], d));
        cols.push_back(vec(cv.harmonic_amplitude[o].col(static_cast<Eigen::Index>(hh))));
      }
    }
    write(fmt::format("force_response_{}.csv", r.force_response_table[k] + 1), csv(h, cols));
  }
  for (std::size_t k = 0; k < r.amplitude_control.size(); ++k) {
    const auto& a = r.amplitude_control[k];
    std::vector<std::string> h{"omega_rad_s", "frequency_hz", "force_scale"};
    std::vector<std::vector<double>> cols{vec(a.omega), vec(a.omega / (2.0 * std::numbers::pi)),
                                          vec(a.force_scale)};
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      h.push_back(fmt::format("amplitude_dof{}_m", c.output_dofs[o]));
      cols.push_back(vec(a.output_amplitude.col(static_cast<Eigen::Index>(o))));
    }
    write(fmt::format("amplitude_control_{}.csv", r.amplitude_control_table[k] + 1), csv(h, cols));
  }
  for (std::size_t k = 0; k < r.phase_resonance.size(); ++k) {
    const auto& p = r.phase_resonance[k];
    std::vector<std::string> h{"amplitude_m", "omega_rad_s", "frequency_hz", "force_scale"};
    std::vector<std::vector<double>> cols{vec(p.amplitude), vec(p.omega),
                                          vec(p.omega / (2.0 * std::numbers::pi)),
                                          vec(p.force_scale)};
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      h.push_back(fmt::format("amplitude_dof{}_m", c.output_dofs[o]));
      cols.push_back(vec(p.output_amplitude.col(static_cast<Eigen::Index>(o))));
    }
    write(fmt::format("phase_resonance_{}.csv", r.phase_resonance_table[k] + 1), csv(h, cols));
  }
  for (std::size_t k = 0; k < r.superharmonic_resonance.size(); ++k) {
    const auto& p = r.superharmonic_resonance[k];
    std::vector<std::string> h{"force_scale", "omega_rad_s", "frequency_hz"};
    std::vector<std::vector<double>> cols{vec(p.force_scale), vec(p.omega),
                                          vec(p.omega / (2.0 * std::numbers::pi))};
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      const auto oi = static_cast<Eigen::Index>(o);
      h.push_back(fmt::format("amplitude_dof{}_m", c.output_dofs[o]));
      cols.push_back(vec(p.output_amplitude.col(oi)));
      h.push_back(fmt::format("harmonic{}_dof{}_m", p.harmonic, c.output_dofs[o]));
      cols.push_back(vec(p.output_harmonic_amplitude.col(oi)));
    }
    write(fmt::format("superharmonic_resonance_{}.csv", r.superharmonic_resonance_table[k] + 1),
          csv(h, cols));
  }
  for (std::size_t k = 0; k < r.backbone_rom.size(); ++k) {
    const auto& m = r.backbone_rom[k];
    std::vector<std::string> h{"omega_rad_s", "frequency_hz", "modal_amplitude", "side"};
    std::vector<double> side;  // 0: below the backbone, 1: above it
    for (Eigen::Index i = 0; i < m.omega.size(); ++i)
      side.push_back(static_cast<std::size_t>(i) < m.low_side_points ? 0.0 : 1.0);
    std::vector<std::vector<double>> cols{vec(m.omega), vec(m.omega / (2.0 * std::numbers::pi)),
                                          vec(m.amplitude), std::move(side)};
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      h.push_back(fmt::format("amplitude_dof{}_m", c.output_dofs[o]));
      cols.push_back(vec(m.output_amplitude.col(static_cast<Eigen::Index>(o))));
    }
    write(fmt::format("backbone_rom_{}.csv", k + 1), csv(h, cols));
  }
  if (r.quasi_static_mode) {
    const auto& q = *r.quasi_static_mode;
    write("quasi_static_mode.csv",
          csv({"amplitude", "omega_rad_s", "frequency_hz", "damping_ratio", "modal_force",
               "dissipation_J"},
              {vec(q.amplitude), vec(q.omega), vec(q.frequency_hz), vec(q.damping_ratio),
               vec(q.modal_force), vec(q.dissipation)}));
  }
  if (!plots) return written;

  // omega(a) and zeta(a): EPMC and the quasi-static estimate on one log amplitude axis.
  if (r.nonlinear_mode || r.quasi_static_mode) {
    PlotSpec f{.title = "Nonlinear mode: natural frequency against modal amplitude",
               .xlabel = "modal amplitude a [sqrt(kg) m]",
               .ylabel = "frequency [Hz]",
               .logx = true};
    PlotSpec z{.title = "Nonlinear mode: damping ratio against modal amplitude",
               .xlabel = "modal amplitude a [sqrt(kg) m]",
               .ylabel = "damping ratio zeta",
               .logx = true};
    bool zpos = true;
    if (r.nonlinear_mode) zpos = zpos && (r.nonlinear_mode->damping_ratio.array() > 0.0).all();
    if (r.quasi_static_mode)
      zpos = zpos && (r.quasi_static_mode->damping_ratio.array() > 0.0).all();
    z.logy = zpos;
    if (r.nonlinear_mode) {
      const auto& m = *r.nonlinear_mode;
      f.series.push_back(
          positive_series("EPMC (harmonic balance)", m.amplitude, m.frequency_hz, false, "lines"));
      z.series.push_back(
          positive_series("EPMC (harmonic balance)", m.amplitude, m.damping_ratio, zpos, "lines"));
    }
    if (r.quasi_static_mode) {
      const auto& q = *r.quasi_static_mode;
      f.series.push_back(positive_series("quasi-static (Masing)", q.amplitude, q.frequency_hz,
                                         false, "linespoints pt 6 ps 0.7 dt 2"));
      z.series.push_back(positive_series("quasi-static (Masing)", q.amplitude, q.damping_ratio,
                                         zpos, "linespoints pt 6 ps 0.7 dt 2"));
    }
    plot_png(dir.file("modal_frequency.png"), f);
    written.push_back("modal_frequency.png");
    plot_png(dir.file("modal_damping.png"), z);
    written.push_back("modal_damping.png");
  }
  // The interface at the largest amplitude: dissipation per cycle and area by element,
  // eight classes a factor 10^(1/2) apart down from the largest, seen along the normal.
  if (r.nonlinear_mode && r.nonlinear_mode_interface &&
      r.nonlinear_mode_interface->dissipation.rows() > 0) {
    const auto& m = *r.nonlinear_mode_interface;
    const Eigen::Index last = m.dissipation.rows() - 1;
    const double wmax = m.dissipation.row(last).maxCoeff();
    constexpr int kClasses = 8;
    static const char* colours[kClasses] = {"#440154", "#46327e", "#365c8d", "#277f8e",
                                            "#1fa187", "#4ac16d", "#a0da39", "#fde725"};
    PlotSpec pm{.title = fmt::format("Interface dissipation per cycle at modal amplitude {:.3g} "
                                     "({:.2f} Hz)",
                                     r.nonlinear_mode->amplitude(last),
                                     r.nonlinear_mode->frequency_hz(last)),
                .xlabel = "x [mm]",
                .ylabel = "y [mm]",
                .extra = "set size ratio -1\nset key outside right"};
    Series low{.title = "below 1e-4 of the largest",
               .style = "points pt 5 ps 1.2 lc rgb '#d0d0d0'"};
    std::vector<Series> cls(kClasses);
    for (int k = 0; k < kClasses; ++k) {
      cls[static_cast<std::size_t>(k)].title =
          fmt::format("{:.2g}-{:.2g} J/m^2", wmax * std::pow(10.0, -0.5 * (kClasses - k)),
                      wmax * std::pow(10.0, -0.5 * (kClasses - 1 - k)));
      cls[static_cast<std::size_t>(k)].style =
          fmt::format("points pt 5 ps 1.2 lc rgb '{}'", colours[k]);
    }
    for (std::size_t j = 0; j < m.elements.size(); ++j) {
      const Eigen::Vector3d x = c.element_sites[m.elements[j]].centroid * 1e3;
      const double w = m.dissipation(last, static_cast<Eigen::Index>(j));
      const double classes_down = wmax > 0.0 && w > 0.0 ? std::log10(wmax / w) / 0.5 : 1e9;
      Series& target =
          classes_down >= kClasses
              ? low
              : cls[static_cast<std::size_t>(
                    kClasses - 1 - std::min(kClasses - 1, static_cast<int>(classes_down)))];
      target.x.push_back(x.x());
      target.y.push_back(x.y());
    }
    if (!low.x.empty()) pm.series.push_back(low);
    for (auto it = cls.rbegin(); it != cls.rend(); ++it)
      if (!it->x.empty()) pm.series.push_back(*it);
    plot_png(dir.file("interface_dissipation.png"), pm);
    written.push_back("interface_dissipation.png");
  }
  // The backbone against each output point's acceleration (its direction of largest
  // response at the largest amplitude), as a measured backbone is plotted.
  if (r.nonlinear_mode) {
    const auto& m = *r.nonlinear_mode;
    for (const auto& op : r.nonlinear_mode_output_points) {
      if (op.acceleration.rows() == 0) continue;
      Eigen::Index d = 0;
      op.acceleration.row(op.acceleration.rows() - 1).maxCoeff(&d);
      const std::string axis =
          fmt::format("first-harmonic acceleration of {} ({}) [m/s^2]", op.name, "xyz"[d]);
      const bool zpos = (m.damping_ratio.array() > 0.0).all();
      PlotSpec f{
          .title = fmt::format("Nonlinear mode: frequency against the response at {}", op.name),
          .xlabel = axis,
          .ylabel = "frequency [Hz]",
          .logx = true};
      PlotSpec z{
          .title = fmt::format("Nonlinear mode: damping ratio against the response at {}", op.name),
          .xlabel = axis,
          .ylabel = "damping ratio zeta",
          .logx = true,
          .logy = zpos};
      f.series.push_back(positive_series("EPMC (harmonic balance)", op.acceleration.col(d),
                                         m.frequency_hz, false, "lines"));
      z.series.push_back(positive_series("EPMC (harmonic balance)", op.acceleration.col(d),
                                         m.damping_ratio, zpos, "lines"));
      const std::string stem = file_stem(op.name);
      plot_png(dir.file("modal_frequency_" + stem + ".png"), f);
      written.push_back("modal_frequency_" + stem + ".png");
      plot_png(dir.file("modal_damping_" + stem + ".png"), z);
      written.push_back("modal_damping_" + stem + ".png");
    }
  }
  if (!r.frequency_response.empty()) {
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      PlotSpec p{.title = fmt::format("Forced response of DOF {}: first-harmonic amplitude",
                                      c.output_dofs[o]),
                 .xlabel = "excitation frequency [Hz]",
                 .ylabel = "amplitude [m]",
                 .logy = true};
      for (std::size_t k = 0; k < r.frequency_response.size(); ++k) {
        const auto& cv = r.frequency_response[k];
        Series s{.title = force_label(c, r.frequency_response_table[k], cv.force_scale),
                 .style = "lines"};
        for (Eigen::Index i = 0; i < cv.omega.size(); ++i) {
          const double y = cv.output_amplitude(i, static_cast<Eigen::Index>(o));
          if (!(y > 0.0)) continue;  // a log axis: a DOF at rest has no point to draw
          s.x.push_back(cv.omega(i) / (2.0 * std::numbers::pi));
          s.y.push_back(y);
        }
        p.series.push_back(std::move(s));
      }
      // Unstable stretches (Hill's method) over the curves, broken between stretches
      // (gnuplot leaves out the segments at an undefined point).
      Series unstable{.title = "unstable (Hill)",
                      .style = "linespoints dt 2 pt 2 ps 0.6 lc rgb '#d62728'"};
      const auto gap = [&unstable] {
        if (!unstable.x.empty() && !std::isnan(unstable.x.back())) {
          unstable.x.push_back(std::numeric_limits<double>::quiet_NaN());
          unstable.y.push_back(std::numeric_limits<double>::quiet_NaN());
        }
      };
      for (const auto& cv : r.frequency_response) {
        if (cv.stability.empty()) continue;
        for (Eigen::Index i = 0; i < cv.omega.size(); ++i) {
          const double y = cv.output_amplitude(i, static_cast<Eigen::Index>(o));
          if (cv.stability[static_cast<std::size_t>(i)].stable || !(y > 0.0)) {
            gap();
            continue;
          }
          unstable.x.push_back(cv.omega(i) / (2.0 * std::numbers::pi));
          unstable.y.push_back(y);
        }
        gap();
      }
      if (!unstable.x.empty()) p.series.push_back(std::move(unstable));
      // The refined peaks of this output and the folds of every curve, as markers.
      Series peaks{.title = "peaks (refined)", .style = "points pt 7 ps 1.2"};
      Series folds{.title = "folds (turning points)", .style = "points pt 6 ps 1.2"};
      for (const auto& cv : r.frequency_response) {
        for (const auto& pk : cv.peaks) {
          if (pk.output != o || !(pk.amplitude > 0.0)) continue;
          peaks.x.push_back(pk.omega / (2.0 * std::numbers::pi));
          peaks.y.push_back(pk.amplitude);
        }
        for (const auto& f : cv.folds) {
          const double y = f.output_amplitude(static_cast<Eigen::Index>(o));
          if (!(y > 0.0)) continue;
          folds.x.push_back(f.omega / (2.0 * std::numbers::pi));
          folds.y.push_back(y);
        }
      }
      if (!peaks.x.empty()) p.series.push_back(std::move(peaks));
      if (!folds.x.empty()) p.series.push_back(std::move(folds));
      // The backbone (the nonlinear mode's first-harmonic amplitude of this output against
      // its frequency) over the curves, within their frequency and amplitude range (up to
      // twice their largest amplitude: the mode goes on to amplitudes no curve reaches).
      if (r.nonlinear_mode &&
          r.nonlinear_mode->output_amplitude.cols() > static_cast<Eigen::Index>(o)) {
        double f_lo = std::numeric_limits<double>::infinity(), f_hi = 0.0, a_hi = 0.0;
        for (const auto& cv : r.frequency_response) {
          for (Eigen::Index i = 0; i < cv.omega.size(); ++i) {
            f_lo = std::min(f_lo, cv.omega(i) / (2.0 * std::numbers::pi));
            f_hi = std::max(f_hi, cv.omega(i) / (2.0 * std::numbers::pi));
            a_hi = std::max(a_hi, cv.output_amplitude(i, static_cast<Eigen::Index>(o)));
          }
        }
        const auto& m = *r.nonlinear_mode;
        Series bb{.title = "backbone (nonlinear mode)", .style = "lines dt 2 lc rgb '#000000'"};
        for (Eigen::Index i = 0; i < m.frequency_hz.size(); ++i) {
          const double y = m.output_amplitude(i, static_cast<Eigen::Index>(o));
          const double f = m.frequency_hz(i);
          if (!(y > 0.0) || f < f_lo || f > f_hi || y > 2.0 * a_hi) continue;
          bb.x.push_back(f);
          bb.y.push_back(y);
        }
        if (bb.x.size() > 1) p.series.push_back(std::move(bb));
      }
      const std::string name = c.output_dofs.size() == 1
                                   ? std::string("frequency_response.png")
                                   : fmt::format("frequency_response_dof{}.png", c.output_dofs[o]);
      plot_png(dir.file(name), p);
      written.push_back(name);
    }
  }
  const double two_pi = 2.0 * std::numbers::pi;
  const auto output_name = [&](const char* stem, std::size_t o) {
    return c.output_dofs.size() == 1 ? fmt::format("{}.png", stem)
                                     : fmt::format("{}_dof{}.png", stem, c.output_dofs[o]);
  };
  // The backbone ROM's curves over the full harmonic-balance ones (when the case has them).
  if (!r.backbone_rom.empty()) {
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      const auto oi = static_cast<Eigen::Index>(o);
      PlotSpec p{.title = fmt::format("Backbone ROM (circles) and harmonic balance of DOF {}",
                                      c.output_dofs[o]),
                 .xlabel = "excitation frequency [Hz]",
                 .ylabel = "first-harmonic amplitude [m]",
                 .logy = true};
      for (std::size_t k = 0; k < r.frequency_response.size(); ++k) {
        const auto& cv = r.frequency_response[k];
        p.series.push_back(
            positive_series("HB, " + force_label(c, r.frequency_response_table[k], cv.force_scale),
                            cv.omega / two_pi, cv.output_amplitude.col(oi), true, "lines"));
      }
      for (std::size_t k = 0; k < r.backbone_rom.size(); ++k) {
        const auto& m = r.backbone_rom[k];
        Series rom = positive_series(
            "ROM, " + force_legend(c.backbone_roms[r.backbone_rom_table[k]],
                                   r.backbone_rom_force_scale[k]),
            m.omega / two_pi, m.output_amplitude.col(oi), true, "points pt 6 ps 0.8");
        // About 60 open circles per curve, so the harmonic-balance line shows through them.
        const std::size_t stride = std::max<std::size_t>(1, rom.x.size() / 60);
        Series thin{.title = rom.title, .style = rom.style};
        for (std::size_t i = 0; i < rom.x.size(); i += stride) {
          thin.x.push_back(rom.x[i]);
          thin.y.push_back(rom.y[i]);
        }
        p.series.push_back(std::move(thin));
      }
      if (r.nonlinear_mode) {
        const auto& m = *r.nonlinear_mode;
        // The backbone within the plotted amplitudes: beyond them it would set the scale.
        double top = 0.0;
        for (const auto& cv : r.backbone_rom)
          if (cv.output_amplitude.rows() > 0)
            top = std::max(top, cv.output_amplitude.col(oi).maxCoeff());
        Series b{.title = "backbone (nonlinear mode)", .style = "lines dt 2 lc rgb 'black'"};
        for (Eigen::Index i = 0; i < m.omega.size(); ++i) {
          const double y = m.output_amplitude(i, oi);
          if (y > 0.0 && y <= 1.5 * top) {
            b.x.push_back(m.frequency_hz(i));
            b.y.push_back(y);
          }
        }
        if (!b.x.empty()) p.series.push_back(std::move(b));
      }
      plot_png(dir.file(output_name("backbone_rom", o)), p);
      written.push_back(output_name("backbone_rom", o));
    }
  }
  // Force responses: amplitude against the force scale, with their folds.
  if (!r.force_response.empty()) {
    for (std::size_t o = 0; o < c.output_dofs.size(); ++o) {
      const auto oi = static_cast<Eigen::Index>(o);
      PlotSpec p{
          .title = fmt::format("Force response of DOF {} at a fixed frequency", c.output_dofs[o]),
          .xlabel = "force scale lambda",
          .ylabel = "first-harmonic amplitude [m]"};
      Series folds{.title = "folds (turning points)", .style = "points pt 6 ps 1.2"};
      for (std::size_t k = 0; k < r.force_response.size(); ++k) {
        const auto& cv = r.force_response[k];
        Series s{.title = fmt::format("table {}, {:.6g} Hz", r.force_response_table[k] + 1,
                                      cv.omega / two_pi),
                 .style = "lines"};
        for (Eigen::Index i = 0; i < cv.force_scale.size(); ++i) {
          s.x.push_back(cv.force_scale(i));
          s.y.push_back(cv.output_amplitude(i, oi));
        }
        p.series.push_back(std::move(s));
        for (const auto& f : cv.folds) {
          folds.x.push_back(f.force_scale);
          folds.y.push_back(f.output_amplitude(oi));
        }
      }
      if (!folds.x.empty()) p.series.push_back(std::move(folds));
      plot_png(dir.file(output_name("force_response", o)), p);
      written.push_back(output_name("force_response", o));
    }
  }
  // Amplitude control: the force scale that holds the amplitude, against frequency.
  if (!r.amplitude_control.empty()) {
    PlotSpec p{.title = "Amplitude control: force scale holding the controlled amplitude",
               .xlabel = "excitation frequency [Hz]",
               .ylabel = "force scale lambda",
               .logy = true};
    for (std::size_t k = 0; k < r.amplitude_control.size(); ++k) {
      const auto& a = r.amplitude_control[k];
      const auto& opt = c.amplitude_controls[r.amplitude_control_table[k]];
      p.series.push_back(
          positive_series(fmt::format("table {}: DOF {} at {:.4g} m",
                                      r.amplitude_control_table[k] + 1, opt.dof, opt.amplitude),
                          a.omega / two_pi, a.force_scale, true, "linespoints pt 7 ps 0.5"));
    }
    plot_png(dir.file("amplitude_control.png"), p);
    written.push_back("amplitude_control.png");
  }
  // Phase resonance: the resonance frequency (the backbone) against the amplitude.
  if (!r.phase_resonance.empty()) {
    PlotSpec p{.title = "Phase resonance: frequency against the controlled amplitude",
               .xlabel = "first-harmonic amplitude of the controlled DOF [m]",
               .ylabel = "frequency [Hz]",
               .logx = true};
    for (std::size_t k = 0; k < r.phase_resonance.size(); ++k) {
      const auto& ph = r.phase_resonance[k];
      p.series.push_back(positive_series(
          fmt::format("phase resonance, table {} (DOF {})", r.phase_resonance_table[k] + 1,
                      c.phase_resonances[r.phase_resonance_table[k]].dof),
          ph.amplitude, ph.omega / two_pi, false, "linespoints pt 7 ps 0.5"));
    }
    plot_png(dir.file("phase_resonance.png"), p);
    written.push_back("phase_resonance.png");
  }
  if (!r.superharmonic_resonance.empty()) {
    // The excitation frequency times r: where the superharmonic meets the mode it excites.
    PlotSpec p{.title = "Superharmonic resonance (VPRNM): r times the excitation frequency",
               .xlabel = "force scale lambda (F_ex = lambda force)",
               .ylabel = "r x excitation frequency [Hz]",
               .logx = true};
    for (std::size_t k = 0; k < r.superharmonic_resonance.size(); ++k) {
      const auto& sr = r.superharmonic_resonance[k];
      p.series.push_back(positive_series(
          fmt::format("{}:1, table {}", sr.harmonic, r.superharmonic_resonance_table[k] + 1),
          sr.force_scale, sr.harmonic * sr.omega / two_pi, false, "linespoints pt 7 ps 0.5"));
    }
    plot_png(dir.file("superharmonic_resonance.png"), p);
    written.push_back("superharmonic_resonance.png");
  }
  return written;
}

std::string text_summary(const VibrationCase& c, const VibrationResult& r) {
  std::string out;
  // Element types in order of first appearance, with their counts when repeated
  // ("rough_contact x 200" for a finite-element interface).
  std::vector<std::pair<std::string, std::size_t>> counted;
  for (const auto& e : c.elements) {
    const std::string t = e.element->type();
    const auto it =
        std::find_if(counted.begin(), counted.end(), [&](const auto& tc) { return tc.first == t; });
    if (it == counted.end()) {
      counted.emplace_back(t, 1);
    } else {
      ++it->second;
    }
  }
  std::string types;
  for (const auto& [t, count] : counted) {
    if (!types.empty()) types += ", ";
    types += count > 1 ? fmt::format("{} x {}", t, count) : t;
  }
  std::string hs;
  for (int h : c.harmonic_balance.harmonics) {
    if (!hs.empty()) hs += ',';
    hs += std::to_string(h);
  }
  out += fmt::format("{}: {} DOF(s), {} element(s){}, harmonics {}, {} time points\n", c.source,
                     c.structure.dofs(), c.elements.size(), types.empty() ? "" : " (" + types + ")",
                     hs, c.harmonic_balance.time_points);
  if (r.nonlinear_mode) {
    const auto& m = *r.nonlinear_mode;
    const auto np = m.amplitude.size();
    if (np > 0) {
      out += fmt::format(
          "nonlinear mode {}: {} points, a = {:.4g} .. {:.4g}: frequency {:.6g} .. {:.6g} Hz "
          "(linear {:.6g} Hz), damping ratio {:.4g} .. {:.4g} (max {:.4g})\n",
          c.nonlinear_mode->mode, np, m.amplitude(0), m.amplitude(np - 1), m.frequency_hz(0),
          m.frequency_hz(np - 1), m.linear_omega / (2.0 * std::numbers::pi), m.damping_ratio(0),
          m.damping_ratio(np - 1), m.damping_ratio.maxCoeff());
    }
  }
  for (std::size_t k = 0; k < r.frequency_response.size(); ++k) {
    const auto& cv = r.frequency_response[k];
    if (cv.omega.size() == 0 || c.output_dofs.empty()) continue;
    Eigen::Index i = 0;
    double peak = cv.output_amplitude.col(0).maxCoeff(&i);
    double peak_omega = cv.omega(i);
    for (const auto& pk : cv.peaks) {  // the refined peaks lie between the points
      if (pk.output == 0 && pk.amplitude >= peak) {
        peak = pk.amplitude;
        peak_omega = pk.omega;
      }
    }
    out += fmt::format(
        "frequency response {} ({}, force scale {:.4g}): {} points, peak amplitude of DOF {} "
        "{:.6g} m at {:.6g} Hz, {} fold(s)\n",
        k + 1, force_label(c, r.frequency_response_table[k], cv.force_scale), cv.force_scale,
        cv.omega.size(), c.output_dofs[0], peak, peak_omega / (2.0 * std::numbers::pi),
        cv.folds.size());
    if (!cv.stability.empty()) {
      const auto unstable = std::count_if(cv.stability.begin(), cv.stability.end(),
                                          [](const PeriodicStability& p) { return !p.stable; });
      out.insert(out.size() - 1, fmt::format(", {} unstable point(s) (Hill)", unstable));
    }
  }
  for (std::size_t k = 0; k < r.backbone_rom.size(); ++k) {
    const auto& m = r.backbone_rom[k];
    if (m.omega.size() == 0 || c.output_dofs.empty()) continue;
    Eigen::Index i = 0;
    const double peak = m.output_amplitude.col(0).maxCoeff(&i);
    out += fmt::format(
        "backbone ROM {} (force scale {:.4g}): {} points, peak amplitude of DOF {} {:.6g} m at "
        "{:.6g} Hz\n",
        k + 1, r.backbone_rom_force_scale[k], m.omega.size(), c.output_dofs[0], peak,
        m.omega(i) / (2.0 * std::numbers::pi));
  }
  if (r.quasi_static_mode) {
    const auto& q = *r.quasi_static_mode;
    const auto np = q.amplitude.size();
    out += fmt::format(
        "quasi-static mode {}: {} points, frequency {:.6g} .. {:.6g} Hz, damping ratio {:.4g} .. "
        "{:.4g}\n",
        c.quasi_static_mode->mode, np, q.frequency_hz(0), q.frequency_hz(np - 1),
        q.damping_ratio(0), q.damping_ratio(np - 1));
  }
  const SummaryValue s(r.summary);
  const auto* sv = s.find("solver");
  auto geti = [&](const char* k) { return std::get<std::int64_t>(sv->find(k)->data); };
  out += fmt::format(
      "solver: {} points, {} Newton iterations, {} residual and {} Jacobian evaluations, {} "
      "rejected steps, {} turning points, {:.3g} s\n",
      geti("points"), geti("newton_iterations"), geti("residual_evaluations"),
      geti("jacobian_evaluations"), geti("rejected_steps"), geti("turning_points"),
      std::get<double>(sv->find("wall_time_s")->data));
  return out;
}

void run_vibration(const VibrationOptions& o, std::string& out) {
  const bool files = o.out_dir.has_value();
  if (files) {
    require_case_output_directory(*o.out_dir, o.case_file);
  }
  VibrationCase c = read_case_file(o.case_file);
  if (o.stability) {
    for (auto& fr : c.frequency_responses) fr.options.stability = true;
  }
  const bool bar = isatty(STDERR_FILENO) != 0;
  bool bar_drawn = false;
  const CaseProgress progress = [&](const std::string& analysis, double x) {
    if (!bar) return;
    const std::size_t width = 30;
    const auto done = static_cast<std::size_t>(std::clamp(x, 0.0, 1.0) * width);
    std::cerr << fmt::format("\r[{}{}] {:3.0f}% {:<20}", std::string(done, '#'),
                             std::string(width - done, ' '), 100.0 * x, analysis)
              << std::flush;
    bar_drawn = true;
  };
  VibrationResult r;
  try {
    r = run_case(c, progress);
  } catch (...) {
    if (bar_drawn) std::cerr << "\n";
    throw;
  }
  if (bar_drawn) std::cerr << "\n";

  std::vector<std::string> written;
  if (files) {
    joint::StagedDirectory dir(*o.out_dir, "asperity vibration");
    written = write_files(c, r, dir, !o.no_plots);
    dir.commit();
  }
  for (const auto& w : r.warnings) fmt::print(stderr, "warning: {}\n", w);
  out = o.json ? json_output(to_json(SummaryValue(r.summary))) : text_summary(c, r);
  if (!o.json) {
    if (files) {
      std::string list;
      for (const auto& f : written) {
        if (!list.empty()) list += ", ";
        list += f;
      }
      out += fmt::format("wrote {}/ ({})\n", *o.out_dir, list);
    } else {
      out += "no files written (--out DIR writes summary.json, the curves as CSV and plots)\n";
    }
  }
  if (!r.complete) {
    // The points computed are written whole (complete = false in summary.json); the
    // run itself failed to cover its range: numerical failure, exit 3.
    std::fputs(out.c_str(), stdout);
    std::fflush(stdout);
    out.clear();
    // Curves that could not start are named too when another stop came first.
    std::string not_started;
    if (!r.failures.empty() && r.stop_reason.find("could not start") == std::string::npos) {
      not_started = fmt::format("; {} curve(s) could not start, first {}", r.failures.size(),
                                r.failures.front());
    }
    throw NumericalError(fmt::format(
        "{}{}; the {} points computed are kept{} (solver.complete = false): {}", r.stop_reason,
        not_started,
        std::get<std::int64_t>(SummaryValue(r.summary).find("solver")->find("points")->data),
        files ? fmt::format(" in {}", *o.out_dir) : std::string(), r.remedy));
  }
}

}  // namespace

void add_vibration_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<VibrationOptions>();
  auto* cmd = app.add_subcommand(
      "vibration",
      "Vibration of a structure with joint elements by harmonic balance: amplitude-dependent "
      "natural frequency and damping (nonlinear modes, EPMC), forced response curves and the "
      "quasi-static modal estimate. Writes summary.json, one CSV per curve and PNG plots "
      "(format: docs/vibration.md, examples/vibration).");
  cmd->add_option("case", o->case_file,
                  "TOML case file with [structure], [[element]], [harmonic_balance] and the "
                  "analyses ([nonlinear_mode], [[frequency_response]], [quasi_static_mode])")
      ->required();
  cmd->add_option("--out", o->out_dir,
                  "output directory, written whole (created; an existing one is replaced only "
                  "if asperity wrote it); without it only the summary is printed");
  cmd->add_flag("--json", o->json, "print summary.json instead of the text summary");
  cmd->add_flag("--no-plots", o->no_plots, "skip the PNG plots (no gnuplot needed)");
  cmd->add_flag("--stability", o->stability,
                "Hill's stability of every forced-response point (as stability = true in each "
                "[[frequency_response]] table)");
  cmd->callback([o, &action] {
    action = [o] { return run_guarded([o](std::string& out) { run_vibration(*o, out); }); };
  });
}

}  // namespace asperity::cli
