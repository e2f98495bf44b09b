#pragma once
// An output directory written whole or not at all: files go into a temporary sibling
// (DIR.tmp-XXXXXXXX) which commit() renames to DIR (replacing an older DIR); if the
// object is destroyed before commit() (an error), the temporary directory is removed,
// so no partial directory is left behind as if complete.
#include <filesystem>
#include <string>

namespace asperity::joint {

class StagedDirectory {
 public:
  /// Creates the temporary sibling of `final_dir`. Throws InvalidInput when the parent
  /// does not exist or is not writable, or when `final_dir` is an existing file.
  explicit StagedDirectory(const std::string& final_dir);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;
  /// Path of a file inside the temporary directory.
  [[nodiscard]] std::string file(const std::string& name) const;
  [[nodiscard]] const std::filesystem::path& staging() const { return tmp_; }
  /// Moves the temporary directory to its final name.
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path tmp_;
  bool committed_ = false;
};

}  // namespace asperity::joint
