#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine and runs every test: the C++ suite
# (GoogleTest, CLI checks, the downstream find_package check) with warnings as errors,
# a short libFuzzer smoke run of the profile readers, then the Python package installed
# with pip and its pytest suite.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh

echo "== C++: configure, build (warnings as errors), test"
cmake --preset ci
cmake --build --preset ci -j 2
ctest --preset ci -j 2

echo "== Fuzz smoke run of the profile readers (libFuzzer, clang, ASan + UBSan)"
cmake -S . -B build/fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DASPERITY_BUILD_FUZZ=ON \
  -DASPERITY_BUILD_TESTS=OFF -DASPERITY_BUILD_CLI=OFF -DASPERITY_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build/fuzz --target fuzz_targets -j 2
ctest --test-dir build/fuzz -L fuzz --output-on-failure

echo "== Python: pip install . and pytest"
python3 -m pip install --quiet --disable-pip-version-check --no-build-isolation .
python3 -m pytest tests/python -q
