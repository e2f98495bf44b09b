#include "asperity/core/file_io.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <pthread.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <mutex>
#include <random>

#include "asperity/core/error.hpp"

namespace asperity::core {

namespace fs = std::filesystem;

namespace {

std::string byte_count(std::uint64_t b) {
  if (b >= (std::uint64_t{1} << 20) && b % (std::uint64_t{1} << 20) == 0)
    return fmt::format("{} MiB", b >> 20);
  if (b >= (std::uint64_t{1} << 20))
    return fmt::format("{:.4g} MiB", static_cast<double>(b) / 1048576.0);
  return fmt::format("{} bytes", b);
}

const char* file_kind(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISFIFO(m)) return "a pipe";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

// ------------------------------------------------------------------ registry

constexpr int kSlots = 64;
constexpr std::size_t kPathBytes = 4096;

struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 registered
  bool is_directory = false;
  std::array<char, kPathBytes> path{};
};

std::array<Slot, kSlots> g_slots;
std::mutex g_names_mutex;
std::map<int, std::pair<std::string, std::string>> g_names;  // slot -> (temporary, final)

struct LinuxDirent64 {
  std::uint64_t d_ino;
  std::int64_t d_off;
  unsigned short d_reclen;
  unsigned char d_type;
  char d_name[1];
};

// Empties the open directory `fd` (async-signal-safe: getdents64, unlinkat, openat).
void empty_directory(int fd, int depth) noexcept {
  alignas(8) char buf[4096];
  for (int pass = 0; pass < 4; ++pass) {
    bool removed = false;
    lseek(fd, 0, SEEK_SET);
    for (;;) {
      const long n = syscall(SYS_getdents64, fd, buf, sizeof buf);
      if (n <= 0) break;
      for (long off = 0; off < n;) {
        const auto* d = reinterpret_cast<const LinuxDirent64*>(buf + off);
        off += d->d_reclen;
        const char* name = d->d_name;
        if (name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'))) continue;
        if (unlinkat(fd, name, 0) == 0) {
          removed = true;
        } else if (errno == EISDIR && depth < 8) {
          const int sub = openat(fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
          if (sub >= 0) {
            empty_directory(sub, depth + 1);
            close(sub);
          }
          if (unlinkat(fd, name, AT_REMOVEDIR) == 0) removed = true;
        }
      }
    }
    if (!removed) break;
  }
}

void remove_now(const char* path, bool is_directory) noexcept {
  if (!is_directory) {
    unlink(path);
    return;
  }
  const int fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) {
    empty_directory(fd, 0);
    close(fd);
  }
  rmdir(path);
}

std::atomic<long> g_cleanup_child{0};
static_assert(std::atomic<long>::is_always_lock_free);  // read in a signal handler

extern "C" void asperity_cleanup_handler(int sig) {
  const int saved = errno;
  if (const long child = g_cleanup_child.load(); child > 0) {
    kill(static_cast<pid_t>(child), SIGKILL);  // async-signal-safe, as is waitpid
    while (waitpid(static_cast<pid_t>(child), nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  remove_registered_temporaries();
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  errno = saved;
  raise(sig);  // blocked while in the handler: delivered, with the default action, on return
}

bool process_runs(long pid) {
  if (pid <= 0) return true;  // not ours to judge
  if (pid == static_cast<long>(getpid())) return true;
  return kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

bool all_hex(std::string_view s) {
  for (char c : s) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return !s.empty();
}

bool all_digits(std::string_view s) {
  for (char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return !s.empty() && s.size() < 10;
}

void write_all(int fd, std::string_view content, const std::string& shown) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, std::min<std::size_t>(left, std::size_t{1} << 20));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InvalidInput(fmt::format("cannot write \"{}\": {}", shown, std::strerror(errno)));
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

// The descriptor of /dev/stdout, /dev/stderr, /dev/fd/N or /proc/self/fd/N; -1 otherwise.
int standard_stream(const std::string& path) {
  if (path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  for (std::string_view prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (path.rfind(prefix, 0) == 0 && all_digits(std::string_view(path).substr(prefix.size())))
      return std::stoi(path.substr(prefix.size()));
  }
  return -1;
}

}  // namespace

// ------------------------------------------------------------------ reading

std::string read_input_file(const std::string& path, std::size_t max_bytes, std::string_view what) {
  // O_NONBLOCK: opening a named pipe must not wait for a writer (it is refused below).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) {
    throw InvalidInput(fmt::format("{}: cannot open {}: {}", path, what, std::strerror(errno)));
  }
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (fstat(fd, &st) != 0) {
    throw InvalidInput(fmt::format("{}: cannot read {}: {}", path, what, std::strerror(errno)));
  }
  if (!S_ISREG(st.st_mode)) {
    throw InvalidInput(fmt::format("{}: {} is not a regular file (it is {}): give a file", path,
                                   what, file_kind(st.st_mode)));
  }
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes) {
    throw InvalidInput(fmt::format("{}: {} is {}, more than the {} this reader accepts", path, what,
                                   byte_count(size), byte_count(max_bytes)));
  }
  std::string bytes(static_cast<std::size_t>(size), '\0');
  std::size_t got = 0;
  for (;;) {
    if (got == bytes.size()) {
      if (bytes.size() > max_bytes) break;
      bytes.resize(std::min<std::size_t>(bytes.size() + 65536, max_bytes + 1));  // it grew
    }
    const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InvalidInput(
          fmt::format("{}: reading {} failed: {}", path, what, std::strerror(errno)));
    }
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  if (got > max_bytes) {
    throw InvalidInput(fmt::format("{}: {} grew past the {} this reader accepts while it was read",
                                   path, what, byte_count(max_bytes)));
  }
  bytes.resize(got);
  return bytes;
}

void require_regular_input(const std::string& path, std::size_t max_bytes, std::string_view what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    throw InvalidInput(fmt::format("{}: cannot open {}: {}", path, what, std::strerror(errno)));
  }
  if (!S_ISREG(st.st_mode)) {
    throw InvalidInput(fmt::format("{}: {} is not a regular file (it is {}): give a file", path,
                                   what, file_kind(st.st_mode)));
  }
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes) {
    throw InvalidInput(fmt::format("{}: {} is {}, more than the {} this reader accepts", path, what,
                                   byte_count(size), byte_count(max_bytes)));
  }
}

CaseFileText read_case_file_text(const std::string& path) {
  CaseFileText f;
  f.text = read_input_file(path, kMaxCaseFileBytes, "the case file");
  require_utf8(f.text, path, "the case file");
  const auto dir = fs::path(path).parent_path();
  f.base_dir = dir.empty() ? "." : dir.string();
  return f;
}

void require_utf8(std::string_view text, std::string_view path, std::string_view what,
                  std::size_t first_line) {
  std::size_t line = first_line, line_start = 0;
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = s[i];
    std::size_t len = 0;
    std::uint32_t cp = 0;
    if (c < 0x80) {
      if (c == '\n') {
        ++line;
        line_start = i + 1;
      }
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      len = 2;
      cp = c & 0x1Fu;
    } else if ((c & 0xF0) == 0xE0) {
      len = 3;
      cp = c & 0x0Fu;
    } else if ((c & 0xF8) == 0xF0) {
      len = 4;
      cp = c & 0x07u;
    }
    bool ok = len != 0 && i + len <= n;
    for (std::size_t k = 1; ok && k < len; ++k) {
      ok = (s[i + k] & 0xC0) == 0x80;
      cp = (cp << 6) | (s[i + k] & 0x3Fu);
    }
    if (ok) {
      static constexpr std::uint32_t kMin[] = {0, 0, 0x80, 0x800, 0x10000};
      ok = cp >= kMin[len] && cp <= 0x10FFFF && !(cp >= 0xD800 && cp <= 0xDFFF);
    }
    if (!ok) {
      throw InvalidInput(fmt::format(
          "{}:{}:{}: {} is not valid UTF-8 text (byte 0x{:02X} at offset {}); save it as UTF-8",
          path, line, i - line_start + 1, what, c, i));
    }
    i += len;
  }
}

// ------------------------------------------------------------------ registry

int register_temporary(const fs::path& temporary, bool is_directory,
                       const std::string& final_path) {
  const std::string p = fs::absolute(temporary).lexically_normal().string();
  if (p.size() + 1 > kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (g_slots[static_cast<std::size_t>(i)].state.compare_exchange_strong(expected, 1)) {
      auto& s = g_slots[static_cast<std::size_t>(i)];
      std::memcpy(s.path.data(), p.c_str(), p.size() + 1);
      s.is_directory = is_directory;
      s.state.store(2, std::memory_order_release);
      const std::lock_guard lock(g_names_mutex);
      g_names[i] = {p, final_path};
      return i;
    }
  }
  return -1;
}

fs::path create_registered_temporary_directory(std::string_view prefix, std::string_view what,
                                               int* slot) {
  std::string templ = (fs::temp_directory_path() / fmt::format("{}-XXXXXX", prefix)).string();
  const SignalBlock block;  // created and registered before a SIGTERM can land
  if (mkdtemp(templ.data()) == nullptr) {
    throw Error(fmt::format("cannot create a temporary directory for {} ({}): {}", what, templ,
                            std::strerror(errno)));
  }
  *slot = register_temporary(templ, true, templ);
  return templ;
}

void unregister_temporary(int slot) noexcept {
  if (slot < 0 || slot >= kSlots) return;
  {
    const std::lock_guard lock(g_names_mutex);
    g_names.erase(slot);
  }
  g_slots[static_cast<std::size_t>(slot)].state.store(0, std::memory_order_release);
}

void remove_registered_temporaries() noexcept {
  for (auto& s : g_slots) {
    if (s.state.load(std::memory_order_acquire) == 2) remove_now(s.path.data(), s.is_directory);
  }
}

void set_cleanup_child(long pid) noexcept {
  g_cleanup_child.store(pid);
}

void install_cleanup_signal_handlers() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    sigaction(sig, nullptr, &old);
    if (old.sa_handler == SIG_IGN) continue;  // e.g. started with nohup: stay ignored
    struct sigaction sa {};
    sa.sa_handler = asperity_cleanup_handler;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, nullptr);
  }
  // Past a file-size limit (ulimit -f) a write fails with EFBIG, reported like a full
  // disk, instead of the process being killed with its temporaries left behind.
  std::signal(SIGXFSZ, SIG_IGN);
}

