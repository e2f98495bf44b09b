#include "asperity/joint/output_dir.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <system_error>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"

namespace asperity::joint {

namespace fs = std::filesystem;

namespace {

// The files the marker of `dir` lists (relative paths); empty when there is no marker,
// it lists nothing (an empty hand-made one) or it cannot be read.
std::set<std::string> listed_files(const fs::path& dir) {
  std::set<std::string> files;
  std::string text;
  try {
    text = core::read_input_file((dir / kOutputMarker).string(), std::size_t{1} << 20,
                                 "the output marker");
  } catch (const Error&) {
    return files;
  }
  std::istringstream in(text);
  std::string line;
  bool in_list = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (in_list && !line.empty()) files.insert(line);
    if (line == kOutputMarkerListHeader) in_list = true;
  }
  return files;
}

// The entries of `dir` (relative paths, directories with a trailing '/') that the marker
// does not list: the user's files.
std::vector<std::string> unlisted_entries(const fs::path& dir,
                                          const std::set<std::string>& listed) {
  std::vector<std::string> other;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string rel = it->path().lexically_relative(dir).generic_string();
    if (rel == kOutputMarker) continue;
    std::error_code e2;
    if (it->is_directory(e2) && !it->is_symlink(e2)) {
      const std::string prefix = rel + "/";
      const auto pos = listed.lower_bound(prefix);
      if (pos == listed.end() || pos->compare(0, prefix.size(), prefix) != 0) {
        other.push_back(prefix);
        it.disable_recursion_pending();
      }
      continue;
    }
    if (!listed.contains(rel)) other.push_back(rel);
  }
  if (ec) other.push_back(fmt::format("(cannot list the directory: {})", ec.message()));
  std::sort(other.begin(), other.end());
  return other;
}

}  // namespace

void require_replaceable_output(const fs::path& dir, const std::string& given) {
  std::error_code ec;
  const auto st = fs::symlink_status(dir, ec);
  if (ec || !fs::exists(st)) return;  // nothing there: it will be created
  if (fs::is_symlink(st)) {
    throw InvalidInput(fmt::format(
        "--out \"{}\" is a symbolic link; give a directory path (asperity replaces the output "
        "directory as a whole)",
        given));
  }
  if (!fs::is_directory(st)) {
    throw InvalidInput(fmt::format("--out \"{}\" is an existing file, not a directory", given));
  }
  if (fs::is_empty(dir, ec) && !ec) return;
  const bool marked = fs::exists(dir / kOutputMarker, ec);
  const auto other = unlisted_entries(dir, listed_files(dir));
  if (other.empty()) return;  // only what an earlier asperity wrote (and the marker)
  std::string names;
  for (std::size_t i = 0; i < other.size() && i < 5; ++i) names += (i ? ", " : "") + other[i];
  if (other.size() > 5) names += fmt::format(" and {} more", other.size() - 5);
  if (!marked) {
    throw InvalidInput(fmt::format(
        "--out \"{}\" is an existing directory that asperity did not write (it has files but no "
        "{} marker: {}); asperity replaces its output directory as a whole, so it refuses to "
        "touch it: choose another --out or remove the directory yourself",
        given, kOutputMarker, names));
  }
  throw InvalidInput(fmt::format(
      "--out \"{}\" holds files that asperity did not write (its {} marker does not list "
      "them): {}; asperity replaces its output directory as a whole, so it refuses: move them "
      "out or choose another --out",
      given, kOutputMarker, names));
}

namespace {

// The path absolute and normalized as written, and with symbolic links resolved.
std::vector<fs::path> path_forms(const std::string& p) {
  std::error_code ec;
  auto lexical = fs::absolute(fs::path(p), ec).lexically_normal();
  if (ec) lexical = fs::path(p).lexically_normal();
  while (!lexical.has_filename() && lexical.has_relative_path()) lexical = lexical.parent_path();
  std::vector<fs::path> forms{lexical};
  const auto canonical = fs::weakly_canonical(lexical, ec);
  if (!ec && canonical != lexical) forms.push_back(canonical);
  return forms;
}

// True when `inner` is `outer` or lies below it (component-wise, not by text prefix).
bool within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

}  // namespace

void require_output_apart_from_inputs(const std::string& dir,
                                      const std::vector<NamedInput>& inputs) {
  const auto out_forms = path_forms(dir);
  for (const auto& in : inputs) {
    if (in.path.empty()) continue;
    for (const auto& i : path_forms(in.path)) {
      for (const auto& o : out_forms) {
        if (i == o) {
          throw InvalidInput(
              fmt::format("--out \"{}\" names {} \"{}\": give the output directory its own name",
                          dir, in.what, in.path));
        }
        if (within(i, o)) {
          throw InvalidInput(fmt::format(
              "--out \"{}\" holds {} \"{}\": asperity replaces its output directory as a "
              "whole, which would delete the input; choose another --out or move the input",
              dir, in.what, in.path));
        }
      }
    }
  }
}

