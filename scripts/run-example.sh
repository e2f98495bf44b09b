#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine, builds asperity and runs the main job
# on a shipped example: the friction prediction for the thesis's two-bolt steel 420 lap
# joint (chapter 5, Tables 5.3-5.5) over its four bolt torques - preload, separation,
# mu, tangential stiffness, static friction and, per amplitude, peak force, energy per
# cycle and regime - written to out/steel420/ (summary.json, loops.csv, energy.csv and
# the plots loops.png, energy_vs_force.png, mu_vs_preload.png, stiffness_vs_preload.png).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh >/dev/null
cmake --preset default -DPython3_EXECUTABLE="$PWD/.venv/bin/python" >/dev/null
cmake --build --preset default -j 2 >/dev/null

mkdir -p out
./build/release/src/cli/asperity predict examples/joints/steel420_two_bolts.toml --out out/steel420
