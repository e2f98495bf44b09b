// asperity sweep: the sweeps and Monte Carlo of python/asperity/sweep (Dask, xarray), run
// as a separate program: the Python module `asperity.sweep` under an interpreter that has
// the asperity package, with every argument forwarded and its exit code returned (the
// process is replaced by the interpreter, so its output, signals and exit status are the
// module's own).
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>

#include "asperity/core/process.hpp"
#include "commands.hpp"

namespace asperity::cli {

namespace {

// Runs the module under the name `asperity sweep` (its usage, help and messages).
constexpr const char* sweep_entry =
    "import sys; from asperity.sweep.__main__ import main; "
    "sys.exit(main(prog='asperity sweep'))";

// Whether `python` starts and imports the sweep module (the package, its compiled core
// and the sweep dependencies); the reason when it does not.
std::optional<std::string> lacks_sweep_module(const std::string& python) {
  const auto run = core::run_program({python, "-c", "import asperity.sweep.__main__"}, 120.0);
  if (run.spawn_error == ENOENT) return std::string("not found");
  if (run.spawn_error != 0) return std::string(std::strerror(run.spawn_error));
  if (run.exited_zero) return std::nullopt;
  // The last line of the interpreter's output: the exception (ModuleNotFoundError: ...).
  std::string out = run.output;
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  const auto nl = out.rfind('\n');
  return nl == std::string::npos ? out : out.substr(nl + 1);
}

// The interpreters tried, in order: ASPERITY_PYTHON alone when set; otherwise python3 and
// python in the directory of this executable (a wheel installs `asperity` next to the
// environment's interpreter), then python3 on PATH.
std::vector<std::string> candidate_interpreters() {
  if (const char* env = std::getenv("ASPERITY_PYTHON"); env != nullptr && *env != '\0')
    return {env};
  std::vector<std::string> out;
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const char* name : {"python3", "python"}) {
      const auto p = self.parent_path() / name;
      if (::access(p.c_str(), X_OK) == 0) out.push_back(p.string());
    }
  }
  out.emplace_back("python3");
  return out;
}

}  // namespace

int run_sweep(const std::vector<std::string>& args) {
  const bool from_env =
      std::getenv("ASPERITY_PYTHON") != nullptr && *std::getenv("ASPERITY_PYTHON") != '\0';
  std::string tried;
  for (const auto& python : candidate_interpreters()) {
    const auto reason = lacks_sweep_module(python);
    if (!reason) {
      std::vector<std::string> argv{python, "-c", sweep_entry};
      argv.insert(argv.end(), args.begin(), args.end());
      std::vector<char*> cargv;
      for (auto& a : argv) cargv.push_back(a.data());
      cargv.push_back(nullptr);
      std::cout.flush();
      std::cerr.flush();
      ::execvp(cargv[0], cargv.data());
      std::cerr << "asperity: error: cannot run " << python << ": " << std::strerror(errno) << "\n";
      return 1;
    }
    tried += fmt::format("{}{}{} ({})", tried.empty() ? "" : "; ",
                         from_env ? "ASPERITY_PYTHON=" : "", python, *reason);
  }
  // The user's environment, like a missing gnuplot: exit 2.
  std::cerr << "asperity: error: sweep needs a Python interpreter with the asperity package "
               "and its sweep extras (pip install 'asperity[sweep]'); tried "
            << tried << (from_env ? "" : "; set ASPERITY_PYTHON to the interpreter to use") << "\n";
  return 2;
}

void add_sweep_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand(
      "sweep",
      "Sweeps and Monte Carlo of a joint or dynamics case on Dask (grids, uniform, normal, "
      "choice; random, Sobol or LHS), results as NetCDF/Parquet with summary, sensitivity and "
      "plots: runs the Python module asperity.sweep (`asperity sweep --help` lists its "
      "options) under ASPERITY_PYTHON, else a python3 or python next to this executable, else "
      "python3 on PATH; needs pip install 'asperity[sweep]'.");
  // Every argument, --help included, goes to the module (main() calls run_sweep before
  // parsing; this subcommand lists `sweep` in --help).
  cmd->prefix_command();
  cmd->set_help_flag();
  cmd->allow_extras();
  cmd->callback([cmd, &action] { action = [args = cmd->remaining()] { return run_sweep(args); }; });
}

}  // namespace asperity::cli
