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

#include "asperity/core/error.hpp"

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

namespace {

std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
  std::random_device rd;
  return path.parent_path() /
         fmt::format(".{}.tmp-{:08x}", path.filename().string(), static_cast<unsigned>(rd()));
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& content) {
  const std::filesystem::path target(path);
  if (target.filename().empty()) throw InvalidInput(fmt::format("output path \"{}\" names no file", path));
  const auto tmp = temporary_sibling(target);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw InvalidInput(fmt::format("cannot write \"{}\": the directory does not exist or is not "
                                     "writable",
                                     path));
    }
    out << content;
    out.flush();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw InvalidInput(fmt::format("writing \"{}\" failed", path));
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InvalidInput(fmt::format("cannot write \"{}\": {}", path, ec.message()));
  }
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
  if (target.filename().empty()) throw InvalidInput(fmt::format("output path \"{}\" names no file", path));
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
  const auto script_path = dir / fmt::format("asperity-plot-{:08x}.gp", static_cast<unsigned>(rd()));
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
    for (std::size_t j = 0; j < s.x.size(); ++j) gp << fmt::format("{:.10g} {:.10g}\n", s.x[j], s.y[j]);
    gp << "e\n";
  }
  {
    std::ofstream script(script_path);
    script << gp.str();
  }
  const std::string cmd =
      fmt::format("gnuplot {} 2>&1", gnuplot_quote(script_path.string()));
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
  if (status != 0 || !std::filesystem::exists(tmp_png) || std::filesystem::file_size(tmp_png, ec) == 0) {
    std::filesystem::remove(tmp_png, ec);
    if (messages.find("pngcairo") != std::string::npos) {
      throw Error(fmt::format("plotting \"{}\" failed: gnuplot has no pngcairo terminal ({})",
                              path, messages));
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