SignalBlock::SignalBlock() {
  static_assert(sizeof(sigset_t) <= sizeof(saved_));
  sigset_t block;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  sigaddset(&block, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &block, reinterpret_cast<sigset_t*>(saved_));
}

SignalBlock::~SignalBlock() {
  pthread_sigmask(SIG_SETMASK, reinterpret_cast<const sigset_t*>(saved_), nullptr);
}

std::string shown_path(const std::string& path) {
  std::error_code ec;
  const std::string abs = fs::absolute(path, ec).lexically_normal().string();
  if (ec) return path;
  const std::lock_guard lock(g_names_mutex);
  for (const auto& [slot, names] : g_names) {
    const auto& [tmp, final_path] = names;
    if (abs.size() > tmp.size() && abs.compare(0, tmp.size(), tmp) == 0 && abs[tmp.size()] == '/')
      return (fs::path(final_path) / abs.substr(tmp.size() + 1)).string();
  }
  return path;
}

// ------------------------------------------------------------------ temporaries

fs::path temporary_sibling(const fs::path& target, std::string_view kind) {
  static thread_local std::mt19937 gen(std::random_device{}());
  return target.parent_path() / fmt::format(".{}.{}-{}-{:08x}", target.filename().string(), kind,
                                            static_cast<long>(getpid()),
                                            static_cast<unsigned>(gen()));
}

