#include "asperity/core/process.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/interrupt.hpp"

extern char** environ;  // POSIX: the environment, for posix_spawnp

namespace asperity::core {
namespace {

void reap(pid_t pid, int* status) {
  // Waited for without reaping first: until waitpid the pid cannot belong to another
  // process, so the cleanup handler never kills a stranger.
  siginfo_t info{};
  while (waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
  }
  set_cleanup_child(0);
  while (waitpid(pid, status, 0) < 0 && errno == EINTR) {
  }
}

}  // namespace

ProgramRun run_program(std::vector<std::string> argv, double time_limit) {
  ProgramRun run;
  int fds[2];
  if (pipe(fds) != 0) throw Error(fmt::format("cannot run {}: {}", argv[0], std::strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  std::vector<char*> args;
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  pid_t pid = 0;
  int rc = 0;
  {
    // Spawned and registered with signals blocked, so that a SIGTERM cannot fall between
    // the two; the child starts with no signal blocked.
    const SignalBlock block;
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
    rc = posix_spawnp(&pid, args[0], &actions, &attr, args.data(), environ);
    posix_spawnattr_destroy(&attr);
    if (rc == 0) set_cleanup_child(pid);  // a SIGTERM meanwhile ends the child too
  }
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  if (rc != 0) {
    close(fds[0]);
    run.spawn_error = rc;
    return run;
  }
  const auto start = std::chrono::steady_clock::now();
  constexpr std::size_t kKeep = std::size_t{1} << 16;
  char buf[4096];
  int status = 0;
  try {
    for (;;) {
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (elapsed > time_limit) {
        run.timed_out = true;
        kill(pid, SIGKILL);
        break;
      }
      check_interrupt();
      pollfd p{fds[0], POLLIN, 0};
      const int ready = poll(&p, 1, 100);
      if (ready < 0 && errno != EINTR) break;
      if (ready <= 0) continue;
      const ssize_t n = read(fds[0], buf, sizeof buf);
      if (n > 0) {
        run.output.append(buf, static_cast<std::size_t>(n));
        if (run.output.size() > 2 * kKeep) run.output.erase(0, run.output.size() - kKeep);
      } else if (n == 0 || errno != EINTR) {
        break;  // the child closed its output: it is ending
      }
    }
  } catch (...) {
    kill(pid, SIGKILL);
    close(fds[0]);
    reap(pid, &status);
    throw;
  }
  close(fds[0]);
  reap(pid, &status);
  run.exited_zero = !run.timed_out && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  run.status = WIFEXITED(status) ? fmt::format("exit status {}", WEXITSTATUS(status))
                                 : fmt::format("signal {}", WTERMSIG(status));
  return run;
}

}  // namespace asperity::core
