#!/usr/bin/env bash
# The installed wheel on a machine without the libraries it bundles (issue 21: a
# self-contained wheel; python/CMakeLists.txt, "A self-contained wheel").
#   scripts/check-wheel-alone.sh VENV
# VENV: a virtual environment with the wheel installed (with its `test` extra: scipy).
# In a private mount namespace (unshare -m; needs root, as scripts/setup.sh does) /dev/null
# is bound over the system's copy of every library in the wheel's asperity.libs/, except
# those the Python interpreter itself loads (libz), so only the wheel can serve them. Then
# the command and the module are used through each bundled library: a TOML case (toml++),
# an X3P scan (libzip, pugixml), a MATLAB reduced model (matio, HDF5), formatted output
# (fmt). The build tree's command (scripts/test.sh's) must fail there (a control, run first).
set -euo pipefail
cd "$(dirname "$0")/.."
venv="$(cd "$1" && pwd)"
bundle="$("$venv/bin/python" -c 'import asperity, pathlib; print(pathlib.Path(asperity.__file__).resolve().parent.parent / "asperity.libs")')"
[ -d "$bundle" ] || { echo "check-wheel-alone: no $bundle: the wheel bundles no libraries" >&2; exit 1; }
interpreter_libs="$(ldd "$(readlink -f "$venv/bin/python")" | awk '{print $1}')"
hide=()
for lib in "$bundle"/*; do
  name="$(basename "$lib")"
  grep -qx "$name" <<<"$interpreter_libs" && continue
  for dir in /usr/lib/x86_64-linux-gnu /lib/x86_64-linux-gnu /usr/lib /usr/local/lib; do
    [ -e "$dir/$name" ] && hide+=("$(readlink -f "$dir/$name")")
  done
done
mapfile -t hide < <(printf '%s\n' "${hide[@]}" | sort -u)  # /lib is /usr/lib (merged /usr)
[ "${#hide[@]}" -gt 0 ] || { echo "check-wheel-alone: no system copy to hide" >&2; exit 1; }

# A reduced model in the published Brake-Reuss beam layout (M, K, Fv, L, Qm, Tm), written
# by scipy before the libraries are hidden (scipy's own extensions use some of them: libffi).
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
model="$tmp/model.mat"
"$venv/bin/python" - "$model" <<'PY'
import sys

import numpy as np
import scipy.io

n = 6
q = np.zeros((3, n))
q[:, :3] = np.eye(3)
scipy.io.savemat(sys.argv[1], dict(M=np.eye(n), K=np.diag(np.arange(1.0, n + 1) * 1e6),
                                   Fv=np.zeros((n, 1)), L=np.vstack([np.eye(n)] * 3), Qm=q,
                                   Tm=q.T * 1e-4))
PY

unshare -m bash -euo pipefail -s "$venv" "$model" "${hide[@]}" <<'EOF'
venv="$1"; model="$2"; shift 2
for f in "$@"; do mount --bind /dev/null "$f"; done
echo "hidden: $# system libraries (fmt, libzip, pugixml, toml++, matio, HDF5 and theirs)"
[ -x build/ci/src/cli/asperity ] || { echo "check-wheel-alone: no build/ci (run scripts/test.sh first)" >&2; exit 1; }
if build/ci/src/cli/asperity --version >/dev/null 2>&1; then
  echo "check-wheel-alone: the build tree's command still runs: nothing was hidden" >&2
  exit 1
fi
"$venv/bin/asperity" --version
"$venv/bin/asperity" vibration examples/vibration/jenkins_sdof.toml >/dev/null
"$venv/bin/asperity" roughness --surface tests/data/mountainsmap-650x650.x3p --lc 26.5um \
  --ls 1.6um --json >/dev/null
"$venv/bin/python" - "$model" <<'PY'
import sys

import asperity
import asperity.fem

m = asperity.fem.read_reduced_model(sys.argv[1])
assert m["K"][1, 1] == 2e6, m["K"]
print(f"module {asperity.version_info()['version']}: reduced model read, K[1,1] = {m['K'][1, 1]:g}")
PY
echo "the wheel runs without the system's copies of its libraries"
EOF
