#include "asperity/joint/output_dir.hpp"

#include <fmt/format.h>

#include <random>
#include <system_error>

#include "asperity/core/error.hpp"

namespace asperity::joint {

namespace fs = std::filesystem;

StagedDirectory::StagedDirectory(const std::string& final_dir) : final_(final_dir) {
  if (final_dir.empty()) throw InvalidInput("--out: empty directory name");
  std::error_code ec;
  if (fs::exists(final_, ec) && !fs::is_directory(final_, ec)) {
    throw InvalidInput(fmt::format("--out \"{}\" is an existing file, not a directory", final_dir));
  }
  auto name = final_.filename();
  if (name.empty()) {
    final_ = final_.parent_path();
    name = final_.filename();
  }
  std::random_device rd;
  tmp_ = final_.parent_path() /
         fmt::format(".{}.tmp-{:08x}", name.string(), static_cast<unsigned>(rd()));
  if (!fs::create_directory(tmp_, ec) || ec) {
    throw InvalidInput(fmt::format(
        "--out \"{}\": cannot create a directory next to it ({}): does the parent exist and is it "
        "writable?",
        final_dir, ec ? ec.message() : "it exists"));
  }
}

StagedDirectory::~StagedDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(tmp_, ec);
  }
}

std::string StagedDirectory::file(const std::string& name) const {
  return (tmp_ / name).string();
}

void StagedDirectory::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(final_, ec)) {
    std::random_device rd;
    old = final_.parent_path() /
          fmt::format(".{}.old-{:08x}", final_.filename().string(), static_cast<unsigned>(rd()));
    fs::rename(final_, old, ec);
    if (ec)
      throw InvalidInput(fmt::format("cannot replace \"{}\": {}", final_.string(), ec.message()));
  }
  fs::rename(tmp_, final_, ec);
  if (ec) {
    if (!old.empty()) fs::rename(old, final_, ec);
    throw InvalidInput(fmt::format("cannot write \"{}\": {}", final_.string(), ec.message()));
  }
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace asperity::joint
