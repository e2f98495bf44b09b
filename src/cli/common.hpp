#pragma once
// Helpers shared by the subcommands: quantity options, atomic output files, gnuplot.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "asperity/contact/material.hpp"
#include "asperity/core/units.hpp"

namespace asperity::cli {

using Json = nlohmann::ordered_json;

/// The flags of two materials (--E1 --nu1 --G1 --H1, --E2 ..., or --H for the softer
/// one when nu1 = nu2), shared by the subcommands.
struct MaterialOptions {
  std::optional<std::string> E1, nu1, G1, H1, E2, nu2, G2, H2, H;
  void add_to(CLI::App* cmd, const std::string& body1, const std::string& body2);
  /// Parses and checks each value under its flag's name.
  [[nodiscard]] std::pair<contact::Material, contact::Material> parse() const;
};

/// Parses an optional option's text as a quantity of the given dimension; the error
/// names the flag.
std::optional<double> quantity(const std::optional<std::string>& text, core::Dimension d,
                               const std::string& flag);
/// Parses a required option's text as a quantity of the given dimension.
double required_quantity(const std::optional<std::string>& text, core::Dimension d,
                         const std::string& flag);

/// Writes `content` to a temporary file next to `path` and renames it over `path`,
/// so the file is written whole or not at all. Throws InvalidInput on failure.
void write_file_atomically(const std::string& path, const std::string& content);

/// One data series for a plot: (x, y) points and a title.
struct Series {
  std::string title;
  std::vector<double> x;
  std::vector<double> y;
  std::string style = "lines";
};

struct PlotSpec {
  std::string title;
  std::string xlabel;
  std::string ylabel;
  bool logx = false;
  bool logy = false;
  std::vector<Series> series;
  std::string extra;  ///< further gnuplot commands before the plot line
};

/// Draws `spec` with gnuplot into a PNG at `path` (written atomically). Throws Error
/// if gnuplot is missing or fails.
void plot_png(const std::string& path, const PlotSpec& spec);

/// Runs a subcommand body, mapping errors to a one-line message on stderr and exit
/// codes (2 bad input, 3 numerical failure). `out` is printed only on success.
int run_guarded(const std::function<void(std::string& out)>& body);

}  // namespace asperity::cli
