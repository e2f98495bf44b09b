#include "common.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <sstream>
#include <stdexcept>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/process.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/core/version.hpp"
#include "asperity/joint/output_dir.hpp"

namespace asperity::cli {

std::string lowercase(std::string s) {
  for (char& c : s) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return s;
}

std::optional<double> quantity(const std::optional<std::string>& text, core::Dimension d,
                               const std::string& flag) {
  if (!text) return std::nullopt;
  return core::parse_quantity(*text, d, flag);
}

std::size_t whole_number(const std::string& text, const std::string& flag, std::size_t lo,
                         std::size_t hi) {
  std::uint64_t v = 0;
  const char* end = text.data() + text.size();
  const auto [p, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || p != end || v < lo || v > hi) {
    throw InvalidInput(fmt::format("{} = {} is not allowed: it must be a whole number in [{}, {}]",
                                   flag, text, lo, hi));
  }
  return static_cast<std::size_t>(v);
}

CLI::Validator whole_number_in(std::size_t lo, std::size_t hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        try {
          (void)whole_number(text, "", lo, hi);
        } catch (const InvalidInput&) {
          return fmt::format("{} is not allowed: it must be a whole number in [{}, {}]", text, lo,
                             hi);
        }
        return {};
      },
      "", "");
}

double required_quantity(const std::optional<std::string>& text, core::Dimension d,
                         const std::string& flag) {
  if (!text) throw InvalidInput(fmt::format("{} is required", flag));
  return core::parse_quantity(*text, d, flag);
}

void MaterialOptions::add_to(CLI::App* cmd, const std::string& body1, const std::string& body2) {
  cmd->add_option("--E1", E1, "Young's modulus of " + body1)->required();
  cmd->add_option("--nu1", nu1, "Poisson's ratio of " + body1 + ", in [0, 0.5)")->required();
  cmd->add_option("--G1", G1, "shear modulus of " + body1 + " (default: E1/(2(1+nu1)))");
  cmd->add_option("--H1", H1,
                  "hardness of " + body1 +
                      "; with --H2 the smaller is the softer material's, alone it marks body 1 "
                      "as the softer material");
  cmd->add_option("--E2", E2, "Young's modulus of " + body2)->required();
  cmd->add_option("--nu2", nu2, "Poisson's ratio of " + body2 + ", in [0, 0.5)")->required();
  cmd->add_option("--G2", G2, "shear modulus of " + body2 + " (default: E2/(2(1+nu2)))");
  cmd->add_option("--H2", H2,
                  "hardness of " + body2 +
                      "; with --H1 the smaller is the softer material's, alone it marks body 2 "
                      "as the softer material");
  cmd->add_option("--H", H, "hardness of the softer material (when nu1 = nu2)");
}

std::pair<contact::Material, contact::Material> MaterialOptions::parse() const {
  auto m = parse_described();
  return {m.body1, m.body2};
}

