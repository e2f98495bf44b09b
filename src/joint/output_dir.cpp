#include "asperity/joint/output_dir.hpp"

#include <fmt/format.h>

#include <fstream>
#include <random>
#include <system_error>

#include "asperity/core/error.hpp"

namespace asperity::joint {

namespace fs = std::filesystem;

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
  if (fs::exists(dir / kOutputMarker, ec)) return;  // an earlier asperity output
  if (fs::is_empty(dir, ec) && !ec) return;
  throw InvalidInput(fmt::format(
      "--out \"{}\" is an existing directory that asperity did not write (it has files but no {} "
      "marker); asperity replaces its output directory as a whole, so it refuses to touch it: "
      "choose another --out or remove the directory yourself",
      given, kOutputMarker));
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
  std::random_device rd;
  tmp_ = final_.parent_path() /
         fmt::format(".{}.tmp-{:08x}", final_.filename().string(), static_cast<unsigned>(rd()));
  if (!fs::create_directory(tmp_, ec) || ec) {
    remove_created_parents();
    throw InvalidInput(fmt::format(
        "--out \"{}\": cannot create a directory next to it ({}): does the parent exist and is it "
        "writable?",
        final_dir, ec ? ec.message() : "it exists"));
  }
  std::ofstream marker(tmp_ / kOutputMarker);
  marker << fmt::format(
      "Written by {}. This directory is replaced as a whole when asperity writes to it again\n"
      "(--out); without this file asperity refuses to touch the directory.\n",
      what);
  if (!marker) {
    fs::remove_all(tmp_, ec);
    remove_created_parents();
    throw InvalidInput(fmt::format("--out \"{}\": cannot write into {}", final_dir, tmp_.string()));
  }
}

StagedDirectory::~StagedDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(tmp_, ec);
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
  // Checked again: the directory may have been created or filled while we worked.
  require_replaceable_output(final_, given_);
  std::error_code ec;
  fs::path old;
  if (fs::exists(fs::symlink_status(final_, ec))) {
    std::random_device rd;
    old = final_.parent_path() /
          fmt::format(".{}.old-{:08x}", final_.filename().string(), static_cast<unsigned>(rd()));
    fs::rename(final_, old, ec);
    if (ec) throw InvalidInput(fmt::format("cannot replace \"{}\": {}", given_, ec.message()));
  }
  fs::rename(tmp_, final_, ec);
  if (ec) {
    std::error_code ec2;
    if (!old.empty()) fs::rename(old, final_, ec2);
    throw InvalidInput(fmt::format("cannot write \"{}\": {}", given_, ec.message()));
  }
  committed_ = true;
  // `old` is an earlier asperity output (it has the marker) or an empty directory.
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace asperity::joint
