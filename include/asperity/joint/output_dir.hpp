#pragma once
// An output directory written whole or not at all, and never over somebody else's files.
//
// Files go into a temporary sibling (.DIR.tmp-PID-XXXXXXXX) which commit() renames to
// DIR. Every directory written this way holds a marker file, `.asperity-output`, that
// lists the files asperity wrote there; an existing DIR is replaced only when it is
// empty or holds nothing but the files its marker lists. Any other file (one the user
// added, or any file at all when the marker is missing or lists nothing) makes it refused
// (InvalidInput, exit 2, naming the files) before any work is done, and checked again at
// commit(). If the object is destroyed before commit() (an error), the temporary
// directory is removed; it is registered for removal on SIGINT/SIGTERM
// (core/file_io.hpp), and a temporary left by a killed run is removed by the next one.
#include <filesystem>
#include <string>
#include <vector>

namespace asperity::joint {

/// Name of the marker file in every directory asperity writes with --out.
inline constexpr const char* kOutputMarker = ".asperity-output";
/// The line of the marker after which it lists the files, one relative path a line.
inline constexpr const char* kOutputMarkerListHeader = "files:";

class StagedDirectory {
 public:
  /// Creates the temporary sibling of `final_dir` (with the marker file), and missing
  /// parent directories (removed again when nothing is committed). Throws InvalidInput
  /// when the parent cannot be created or is not writable, when `final_dir` is
  /// an existing file or symbolic link, or when it is an existing non-empty directory
  /// without the marker. `what` names the writer in the marker ("asperity predict").
  explicit StagedDirectory(const std::string& final_dir, const std::string& what = "asperity");
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;
  /// Path of a file inside the temporary directory.
  [[nodiscard]] std::string file(const std::string& name) const;
  [[nodiscard]] const std::filesystem::path& staging() const { return tmp_; }
  /// Moves the temporary directory to its final name, replacing an older asperity output
  /// (or an empty directory) there.
  void commit();

 private:
  std::string given_;  // the --out text, for messages
  std::filesystem::path final_;
  std::filesystem::path tmp_;
  std::vector<std::filesystem::path> created_parents_;  // innermost first
  std::string what_;
  int slot_ = -1;  // registry slot of tmp_ (core/file_io.hpp)
  bool committed_ = false;
  void remove_created_parents() noexcept;
};

/// Throws InvalidInput unless `dir` may be replaced by an asperity output: it does not
/// exist, or it is a directory that is empty or holds only the marker and the files it
/// lists. The message names (up to five of) the other files.
void require_replaceable_output(const std::filesystem::path& dir, const std::string& given);

/// An input of a command: what it is ("the case file", "data file") and its path.
struct NamedInput {
  std::string what;
  std::string path;
};

/// Throws InvalidInput when the output directory `dir` (the --out text) is one of the
/// `inputs` or holds one of them at any depth: the directory is replaced as a whole, so
/// the input would be deleted. Paths are compared absolute and normalized ("." and
/// ".."), both as written and with symbolic links resolved.
void require_output_apart_from_inputs(const std::string& dir,
                                      const std::vector<NamedInput>& inputs);

}  // namespace asperity::joint