ParsedMaterials MaterialOptions::parse_described() const {
  namespace dim = core::dim;
  contact::Material b1{.E = required_quantity(E1, dim::pressure, "--E1"),
                       .nu = required_quantity(nu1, dim::dimensionless, "--nu1"),
                       .G = quantity(G1, dim::pressure, "--G1").value_or(0.0),
                       .H = quantity(H1, dim::pressure, "--H1").value_or(0.0)};
  contact::Material b2{.E = required_quantity(E2, dim::pressure, "--E2"),
                       .nu = required_quantity(nu2, dim::dimensionless, "--nu2"),
                       .G = quantity(G2, dim::pressure, "--G2").value_or(0.0),
                       .H = quantity(H2, dim::pressure, "--H2").value_or(0.0)};
  // Check each value under its flag's name (Material::validate would say "body1.E").
  core::require_positive("--E1", b1.E);
  core::require_positive("--E2", b2.E);
  core::require_in_half_open("--nu1", b1.nu, 0.0, 0.5);
  core::require_in_half_open("--nu2", b2.nu, 0.0, 0.5);
  if (G1) core::require_positive("--G1", b1.G);
  if (G2) core::require_positive("--G2", b2.G);
  if (G1) contact::require_shear_modulus_range("--G1", b1.G, "--E1", b1.E);
  if (G2) contact::require_shear_modulus_range("--G2", b2.G, "--E2", b2.E);
  if (H1) core::require_positive("--H1", b1.H);
  if (H2) core::require_positive("--H2", b2.H);
  ParsedMaterials out;
  if (H) {
    if (H1 || H2) throw InvalidInput("give either --H (softer material) or --H1/--H2, not both");
    if (b1.nu != b2.nu) {
      throw InvalidInput(
          "--H does not say which body is softer and --nu1 differs from --nu2: give --H1 and "
          "--H2 instead (or only the softer body's)");
    }
    b1.H = b2.H = required_quantity(H, dim::pressure, "--H");
    core::require_positive("--H", b1.H);
    out.softer_body = 0;
    out.softer_rule =
        "--H is the softer material's hardness; nu1 = nu2, so which body is "
        "softer does not matter";
  } else if (H1 && H2) {
    if (b1.H == b2.H && b1.nu != b2.nu) {
      throw InvalidInput(fmt::format(
          "--H1 = --H2 = {} Pa but --nu1 = {} differs from --nu2 = {}: neither body is the "
          "softer one, so the Poisson's ratio of the softer material is undefined; give "
          "only the hardness of the body whose nu is to be used",
          core::format_value(b1.H), core::format_value(b1.nu), core::format_value(b2.nu)));
    }
    out.softer_body = b1.H < b2.H ? 1 : (b2.H < b1.H ? 2 : 0);
    out.softer_rule = out.softer_body == 0
                          ? "--H1 = --H2 and nu1 = nu2: the bodies are alike"
                          : fmt::format("the smaller hardness (--H{})", out.softer_body);
  } else if (H1 || H2) {
    out.softer_body = H1 ? 1 : 2;
    out.softer_rule = fmt::format(
        "only --H{0} is given: body {0} is taken as the softer material (give --H1 and --H2 to "
        "compare)",
        out.softer_body);
  } else {
    throw InvalidInput("the hardness is required: give --H (or --H1/--H2)");
  }
  out.body1 = b1;
  out.body2 = b2;
  return out;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  core::write_output_file(path, content);
}

std::string csv_text(const std::vector<std::string>& header,
                     const std::vector<std::vector<double>>& columns) {
  std::string out;
  for (std::size_t i = 0; i < header.size(); ++i) out += (i ? "," : "") + header[i];
  out += "\n";
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      out += fmt::format("{}{:.12g}", c ? "," : "", columns[c][r]);
    out += "\n";
  }
  return out;
}

void write_output(const std::string& path, const std::string& content, std::string& stdout_text) {
  if (is_standard_output(path)) {
    stdout_text += content;
  } else {
    write_file_atomically(path, content);
  }
}

void write_output(core::OutputSet& outputs, const std::string& path, const std::string& content,
                  std::string& stdout_text) {
  if (is_standard_output(path)) {
    stdout_text += content;
  } else {
    outputs.add(path, content);
  }
}

void report_written(const std::vector<std::string>& files, bool stdout_is_data, std::string& out) {
  std::string list;
  for (const auto& f : files) {
    if (!is_standard_output(f)) list += (list.empty() ? "" : ", ") + f;
  }
  if (list.empty()) return;
  if (stdout_is_data) {
    std::cerr << "asperity: wrote " << list << "\n";
  } else {
    out += "wrote " + list + "\n";
  }
}

void report_written_directory(const std::string& dir, const std::vector<std::string>& files,
                              bool stdout_is_data, std::string& out) {
  std::string list;
  for (const auto& f : files) list += (list.empty() ? "" : ", ") + f;
  std::string d = dir;
  if (!d.ends_with('/')) d += '/';
  const std::string line = fmt::format("wrote {} ({})\n", d, list);
  if (stdout_is_data) {
    std::cerr << line;
  } else {
    out += line;
  }
}

OutKind out_kind(const std::optional<std::string>& out, const std::string& extension) {
  if (!out) return OutKind::none;
  if (is_standard_output(*out)) return OutKind::standard_output;
  const std::string name = std::filesystem::path(*out).filename().string();
  if (name.size() > extension.size() && lowercase(name).ends_with(extension)) return OutKind::file;
  return OutKind::directory;
}

void require_one_stdout(
    bool json, const std::vector<std::pair<std::string, std::optional<std::string>>>& outputs) {
  std::string first;
  for (const auto& [flag, path] : outputs) {
    if (!is_standard_output(path)) continue;
    if (json) {
      throw InvalidInput(fmt::format(
          "--json and {} - both print on standard output: write {} to a file, or leave out --json",
          flag, flag));
    }
    if (!first.empty()) {
      throw InvalidInput(fmt::format(
          "{} - and {} - both print on standard output: give one of them a file", first, flag));
    }
    first = flag;
  }
}

