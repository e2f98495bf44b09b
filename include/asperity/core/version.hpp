#pragma once
// Which asperity this is: the release, the source revision and how it was built (printed by
// `asperity --version` and carried by every JSON output as `asperity_version`).
#include <string_view>

namespace asperity::core {

struct VersionInfo {
  std::string_view version;       ///< release, "0.1.0" (CMake project version)
  std::string_view git_revision;  ///< `git describe --always --dirty`, "unknown" outside git
  std::string_view build_type;    ///< CMake build type, "+asan+ubsan" appended when sanitized
};

/// The version of the library as built (generated at build time, cmake/version_info.cmake).
[[nodiscard]] VersionInfo version_info() noexcept;

}  // namespace asperity::core