std::size_t remove_stale_temporaries(const fs::path& target) noexcept {
  std::size_t removed = 0;
  try {
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    const std::string name = target.filename().string();
    if (name.empty()) return 0;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string f = it->path().filename().string();
      std::string_view rest;
      for (std::string_view kind : {".tmp-", ".old-"}) {
        const std::string prefix = "." + name + std::string(kind);
        if (f.size() > prefix.size() && f.compare(0, prefix.size(), prefix) == 0)
          rest = std::string_view(f).substr(prefix.size());
      }
      if (rest.empty()) continue;
      bool stale = false;
      const auto dash = rest.find('-');
      if (dash != std::string_view::npos) {
        // Ours: PID-XXXXXXXX, stale when that process is gone.
        stale = all_digits(rest.substr(0, dash)) && rest.size() - dash - 1 == 8 &&
                all_hex(rest.substr(dash + 1)) &&
                !process_runs(std::stol(std::string(rest.substr(0, dash))));
      } else if (rest.size() == 8 && all_hex(rest)) {
        // An earlier version's name (no PID): a file, or a directory with the marker.
        std::error_code e2;
        stale = !it->is_directory(e2) || fs::exists(it->path() / ".asperity-output", e2);
      }
      if (!stale) continue;
      std::error_code e3;
      if (fs::remove_all(it->path(), e3) > 0 && !e3) ++removed;
    }
  } catch (...) {
    // Best effort: a leftover that cannot be removed does not stop the run.
  }
  return removed;
}

