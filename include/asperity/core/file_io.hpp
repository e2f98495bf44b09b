#pragma once
// Reading inputs with a stated size cap, and writing outputs whole or not at all.
//
// Reading: every reader takes a regular file only (a directory, a pipe, a terminal or a
// device such as /dev/zero is refused as "not a regular file" before anything is read)
// and at most a stated number of bytes (the caps below).
//
// Writing: an OutputSet writes every output of a command into a hidden temporary next
// to its target (".NAME.tmp-PID-XXXXXXXX"); only when all of them are written whole are
// they renamed into place, so a failure (a full disk, a bad path) leaves none of them.
// What a path may name:
//  - nothing, or a regular file: replaced (temporary, then rename);
//  - a symbolic link to a regular file: the file it points to is replaced, the link
//    stays;
//  - a character device, a pipe or a socket (a terminal, /dev/null, a named pipe), and
//    /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N: written through, in place,
//    never replaced (so `--out /dev/stdout` prints); the standard streams are written on
//    their open descriptors, after whatever the command printed before;
//  - a directory, a block device or a dangling symbolic link: refused (InvalidInput).
// The temporaries are registered: remove_registered_temporaries() removes them (the CLI
// calls it from its SIGINT/SIGTERM/SIGHUP handler), and every later write to the same
// target first removes temporaries of our naming whose process is gone.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace asperity::core {

/// Cap of a case file (TOML): 4 MiB; a case file is a few kilobytes.
inline constexpr std::size_t kMaxCaseFileBytes = std::size_t{4} << 20;
/// Cap of a numeric table (a displacement history, measured fretting data): 512 MiB,
/// about 20 million rows of three columns.
inline constexpr std::size_t kMaxTableFileBytes = std::size_t{512} << 20;
/// Cap of a profile or height-map file (text or X3P): 1 GiB.
inline constexpr std::size_t kMaxProfileFileBytes = std::size_t{1} << 30;

/// The bytes of the regular file `path`, at most `max_bytes` of them. Throws
/// InvalidInput naming the path and `what` ("the case file") when the path does not
/// exist, is not a regular file (a directory, a pipe, a device such as /dev/zero), is
/// larger than the cap (stated in the message), or cannot be read (with the system's
/// reason).
[[nodiscard]] std::string read_input_file(const std::string& path, std::size_t max_bytes,
                                          std::string_view what);

/// Throws InvalidInput at the first byte of `text` that is not valid UTF-8 (overlong
/// forms, surrogates and code points above U+10FFFF included), naming the path, the
/// line, the column and the byte.
/// `first_line` numbers the first line of `text` (a streamed reader checks line by line).
void require_utf8(std::string_view text, std::string_view path, std::string_view what,
                  std::size_t first_line = 1);

/// A case file read for its parser: the text (read_input_file with kMaxCaseFileBytes,
/// then require_utf8) and the directory its relative paths are taken from ("." for a
/// file named without a directory).
struct CaseFileText {
  std::string text;
  std::string base_dir;
};
[[nodiscard]] CaseFileText read_case_file_text(const std::string& path);

/// Throws InvalidInput as read_input_file does, without reading: for readers that stream
/// the file themselves (and stop at the cap).
void require_regular_input(const std::string& path, std::size_t max_bytes, std::string_view what);

/// The outputs of one command, committed together or not at all (see the file comment).
class OutputSet {
 public:
  OutputSet() = default;
  /// Removes every temporary not yet committed.
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  /// Writes `content` for `path` into its temporary now (or keeps it, for a path that is
  /// written through at commit()). Throws InvalidInput naming `path` (never the
  /// temporary) and the system's reason ("No space left on device") on failure.
  void add(const std::string& path, std::string_view content);
  /// As add(), with the content handed piece by piece by `produce` to its sink, written
  /// into the temporary as it comes (memory holds one piece). A path written through (a
  /// device, a pipe) receives the pieces at once, not at commit().
  void add_streamed(
      const std::string& path,
      const std::function<void(const std::function<void(std::string_view)>&)>& produce);
  /// Writes the outputs that are written through, then renames every temporary into
  /// place. Throws InvalidInput when one fails; the temporaries not yet renamed are
  /// removed.
  void commit();

