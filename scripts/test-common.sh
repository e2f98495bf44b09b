# Sourced by scripts/test.sh and scripts/test-full.sh: the machine set up (scripts/setup.sh,
# once per run: ASPERITY_SETUP_DONE=1 skips it), the repository root as the working
# directory, `py` (the interpreter of every Python step, .venv/bin/python) and `stage`, which
# prints a stage's name with the seconds since the script started.
cd "$(dirname "${BASH_SOURCE[0]}")/.."
if [ "${ASPERITY_SETUP_DONE:-}" != 1 ]; then
  bash scripts/setup.sh
  export ASPERITY_SETUP_DONE=1
fi
py="$PWD/.venv/bin/python"
started=$SECONDS
stage() { echo "== [$((SECONDS - started)) s] $*"; }