// ------------------------------------------------------------------ OutputSet

OutputSet::~OutputSet() {
  if (!committed_) discard();
}

void OutputSet::discard() noexcept {
  for (auto& e : entries_) {
    if (!e.temporary.empty()) {
      std::error_code ec;
      fs::remove(e.temporary, ec);
      e.temporary.clear();
    }
    unregister_temporary(e.slot);
    e.slot = -1;
  }
}

bool OutputSet::prepare(const std::string& path, Entry& e, int* fd_out) {
  if (committed_) throw Error("OutputSet::add after commit");
  if (path.empty()) throw InvalidInput("an output path is empty: give a file name");
  e.shown = shown_path(path);
  e.fd = standard_stream(path);
  if (e.fd >= 0) {
    struct stat st {};
    if (fstat(e.fd, &st) != 0) {
      throw InvalidInput(fmt::format("cannot write \"{}\": descriptor {} is not open", path, e.fd));
    }
    return false;
  }
  const fs::path p(path);
  if (!p.has_filename()) throw InvalidInput(fmt::format("output path \"{}\" names no file", path));
  struct stat lst {};
  if (::lstat(path.c_str(), &lst) == 0) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
      throw InvalidInput(fmt::format(
          "cannot write \"{}\": it is a symbolic link to nothing ({}); remove it or give "
          "another path",
          e.shown, std::strerror(errno)));
    }
    if (S_ISDIR(st.st_mode)) {
      throw InvalidInput(
          fmt::format("output path \"{}\" is a directory: give a file name", e.shown));
    }
    if (S_ISBLK(st.st_mode)) {
      throw InvalidInput(fmt::format(
          "output path \"{}\" is a block device: refused (asperity writes regular files, "
          "pipes and terminals)",
          e.shown));
    }
    if (!S_ISREG(st.st_mode)) {  // a terminal, /dev/null, a pipe: written through
      e.target = p;
      return false;
    }
    std::error_code ec;
    e.target = S_ISLNK(lst.st_mode) ? fs::canonical(p, ec) : p;
    if (ec) throw InvalidInput(fmt::format("cannot write \"{}\": {}", e.shown, ec.message()));
  } else if (errno != ENOENT) {
    throw InvalidInput(fmt::format("cannot write \"{}\": {}", e.shown, std::strerror(errno)));
  } else {
    e.target = p;
  }
  remove_stale_temporaries(e.target);
  e.temporary = temporary_sibling(e.target, "tmp");
  const SignalBlock block;  // created and registered before a SIGTERM can land
  const int fd = ::open(e.temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int err = errno;
    e.temporary.clear();
    throw InvalidInput(fmt::format("cannot write \"{}\": {}{}", e.shown, std::strerror(err),
                                   err == ENOENT ? " (its directory does not exist)" : ""));
  }
  e.slot = register_temporary(e.temporary, false, e.target.string());
  *fd_out = fd;
  return true;
}

