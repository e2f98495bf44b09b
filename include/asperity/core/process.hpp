#pragma once
// Running an external program (gmsh, gnuplot) as a separate process: POSIX posix_spawnp,
// no shell, so no quoting of arguments is needed and the program's licence never reaches
// the library.
#include <limits>
#include <string>
#include <vector>

namespace asperity::core {

struct ProgramRun {
  int spawn_error = 0;  ///< errno of posix_spawnp (ENOENT: not found); 0 when it started
  bool exited_zero = false;
  bool timed_out = false;
  std::string status;  ///< "exit status 1", "signal 11"
  std::string output;  ///< the last 64 KiB or more of stdout and stderr, interleaved
};

/// Runs argv[0] (looked up on PATH) with the arguments argv[1...], without a shell,
/// stdin from /dev/null, stdout and stderr collected. The child is the cleanup child
/// (file_io.hpp) while it runs, so that a SIGTERM of this process ends it too; it is
/// killed (SIGKILL) after `time_limit` seconds (then timed_out) or when the interrupt
/// hook throws (then rethrown). Throws Error when no pipe can be made; a program that
/// cannot be started is reported in spawn_error, not thrown.
[[nodiscard]] ProgramRun run_program(std::vector<std::string> argv,
                                     double time_limit = std::numeric_limits<double>::infinity());

}  // namespace asperity::core
