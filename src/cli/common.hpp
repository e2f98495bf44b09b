#pragma once
// Helpers shared by the subcommands: quantity options, atomic output files, gnuplot.
#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "asperity/contact/material.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/units.hpp"
#include "asperity/dynamics/case.hpp"

namespace asperity::cli {

using Json = nlohmann::ordered_json;

/// Two parsed materials and which one is the softer (whose H and nu the contact
/// uses, Eq. 3.5), with the rule that decided it in words.
struct ParsedMaterials {
  contact::Material body1;
  contact::Material body2;
  int softer_body = 0;  ///< 1 or 2; 0 when it does not matter (same H and nu)
  std::string softer_rule;
};

/// The flags of two materials (--E1 --nu1 --G1 --H1, --E2 ..., or --H for the softer
/// one when nu1 = nu2), shared by the subcommands.
///
/// Hardness rule: the contact needs the hardness H and Poisson's ratio of the softer
/// material. --H gives that H when nu1 = nu2 (then it does not matter which body is
/// softer). --H1 and --H2 together: the smaller is the softer body's (equal values
/// need nu1 = nu2). Only one of --H1/--H2: that body is taken as the softer one, and
/// the commands say so in their output.
struct MaterialOptions {
  std::optional<std::string> E1, nu1, G1, H1, E2, nu2, G2, H2, H;
  void add_to(CLI::App* cmd, const std::string& body1, const std::string& body2);
  /// Parses and checks each value under its flag's name.
  [[nodiscard]] std::pair<contact::Material, contact::Material> parse() const;
  /// As parse(), and says which body is the softer one and why.
  [[nodiscard]] ParsedMaterials parse_described() const;
};

/// `s` with ASCII letters in lower case (names given on the command line are
/// case-insensitive: --model BKE is --model bke).
std::string lowercase(std::string s);

/// Parses an optional option's text as a quantity of the given dimension; the error
/// names the flag.
std::optional<double> quantity(const std::optional<std::string>& text, core::Dimension d,
                               const std::string& flag);
/// Parses a whole number in [lo, hi] from an option's text, as typed: a value too large
/// for any integer type is named as written (CLI11 would wrap it to 2^64 - 1).
std::size_t whole_number(const std::string& text, const std::string& flag, std::size_t lo,
                         std::size_t hi);
/// A CLI11 check of an option's text before its conversion: a whole number in [lo, hi]
/// (a value past 2^64 is named as typed, not wrapped to 2^64 - 1 by the conversion).
CLI::Validator whole_number_in(std::size_t lo, std::size_t hi);
/// Parses a required option's text as a quantity of the given dimension.
double required_quantity(const std::optional<std::string>& text, core::Dimension d,
                         const std::string& flag);

/// "0.1.0 (git 8dc2057, Release)": the version, source revision and build type of this
/// asperity (`--version` prints "asperity " and this).
std::string version_text();

/// The text of every JSON output, on stdout or in a file: `j` (an object) with
/// "asperity_version" (version_text()) as its first key, indented by 2, newline-terminated.
/// Every command writes its JSON through this function.
std::string json_output(const Json& j);
/// A library summary (dynamics and vibration case runs) as JSON, keys in order.
Json to_json(const dynamics::SummaryValue& v);

/// Writes `content` to `path` whole or not at all (core::write_output_file).
void write_file_atomically(const std::string& path, const std::string& content);

/// "-" as an output file: standard output (for text outputs where that makes sense).
inline bool is_standard_output(const std::string& path) {
  return path == "-";
}
inline bool is_standard_output(const std::optional<std::string>& path) {
  return path && *path == "-";
}

/// A CSV table as text: the header line, then one row per index, 12 significant digits.
std::string csv_text(const std::vector<std::string>& header,
                     const std::vector<std::vector<double>>& columns);

/// Writes `content` to the file `path` (atomically), or, when `path` is "-", appends it
/// to `stdout_text` (printed by run_guarded only on success: whole or not at all).
void write_output(const std::string& path, const std::string& content, std::string& stdout_text);
/// As write_output, into `outputs` (committed with the command's other outputs).
void write_output(core::OutputSet& outputs, const std::string& path, const std::string& content,
                  std::string& stdout_text);

/// The line every command prints after writing files: "wrote a, b, c\n" (empty for no
/// files). `files` excludes "-" (standard output). When stdout carries data (JSON, or a
/// "-" output), the line goes to stderr so that stdout stays machine-readable.
void report_written(const std::vector<std::string>& files, bool stdout_is_data, std::string& out);

/// The line after writing an output directory: "wrote DIR/ (a, b, c)\n", to stdout or,
/// when stdout carries data, to stderr (as report_written).
void report_written_directory(const std::string& dir, const std::vector<std::string>& files,
                              bool stdout_is_data, std::string& out);

/// How an --out of a command that writes a directory is read: "-" is standard output
/// (the command's main document only), a name ending in `extension` (".json", ".md") is
/// that one file, anything else the directory.
enum class OutKind { none, standard_output, file, directory };
OutKind out_kind(const std::optional<std::string>& out, const std::string& extension);

/// Refuses --json together with an output written to standard output ("-"): both would
/// print on stdout. Each pair is (flag, path).
void require_one_stdout(
    bool json, const std::vector<std::pair<std::string, std::optional<std::string>>>& outputs);

/// Throws InvalidInput when two output flags name the same file (after resolving
/// ".", ".." and symbolic links). Each pair is (flag, path); empty paths are skipped.
void require_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outputs);
/// Checks --out DIR of a command reading one case file, before any work: a name (not .
/// or ..), apart from the case file, and absent or a directory asperity wrote.
void require_case_output_directory(const std::string& out_dir, const std::string& case_file);

/// `s` as a gnuplot single-quoted string literal: no command substitution or escape
/// is expanded inside; quotes are doubled, control characters become spaces. Use it
/// for every text that reaches a gnuplot script (plot_png does for PlotSpec's texts).
std::string gnuplot_string(const std::string& s);

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

/// Draws `spec` with gnuplot into a PNG at `path` (written atomically). gnuplot writes
/// into a private temporary directory, so `path` never enters its script; titles and
/// labels are passed as gnuplot_string. `extra` is inserted verbatim: build any text
/// in it with gnuplot_string. Throws InvalidInput (exit 2) when gnuplot or its
/// pngcairo terminal is missing or `path` is not writable, Error if gnuplot fails.
/// With `outputs`, the PNG is added to that set (committed with the command's other
/// outputs) instead of written at once.
void plot_png(const std::string& path, const PlotSpec& spec, core::OutputSet* outputs = nullptr);

/// Runs a subcommand body, mapping errors to a one-line message on stderr and exit
/// codes (2 bad input, including a problem too large for the memory: std::bad_alloc and
/// std::length_error; 3 numerical failure; 1 any other exception). It never lets an
/// exception escape (no abort). `out` is printed only on success.
int run_guarded(const std::function<void(std::string& out)>& body);

}  // namespace asperity::cli
