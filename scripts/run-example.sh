#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine, builds asperity and runs the main job
# on a shipped example: the micro-scale fretting experiment of the thesis's Table 3.2
# (steel ball on a steel flat, P = 35 N, 1.5 um amplitude) with the four asperity
# models, writing the loops to out/sphere_loops.csv and out/sphere_loops.png.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh >/dev/null
cmake --preset default >/dev/null
cmake --build --preset default -j 2 >/dev/null

mkdir -p out
./build/release/src/cli/asperity sphere \
  --E1 207GPa --nu1 0.3 --G1 82.7GPa --E2 207GPa --nu2 0.3 --G2 82.7GPa --H 6.83GPa \
  --R1 2.5mm --P 35N --mu-cfc 0.284 --delta-max 1.5um \
  --loop out/sphere_loops.csv --plot out/sphere_loops.png
echo
echo "wrote out/sphere_loops.csv and out/sphere_loops.png"