 private:
  struct Entry {
    std::string shown;                // the path as the user gave it, for messages
    std::filesystem::path target;     // what is replaced (a symbolic link's file)
    std::filesystem::path temporary;  // empty when written through
    int fd = -1;                      // a standard stream written on its descriptor
    std::string content;              // kept for outputs written through
    int slot = -1;                    // registry slot of the temporary
  };
  std::vector<Entry> entries_;
  bool committed_ = false;
  void discard() noexcept;
  // Prepares an entry for `path`: true (and the descriptor of its temporary in *fd) when
  // it is staged in a temporary, false when it is written through.
  bool prepare(const std::string& path, Entry& e, int* fd);
};

/// Writes one file through an OutputSet of one entry.
void write_output_file(const std::string& path, std::string_view content);

/// The name of a temporary for `target`: ".NAME.tmp-PID-XXXXXXXX" (`kind` "tmp") or
/// ".NAME.old-PID-XXXXXXXX" (`kind` "old"), in the same directory.
[[nodiscard]] std::filesystem::path temporary_sibling(const std::filesystem::path& target,
                                                      std::string_view kind);

/// Removes the temporaries of `target` left by an earlier asperity that was killed:
/// siblings named ".NAME.tmp-PID-XXXXXXXX" or ".NAME.old-PID-XXXXXXXX" whose process PID
/// no longer runs, and the names of earlier versions without a PID (".NAME.tmp-XXXXXXXX",
/// ".NAME.old-XXXXXXXX"; a directory only when it holds the .asperity-output marker).
/// Returns how many it removed. Never throws.
std::size_t remove_stale_temporaries(const std::filesystem::path& target) noexcept;

/// Registers a temporary file or directory for remove_registered_temporaries(); returns
/// its slot (or -1 when the registry, 64 slots, is full: then it is only removed by its
/// owner or, after a kill, by remove_stale_temporaries). `final_path` is how messages
/// name things inside the temporary (see shown_path).
int register_temporary(const std::filesystem::path& temporary, bool is_directory,
                       const std::string& final_path);
/// Creates a private directory "PREFIX-XXXXXX" under the system's temporary directory
/// (mkdtemp) and registers it, with SIGINT/SIGTERM/SIGHUP blocked between the two so that
/// a signal cannot leave it behind; its slot in *slot. Throws Error naming `what` (the
/// program it is for) when it cannot be created.
[[nodiscard]] std::filesystem::path create_registered_temporary_directory(std::string_view prefix,
                                                                          std::string_view what,
                                                                          int* slot);
/// Forgets a slot (the temporary was renamed or removed by its owner).
void unregister_temporary(int slot) noexcept;
/// Removes every registered temporary (directories with their contents).
/// Async-signal-safe: only open, getdents64, unlinkat and close.
void remove_registered_temporaries() noexcept;
/// The child process (gnuplot) that writes into a registered temporary, or 0 for none:
/// the cleanup handler ends it (SIGKILL, then waits for it) before removing the
/// temporaries, so that it neither outlives the process nor writes into a removed
/// directory. One at a time.
void set_cleanup_child(long pid) noexcept;
/// Installs handlers for SIGINT, SIGTERM and SIGHUP that end the cleanup child, remove
/// the registered temporaries and then end the process by the same signal (exit status
/// 128 + N), and ignores SIGXFSZ (a write past `ulimit -f` then fails with "File too
/// large").
void install_cleanup_signal_handlers();
/// Blocks SIGINT, SIGTERM and SIGHUP in this thread while it lives (pthread_sigmask), so
/// that a sequence of renames that commits outputs is not cut in the middle; a signal
/// that arrives meanwhile is delivered when the object is destroyed.
class SignalBlock {
 public:
  SignalBlock();
  ~SignalBlock();
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  unsigned char saved_[128];  // the previous sigset_t
};

/// `path` with a registered temporary directory replaced by the final path it stands
/// for, so that messages name the user's path, not ".out.tmp-...".
[[nodiscard]] std::string shown_path(const std::string& path);

}  // namespace asperity::core
