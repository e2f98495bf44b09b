#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine and runs every test: the C++ suite
# (GoogleTest, CLI checks, the downstream find_package check) with warnings as errors,
# then the Python package installed with pip and its pytest suite.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh

echo "== C++: configure, build (warnings as errors), test"
cmake --preset ci
cmake --build --preset ci -j 2
ctest --preset ci -j 2

echo "== Python: pip install . and pytest"
python3 -m pip install --quiet --disable-pip-version-check --no-build-isolation .
python3 -m pytest tests/python -q
