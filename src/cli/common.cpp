#include "common.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::cli {

std::optional<double> quantity(const std::optional<std::string>& text, core::Dimension d,
                               const std::string& flag) {
  if (!text) return std::nullopt;
  return core::parse_quantity(*text, d, flag);
}

double required_quantity(const std::optional<std::string>& text, core::Dimension d,
                         const std::string& flag) {
  if (!text) throw InvalidInput(fmt::format("{} is required", flag));
  return core::parse_quantity(*text, d, flag);
}

void MaterialOptions::add_to(CLI::App* cmd, const std::string& body1, const std::string& body2) {
  cmd->add_option("--E1", E1, "Young's modulus of " + body1)->required();
  cmd->add_option("--nu1", nu1, "Poisson's ratio of " + body1 + ", in [0, 0.5)")->required();
  cmd->add_option("--G1", G1, "shear modulus of " + body1 + " (default E1/(2(1+nu1)))");
  cmd->add_option("--H1", H1, "hardness of " + body1);
  cmd->add_option("--E2", E2, "Young's modulus of " + body2)->required();
  cmd->add_option("--nu2", nu2, "Poisson's ratio of " + body2 + ", in [0, 0.5)")->required();
  cmd->add_option("--G2", G2, "shear modulus of " + body2 + " (default E2/(2(1+nu2)))");
  cmd->add_option("--H2", H2, "hardness of " + body2);
  cmd->add_option("--H", H, "hardness of the softer material (when nu1 = nu2)");
}

std::pair<contact::Material, contact::Material> MaterialOptions::parse() const {
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
  if (H1) core::require_positive("--H1", b1.H);
  if (H2) core::require_positive("--H2", b2.H);
  if (H) {
    if (H1 || H2) throw InvalidInput("give either --H (softer material) or --H1/--H2, not both");
    if (b1.nu != b2.nu) {
      throw InvalidInput(
          "--H does not say which body is softer and --nu1 differs from --nu2: give --H1 and "
          "--H2 instead");
    }
    b1.H = b2.H = required_quantity(H, dim::pressure, "--H");
    core::require_positive("--H", b1.H);
  }
  if (b1.H == 0.0 && b2.H == 0.0) {
    throw InvalidInput("the hardness is required: give --H (or --H1/--H2)");
  }
  return {b1, b2};
}

namespace {

std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
  std::random_device rd;
  return path.parent_path() /
         fmt::format(".{}.tmp-{:08x}", path.filename().string(), static_cast<unsigned>(rd()));
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& content) {
  core::write_file_atomically(path, content);
}

namespace {

std::string gnuplot_quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

void plot_png(const std::string& path, const PlotSpec& spec) {
  const std::filesystem::path target(path);
  if (target.filename().empty())
    throw InvalidInput(fmt::format("output path \"{}\" names no file", path));
  const auto tmp_png = temporary_sibling(target);
  {
    // An unwritable output path is bad input (exit 2), not a gnuplot failure: probe it
    // by creating the temporary file gnuplot will overwrite.
    std::ofstream probe(tmp_png, std::ios::binary | std::ios::trunc);
    if (!probe) {
      throw InvalidInput(fmt::format(
          "cannot write \"{}\": the directory does not exist or is not writable", path));
    }
  }
  const auto dir = std::filesystem::temp_directory_path();
  std::random_device rd;
  const auto script_path =
      dir / fmt::format("asperity-plot-{:08x}.gp", static_cast<unsigned>(rd()));
  std::ostringstream gp;
  gp << "set terminal pngcairo size 900,650 enhanced font 'DejaVu Sans,11'\n";
  gp << "set output " << gnuplot_quote(tmp_png.string()) << "\n";
  gp << "set title " << gnuplot_quote(spec.title) << " noenhanced\n";
  gp << "set xlabel " << gnuplot_quote(spec.xlabel) << "\n";
  gp << "set ylabel " << gnuplot_quote(spec.ylabel) << "\n";
  gp << "set grid\nset key outside right top noenhanced\n";
  if (spec.logx) gp << "set logscale x\nset format x '10^{%T}'\n";
  if (spec.logy) gp << "set logscale y\nset format y '10^{%T}'\n";
  gp << spec.extra << "\n";
  gp << "plot ";
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    gp << (i ? ", " : "") << "'-' using 1:2 with " << spec.series[i].style << " lw 2 title "
       << gnuplot_quote(spec.series[i].title);
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
  }
  const std::string cmd = fmt::format("gnuplot {} 2>&1", gnuplot_quote(script_path.string()));
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string messages;
  int status = -1;
  if (pipe) {
    char buf[512];
    while (std::fgets(buf, sizeof buf, pipe)) messages += buf;
    status = pclose(pipe);
  }
  std::error_code ec;
  std::filesystem::remove(script_path, ec);
  if (status != 0 || !std::filesystem::exists(tmp_png) ||
      std::filesystem::file_size(tmp_png, ec) == 0) {
    std::filesystem::remove(tmp_png, ec);
    if (messages.find("pngcairo") != std::string::npos) {
      throw Error(fmt::format("plotting \"{}\" failed: gnuplot has no pngcairo terminal ({})", path,
                              messages));
    }
    throw Error(fmt::format("plotting \"{}\" failed: is gnuplot installed (scripts/setup.sh)? {}",
                            path, messages));
  }
  std::filesystem::rename(tmp_png, target, ec);
  if (ec) {
    std::filesystem::remove(tmp_png, ec);
    throw InvalidInput(fmt::format("cannot write \"{}\": {}", path, ec.message()));
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
  }
  std::cout << out << std::flush;
  return 0;
}

}  // namespace asperity::cli