StagedDirectory::StagedDirectory(const std::string& final_dir, const std::string& what)
    : given_(final_dir) {
  if (final_dir.empty()) throw InvalidInput("--out: empty directory name");
  // "out/", "." and ".." name the directory itself: work on the normalized absolute path.
  std::error_code ec;
  final_ = fs::absolute(fs::path(final_dir), ec).lexically_normal();
  if (ec) throw InvalidInput(fmt::format("--out \"{}\": {}", final_dir, ec.message()));
  while (!final_.has_filename() && final_.has_relative_path()) final_ = final_.parent_path();
  if (!final_.has_filename() || final_ == final_.root_path()) {
    throw InvalidInput(fmt::format("--out \"{}\": give a directory below the root", final_dir));
  }
  require_replaceable_output(final_, given_);
  // Missing parents are created (as mkdir -p) and removed again if nothing is committed.
  for (auto p = final_.parent_path(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    created_parents_.push_back(p);
    if (p == p.root_path()) break;
  }
  if (!created_parents_.empty()) {
    fs::create_directories(final_.parent_path(), ec);
    if (ec) {
      remove_created_parents();
      throw InvalidInput(fmt::format("--out \"{}\": cannot create its parent directory ({})",
                                     final_dir, ec.message()));
    }
  }
  core::remove_stale_temporaries(final_);
  tmp_ = core::temporary_sibling(final_, "tmp");
  const core::SignalBlock block;  // created and registered before a SIGTERM can land
  if (!fs::create_directory(tmp_, ec) || ec) {
    remove_created_parents();
    throw InvalidInput(fmt::format(
        "--out \"{}\": cannot create a directory next to it ({}): does the parent exist and is it "
        "writable?",
        final_dir, ec ? ec.message() : "it exists"));
  }
  slot_ = core::register_temporary(tmp_, true, given_);
  what_ = what;
}

StagedDirectory::~StagedDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(tmp_, ec);
    core::unregister_temporary(slot_);
    remove_created_parents();
  }
}

void StagedDirectory::remove_created_parents() noexcept {
  std::error_code ec;
  for (const auto& p : created_parents_) fs::remove(p, ec);  // innermost first; only if empty
  created_parents_.clear();
}

std::string StagedDirectory::file(const std::string& name) const {
  return (tmp_ / name).string();
}

void StagedDirectory::commit() {
  // The marker lists every file written, so that the next run replaces only those.
  std::vector<std::string> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(tmp_, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code e2;
    if (it->is_directory(e2)) continue;
    const auto rel = it->path().lexically_relative(tmp_).generic_string();
    if (rel != kOutputMarker) files.push_back(rel);
  }
  std::sort(files.begin(), files.end());
  std::string marker = fmt::format(
      "Written by {}. asperity replaces this directory when it writes to it again (--out) only\n"
      "while it holds nothing but the files listed below; it refuses to touch a directory\n"
      "without this file or with other files.\n{}\n",
      what_, kOutputMarkerListHeader);
  for (const auto& f : files) marker += f + "\n";
  core::write_output_file((tmp_ / kOutputMarker).string(), marker);
  // Checked again: the directory may have been created or filled while we worked.
  require_replaceable_output(final_, given_);
  const core::SignalBlock block;  // the renames below are not cut by SIGINT/SIGTERM
  fs::path old;
  int old_slot = -1;
  if (fs::exists(fs::symlink_status(final_, ec))) {
    old = core::temporary_sibling(final_, "old");
    fs::rename(final_, old, ec);
    if (ec) throw InvalidInput(fmt::format("cannot replace \"{}\": {}", given_, ec.message()));
    old_slot = core::register_temporary(old, true, given_);
  }
  fs::rename(tmp_, final_, ec);
  if (ec) {
    std::error_code ec2;
    if (!old.empty()) fs::rename(old, final_, ec2);
    core::unregister_temporary(old_slot);
    throw InvalidInput(fmt::format("cannot write \"{}\": {}", given_, ec.message()));
  }
  committed_ = true;
  core::unregister_temporary(slot_);
  // `old` held only an earlier asperity output's files (checked above) or nothing.
  if (!old.empty()) fs::remove_all(old, ec);
  core::unregister_temporary(old_slot);
}

}  // namespace asperity::joint