void require_case_output_directory(const std::string& out_dir, const std::string& case_file) {
  const auto name = std::filesystem::path(out_dir).lexically_normal().filename().string();
  if (out_dir.empty() || name == "." || name == ".." || name.empty()) {
    throw InvalidInput(fmt::format(
        "--out \"{}\": name a directory to create (or replace whole), not . or ..", out_dir));
  }
  joint::require_output_apart_from_inputs(out_dir, {{"the case file", case_file}});
  joint::require_replaceable_output(out_dir, out_dir);
}

void require_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outputs) {
  namespace fs = std::filesystem;
  std::vector<std::pair<std::string, fs::path>> seen;
  for (const auto& [flag, path] : outputs) {
    if (path.empty() || is_standard_output(path)) continue;  // "-": require_one_stdout
    std::error_code ec;
    // weakly_canonical resolves "." and ".." and symbolic links of the parts that exist.
    fs::path norm = fs::weakly_canonical(fs::absolute(path), ec);
    if (ec) norm = fs::absolute(path).lexically_normal();
    for (const auto& [other_flag, other] : seen) {
      if (other == norm) {
        throw InvalidInput(fmt::format("{} and {} both name \"{}\": give each output its own file",
                                       other_flag, flag, path));
      }
    }
    seen.emplace_back(flag, norm);
  }
}

std::string gnuplot_string(const std::string& s) {
  // gnuplot expands `command` (a shell command) and escapes inside double-quoted
  // strings, but nothing inside single-quoted ones, where '' is a single quote. A line
  // break would end the command, so control characters become spaces.
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out += "''";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == '\x7f') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out + "'";
}

std::string version_text() {
  const auto v = core::version_info();
  return fmt::format("{} (git {}, {})", v.version, v.git_revision, v.build_type);
}

std::string json_output(const Json& j) {
  Json out = Json::object();
  out["asperity_version"] = version_text();
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) out[key] = value;
  } else {
    out["result"] = j;
  }
  return out.dump(2) + "\n";
}

namespace {

/// A private directory under the system's temporary directory, removed with its
/// contents on destruction.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    // removed on SIGINT/SIGTERM
    path_ = core::create_registered_temporary_directory("asperity-plot", "gnuplot", &slot_);
  }
  ~TemporaryDirectory() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
    core::unregister_temporary(slot_);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int slot_ = -1;
};

std::string read_binary(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// A title as gnuplot text in lines of at most `width` characters (broken at spaces, a
// longer word at `width`): a long joint name would run past the canvas, which is 900 px
// wide, about 90 characters of an 11 pt font, less the key beside the plot.
std::string wrapped_title(const std::string& title, std::size_t width) {
  std::vector<std::string> lines{""};
  std::istringstream words(title);
  std::string w;
  while (words >> w) {
    while (w.size() > width) {
      if (!lines.back().empty()) lines.emplace_back();
      lines.back() = w.substr(0, width);
      w.erase(0, width);
      lines.emplace_back();
    }
    if (w.empty()) continue;
    if (!lines.back().empty() && lines.back().size() + 1 + w.size() > width) lines.emplace_back();
    lines.back() += (lines.back().empty() ? "" : " ") + w;
  }
  if (lines.back().empty() && lines.size() > 1) lines.pop_back();
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i)
    out += (i ? ".\"\\n\"." : "") + gnuplot_string(lines[i]);
  return out;
}

}  // namespace

