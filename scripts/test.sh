#!/usr/bin/env bash
# The quick test command (README "Quick start"): sets everything up on a fresh Debian machine,
# checks that the C++ sources are formatted as .clang-format says, builds the `ci` preset once
# (Release, warnings as errors, with the Python module; the benchmarks are left to
# scripts/test-full.sh) and runs its ctest suite: GoogleTest, the CLI checks, the examples and
# the pytest suite against that build's module and `asperity` command, which also runs every
# code block of README.md and docs/*.md (tests/python/test_docs.py). The installed package's
# checks (tests/package: every public header compiled by a downstream find_package project,
# ~70 s of compiling) are left to scripts/test-full.sh, to keep this under 10 minutes. Every Python step runs
# .venv/bin/python (scripts/setup.sh makes it). scripts/test-full.sh runs this and then the
# sanitizer, fuzz, benchmark-build and installed-wheel stages.
set -euo pipefail
source "$(dirname "$0")/test-common.sh"

stage "C++ sources formatted as .clang-format says"
git ls-files -z -- '*.cpp' '*.hpp' | xargs -0 clang-format --dry-run -Werror

stage "C++ and Python (ci preset): configure, build (warnings as errors), ctest"
# The CLI tests run Python drivers: with the venv's interpreter, like everything else.
cmake --preset ci -DPython3_EXECUTABLE="$py" -DASPERITY_BUILD_BENCH=OFF
cmake --build --preset ci -j 2
# The package checks (label `package`, the shared library's among them) run in test-full.sh.
ctest --preset ci -j 2 -LE package
stage "quick tests passed"
