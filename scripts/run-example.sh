#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine, builds asperity and runs the main job
# on a shipped example: the friction prediction for the thesis's two-bolt steel 420 lap
# joint (chapter 5, Tables 5.3-5.5) over its four bolt torques - preload, separation,
# mu, tangential stiffness, static friction and, per amplitude, peak force, energy per
# cycle and regime - written to out/steel420/ (summary.json, loops.csv, energy.csv and
# the plots loops.png, energy_vs_force.png, mu_vs_preload.png, stiffness_vs_preload.png).
set -euo pipefail
cd "$(dirname "$0")/.."

# Each step's output goes to a log: quiet when it works; when a step fails, its last
# lines (the compiler's or cmake's message) are printed and the whole log is kept.
log=$(mktemp "${TMPDIR:-/tmp}/asperity-run-example.XXXXXX.log")
step() {
  local what=$1
  shift
  local rc=0
  "$@" >>"$log" 2>&1 || rc=$?
  if ((rc != 0)); then
    echo "run-example.sh: $what failed (exit $rc); the last lines of its output:" >&2
    tail -n 60 "$log" >&2
    echo "run-example.sh: full log: $log" >&2
    exit "$rc"
  fi
}
step "setup (scripts/setup.sh)" bash scripts/setup.sh
step "configure (cmake --preset default)" \
  cmake --preset default -DPython3_EXECUTABLE="$PWD/.venv/bin/python"
step "build (cmake --build --preset default)" cmake --build --preset default -j 2
rm -f "$log"

mkdir -p out
./build/release/src/cli/asperity predict examples/joints/steel420_two_bolts.toml --out out/steel420