void OutputSet::add(const std::string& path, std::string_view content) {
  Entry e;
  int fd = -1;
  if (!prepare(path, e, &fd)) {
    e.content = std::string(content);  // written through at commit()
    entries_.push_back(std::move(e));
    return;
  }
  entries_.push_back(std::move(e));  // from here the destructor removes the temporary
  Entry& added = entries_.back();
  try {
    write_all(fd, content, added.shown);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) {
    throw InvalidInput(fmt::format("cannot write \"{}\": {}", added.shown, std::strerror(errno)));
  }
}

void OutputSet::add_streamed(
    const std::string& path,
    const std::function<void(const std::function<void(std::string_view)>&)>& produce) {
  Entry e;
  int fd = -1;
  const bool staged = prepare(path, e, &fd);
  if (!staged) {
    // Written through as the pieces come (a stream has no whole to keep back).
    if (e.fd >= 0) {
      std::cout.flush();
      std::fflush(stdout);
      fd = e.fd;
    } else {
      fd = ::open(e.target.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
      if (fd < 0) {
        throw InvalidInput(fmt::format("cannot write \"{}\": {}", e.shown, std::strerror(errno)));
      }
    }
    struct Closer {
      int fd;
      bool own;
      ~Closer() {
        if (own) ::close(fd);
      }
    } closer{fd, e.fd < 0};
    const std::string shown = e.shown;
    produce([fd, &shown](std::string_view piece) { write_all(fd, piece, shown); });
    return;
  }
  entries_.push_back(std::move(e));
  Entry& added = entries_.back();
  try {
    produce([fd, &added](std::string_view piece) { write_all(fd, piece, added.shown); });
  } catch (...) {
    ::close(fd);
    throw;  // the destructor removes the temporary
  }
  if (::close(fd) != 0) {
    throw InvalidInput(fmt::format("cannot write \"{}\": {}", added.shown, std::strerror(errno)));
  }
}

void OutputSet::commit() {
  if (committed_) return;
  try {
    // Written through first: they are the ones that can fail (/dev/full); a rename
    // within a directory does not run out of space.
    for (auto& e : entries_) {
      if (!e.temporary.empty()) continue;
      if (e.fd >= 0) {
        std::cout.flush();
        std::fflush(stdout);
        std::fflush(stderr);
        write_all(e.fd, e.content, e.shown);
        continue;
      }
      const int fd = ::open(e.target.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
      if (fd < 0) {
        throw InvalidInput(fmt::format("cannot write \"{}\": {}", e.shown, std::strerror(errno)));
      }
      try {
        write_all(fd, e.content, e.shown);
      } catch (...) {
        ::close(fd);
        throw;
      }
      ::close(fd);
    }
    const SignalBlock block;  // the renames are not cut by a signal
    for (auto& e : entries_) {
      if (e.temporary.empty()) continue;
      if (std::rename(e.temporary.c_str(), e.target.c_str()) != 0) {
        throw InvalidInput(fmt::format("cannot write \"{}\": {}", e.shown, std::strerror(errno)));
      }
      e.temporary.clear();
      unregister_temporary(e.slot);
      e.slot = -1;
    }
  } catch (...) {
    discard();
    throw;
  }
  committed_ = true;
}

void write_output_file(const std::string& path, std::string_view content) {
  OutputSet set;
  set.add(path, content);
  set.commit();
}

}  // namespace asperity::core