void plot_png(const std::string& path, const PlotSpec& spec, core::OutputSet* outputs) {
  const std::filesystem::path target(path);
  if (target.filename().empty())
    throw InvalidInput(fmt::format("output path \"{}\" names no file", path));
  // gnuplot writes into a private directory under fixed names; the user's path never
  // enters the gnuplot script. The PNG is then moved into place atomically.
  const TemporaryDirectory dir;
  const auto png = dir.path() / "plot.png";
  const auto script_path = dir.path() / "plot.gp";
  std::ostringstream gp;
  gp << "set encoding utf8\nset terminal pngcairo size 900,650 enhanced font 'DejaVu Sans,11'\n";
  gp << "set output " << gnuplot_string(png.string()) << "\n";
  gp << "set title " << wrapped_title(spec.title, 80) << " noenhanced\n";
  gp << "set xlabel " << gnuplot_string(spec.xlabel) << " noenhanced\n";
  gp << "set ylabel " << gnuplot_string(spec.ylabel) << " noenhanced\n";
  gp << "set grid\nset key outside right top noenhanced\n";
  // A margin inside the frame, so that loop tips and end points are not drawn on it
  // (`extra` may set its own).
  if (!spec.logx && !spec.logy)
    gp << "set offsets graph 0.02, graph 0.02, graph 0.05, graph 0.05\n";
  if (spec.logx) gp << "set logscale x\nset format x '10^{%T}'\n";
  if (spec.logy) gp << "set logscale y\nset format y '10^{%T}'\n";
  gp << spec.extra << "\n";
  gp << "plot ";
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    gp << (i ? ", " : "") << "'-' using 1:2 with " << spec.series[i].style << " lw 2 title "
       << gnuplot_string(spec.series[i].title);
  }
  gp << "\n";
  for (const auto& s : spec.series) {
    for (std::size_t j = 0; j < s.x.size(); ++j)
      gp << fmt::format("{:.10g} {:.10g}\n", s.x[j], s.y[j]);
    gp << "e\n";
  }
  {
    std::ofstream script(script_path);
    script << gp.str();
    script.close();
    if (script.fail()) {
      throw Error(fmt::format("cannot write the gnuplot script {}", script_path.string()));
    }
  }
  // gnuplot reads the script file, not stdin; run without a shell (no quoting needed).
  const auto run = core::run_program({"gnuplot", script_path.string()});
  if (run.spawn_error != 0 && run.spawn_error != ENOENT)
    throw Error(fmt::format("cannot run gnuplot: {}", std::strerror(run.spawn_error)));
  if (run.spawn_error == ENOENT) {
    // The user's environment, like an unwritable directory: exit 2 (README).
    throw InvalidInput(
        fmt::format("cannot draw \"{}\": gnuplot is not installed (no gnuplot on PATH); install it "
                    "(scripts/setup.sh installs gnuplot-nox), or leave out the plots (--no-plots; "
                    "--plot where a command has it)",
                    path));
  }
  std::error_code ec;
  if (!run.exited_zero || !std::filesystem::exists(png) ||
      std::filesystem::file_size(png, ec) == 0) {
    if (run.output.find("pngcairo") != std::string::npos) {
      throw InvalidInput(fmt::format(
          "cannot draw \"{}\": this gnuplot has no pngcairo terminal; install gnuplot-nox "
          "(scripts/setup.sh) or leave out the plot ({})",
          path, run.output));
    }
    throw Error(fmt::format("plotting \"{}\" failed: gnuplot said: {}", path, run.output));
  }
  if (outputs) {
    outputs->add(path, read_binary(png));
  } else {
    core::write_output_file(path, read_binary(png));
  }
}

int run_guarded(const std::function<void(std::string& out)>& body) {
  std::string out;
  try {
    body(out);
  } catch (const InvalidInput& e) {
    std::cerr << "asperity: error: " << e.what() << "\n";
    return 2;
  } catch (const NumericalError& e) {
    std::cerr << "asperity: numerical failure: " << e.what() << "\n";
    return 3;
  } catch (const Error& e) {
    std::cerr << "asperity: error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    // Memory exhausted: the input asked for more than this machine holds, which the user
    // fixes like bad input (a smaller problem): exit 2 (README).
    std::cerr << "asperity: error: out of memory: the input asks for more memory than is "
                 "available; make the problem smaller (fewer samples, points or load cases)\n";
    return 2;
  } catch (const std::length_error& e) {
    // A container asked for more elements than it can hold: the same cause as bad_alloc.
    std::cerr << "asperity: error: the input asks for a container larger than this machine "
                 "allows ("
              << e.what() << "); make the problem smaller\n";
    return 2;
  } catch (const std::exception& e) {
    // Anything else (a defect of asperity, not of the input): a message, never an abort.
    std::cerr << "asperity: error: unexpected failure: " << e.what() << "\n";
    return 1;
  }
  std::cout << out << std::flush;
  return 0;
}

Json to_json(const dynamics::SummaryValue& v) {
  return std::visit(
      [](const auto& x) -> Json {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::nullptr_t>) {
          return Json(nullptr);
        } else if constexpr (std::is_same_v<T, dynamics::SummaryArray>) {
          Json a = Json::array();
          for (const auto& e : x) a.push_back(to_json(e));
          return a;
        } else if constexpr (std::is_same_v<T, dynamics::SummaryObject>) {
          Json o = Json::object();
          for (const auto& [k, e] : x) o[k] = to_json(e);
          return o;
        } else {
          return Json(x);
        }
      },
      v.data);
}

}  // namespace asperity::cli
