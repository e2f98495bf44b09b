#!/usr/bin/env bash
# Installs every dependency of asperity on a fresh Debian 12 machine:
# system packages with apt-get, Python packages with pip into the virtual environment
# .venv in the repository root (Debian's python3 is "externally managed", PEP 668:
# pip may not install into it). Activate it with `source .venv/bin/activate` for the
# Python package and examples; the scripts call .venv/bin/python directly.
# Idempotent: packages already present are left alone, an existing .venv is reused.
set -euo pipefail
cd "$(dirname "$0")/.."

apt_packages=(
  build-essential cmake ninja-build pkg-config git
  libboost-dev                # Boost.Math (quadrature, roots), Boost.Odeint
  libkissfft-dev              # FFT for spectra, filtering and harmonic balance (AFT)
  libeigen3-dev               # linear algebra (vibration layer, fretting fits)
  libcli11-dev                # CLI parsing
  libtomlplusplus-dev         # case files
  nlohmann-json3-dev          # JSON output
  libfmt-dev                  # formatting
  libzip-dev libpugixml-dev   # ISO 5436-2 X3P profiles
  zipcmp zipmerge ziptool     # Debian's libzip CMake config checks these tools exist
  gnuplot-nox                 # CLI plots
  gmsh                        # meshes of `asperity structure` (GPL: run as a separate program)
  libspectra-dev              # sparse shift-invert eigenvalues (finite elements)
  libmatio-dev                # MATLAB .mat reduced models (BSD-2-Clause)
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  clang-format
  clang libclang-rt-14-dev    # libFuzzer targets under fuzz/ (ASPERITY_BUILD_FUZZ)
  python3 python3-dev python3-pip python3-venv   # the Python package, in .venv
  python3-numpy               # Debian's numpy: scripts/test-full.sh installs the wheel beside it
)

missing=()
for p in "${apt_packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The virtual environment: reused when its interpreter still runs (a venv breaks when
# the python3 it was made from is removed or upgraded), made anew otherwise.
if ! .venv/bin/python -c "import sys" >/dev/null 2>&1; then
  rm -rf .venv
  python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check -r python/requirements.txt
