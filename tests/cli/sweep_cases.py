#!/usr/bin/env python3
"""`asperity sweep`: the C++ command runs the Python module asperity.sweep under an
interpreter found in a stated order (ASPERITY_PYTHON; else python3 or python next to the
executable; else python3 on PATH), forwards every argument untouched and returns the
module's exit status; without an interpreter that has the package it exits 2 with one line
naming what it tried. `asperity --help` lists the command.

Stand-in interpreters (shell scripts) answer the import probe and then print the arguments
they got and exit with a status of their own, so forwarding is checked without Dask; the
`module_*` cases run the real module from the build tree (PYTHON_DIR, built with
ASPERITY_BUILD_PYTHON=ON).

Usage: sweep_cases.py ASPERITY_EXE PYTHON_DIR CASE. Standard library only.
Exit 0 = pass. Registered in tests/cli/CMakeLists.txt (cli.sweep.<case>).
"""
import os
import re
import shutil
import stat
import subprocess
import sys
import tempfile

# The probe the command runs before it hands over (src/cli/sweep_command.cpp).
PROBE = "import asperity.sweep.__main__"


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


def stand_in(path, tag, status, probe_ok=True):
    """An executable that passes (or fails, like an interpreter without the package) the
    import probe, and otherwise prints `tag` and one line per argument, then exits
    `status`."""
    with open(path, "w") as f:
        f.write("#!/bin/sh\n"
                f'if [ "$2" = "{PROBE}" ]; then\n')
        if probe_ok:
            f.write("  exit 0\n")
        else:
            f.write("  echo \"ModuleNotFoundError: No module named 'asperity'\" >&2; exit 1\n")
        f.write(f"fi\necho {tag}\nshift 2\n"
                'for a in "$@"; do printf "[%s]\\n" "$a"; done\n'
                f"exit {status}\n")
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
    return path


def run(exe, args, env_extra, path=None):
    env = {k: v for k, v in os.environ.items() if k != "ASPERITY_PYTHON"}
    env.update(env_extra)
    if path is not None:
        env["PATH"] = path
    return subprocess.run([exe, *args], capture_output=True, text=True, env=env, timeout=120)


def case_listed_in_help(exe, pydir, tmp):
    r = run(exe, ["--help"], {})
    if r.returncode != 0:
        return fail(f"--help exited {r.returncode}")
    lines = [ln for ln in r.stdout.splitlines() if ln.strip().startswith("sweep ")]
    if len(lines) != 1 or "ASPERITY_PYTHON" not in lines[0]:
        return fail(f"--help lists no `sweep` command naming ASPERITY_PYTHON: {r.stdout}")
    # The shipped examples and schemas, and how to find them (issue 21 item 4).
    for want in ('asperity.data_path("examples")', 'asperity.data_path("schema")'):
        if want not in r.stdout:
            return fail(f"--help does not name {want}: {r.stdout}")
    return 0


def case_module_help_data_path(exe, pydir, tmp):
    """The command --help prints finds the examples and schemas of the package."""
    r = run(exe, ["--help"], {})
    m = re.search(r"python3 -c '([^']*)'", r.stdout)
    if not m:
        return fail(f"--help prints no python3 -c '...' command: {r.stdout}")
    p = subprocess.run([sys.executable, "-c", m.group(1)], capture_output=True, text=True,
                       env={**os.environ, **module_env(pydir)}, timeout=120)
    root = p.stdout.strip()
    if p.returncode != 0 or not os.path.isfile(
            os.path.join(root, "examples", "vibration", "jenkins_sdof.toml")) \
            or not os.path.isfile(os.path.join(root, "schema", "vibration.schema.json")):
        return fail(f"{m.group(1)} printed {root!r} ({p.stderr}): no examples/ and schema/ there")
    return 0


def case_forwards_arguments_and_status(exe, pydir, tmp):
    py = stand_in(os.path.join(tmp, "py"), "stand-in", 3)
    # Every argument verbatim: "--", spaces, options the C++ parser would otherwise take.
    args = ["--", "case file.toml", "--help", "--version", "--out=/x", "-h", "", "--vary",
            "load.bolts.nut_factor ~ uniform(0.158, 0.267)"]
    r = run(exe, ["sweep", *args], {"ASPERITY_PYTHON": py})
    got = r.stdout.splitlines()
    if r.returncode != 3:
        return fail(f"exit status {r.returncode}, the module's was 3: {r.stderr}")
    if got != ["stand-in"] + [f"[{a}]" for a in args]:
        return fail(f"arguments arrived as {got}, sent {args}")
    ok = stand_in(os.path.join(tmp, "py0"), "stand-in", 0)
    r = run(exe, ["sweep"], {"ASPERITY_PYTHON": ok})
    if r.returncode != 0 or r.stdout.splitlines() != ["stand-in"]:
        return fail(f"no arguments: exit {r.returncode}, stdout {r.stdout!r}")
    return 0


def case_interpreter_order(exe, pydir, tmp):
    # A copy of the command in a directory with its own python3, and a python3 on PATH.
    bindir = os.path.join(tmp, "bin")
    pathdir = os.path.join(tmp, "path")
    os.makedirs(bindir)
    os.makedirs(pathdir)
    cli = os.path.join(bindir, "asperity")
    shutil.copy2(exe, cli)
    stand_in(os.path.join(pathdir, "python3"), "on-path", 0)
    env_py = stand_in(os.path.join(tmp, "env-python"), "from-env", 0)
    path = pathdir + os.pathsep + "/usr/bin" + os.pathsep + "/bin"
    # Nothing next to the executable: python3 on PATH.
    r = run(cli, ["sweep"], {}, path)
    if r.stdout.splitlines()[:1] != ["on-path"]:
        return fail(f"without a python next to the executable: {r.stdout!r} {r.stderr!r}")
    # python next to the executable (as a wheel installs both) before PATH.
    stand_in(os.path.join(bindir, "python"), "next-to-exe", 0)
    r = run(cli, ["sweep"], {}, path)
    if r.stdout.splitlines()[:1] != ["next-to-exe"]:
        return fail(f"python next to the executable not taken first: {r.stdout!r}")
    # One next to it without the package: the next in order is taken.
    stand_in(os.path.join(bindir, "python"), "next-to-exe", 0, probe_ok=False)
    r = run(cli, ["sweep"], {}, path)
    if r.stdout.splitlines()[:1] != ["on-path"]:
        return fail(f"a python without the package was not passed over: {r.stdout!r}")
    # ASPERITY_PYTHON before both.
    r = run(cli, ["sweep"], {"ASPERITY_PYTHON": env_py}, path)
    if r.stdout.splitlines()[:1] != ["from-env"]:
        return fail(f"ASPERITY_PYTHON not taken first: {r.stdout!r}")
    return 0


def case_no_interpreter(exe, pydir, tmp):
    missing = os.path.join(tmp, "no-such-python")
    r = run(exe, ["sweep", "x.toml", "--out", "o"], {"ASPERITY_PYTHON": missing})
    lines = r.stderr.strip().splitlines()
    if r.returncode != 2 or len(lines) != 1 or r.stdout:
        return fail(f"exit {r.returncode}, stderr {r.stderr!r}, stdout {r.stdout!r}")
    if not lines[0].startswith("asperity: error: ") or f"ASPERITY_PYTHON={missing}" not in lines[0]:
        return fail(f"the message does not name ASPERITY_PYTHON and its value: {lines[0]}")
    # An interpreter without the package: its reason quoted; ASPERITY_PYTHON is used alone.
    bare = stand_in(os.path.join(tmp, "bare"), "bare", 0, probe_ok=False)
    r = run(exe, ["sweep", "x.toml"], {"ASPERITY_PYTHON": bare})
    if r.returncode != 2 or "No module named 'asperity'" not in r.stderr or r.stdout:
        return fail(f"without the package: exit {r.returncode}, {r.stderr!r} {r.stdout!r}")
    # Nothing anywhere (no python3 on PATH): names what to set.
    r = run(exe, ["sweep", "x.toml"], {}, path=tmp)
    if r.returncode != 2 or "set ASPERITY_PYTHON" not in r.stderr:
        return fail(f"no interpreter on PATH: exit {r.returncode}, {r.stderr!r}")
    return 0


def module_env(pydir):
    return {"ASPERITY_PYTHON": sys.executable,
            "PYTHONPATH": pydir + os.pathsep + os.environ.get("PYTHONPATH", "")}


def case_module_help(exe, pydir, tmp):
    r = run(exe, ["sweep", "--help"], module_env(pydir))
    if r.returncode != 0 or not r.stdout.startswith("usage: asperity sweep"):
        return fail(f"exit {r.returncode}; stdout {r.stdout[:200]!r}; stderr {r.stderr!r}")
    # The same options as `python -m asperity.sweep` (argparse's option list).
    m = subprocess.run([sys.executable, "-m", "asperity.sweep", "--help"], capture_output=True,
                       text=True, env={**os.environ, **module_env(pydir)}, timeout=120)
    opts = lambda text: sorted({w.strip("[],") for w in text.split() if w.startswith(("--", "[--"))})
    if m.returncode != 0 or opts(m.stdout) != opts(r.stdout):
        return fail(f"options differ: {opts(m.stdout)} vs {opts(r.stdout)}")
    return 0


def case_module_bad_input(exe, pydir, tmp):
    # The module's own refusal and exit 2 come through.
    r = run(exe, ["sweep", os.path.join(tmp, "missing.toml"), "--out", os.path.join(tmp, "o")],
            module_env(pydir))
    if r.returncode != 2 or not r.stderr.startswith("asperity sweep: error: ") \
            or "missing.toml" not in r.stderr:
        return fail(f"exit {r.returncode}; stderr {r.stderr!r}")
    return 0


CASES = {name[5:]: fn for name, fn in globals().items() if name.startswith("case_")}


def main():
    if len(sys.argv) != 4 or sys.argv[3] not in CASES:
        print(f"usage: {sys.argv[0]} ASPERITY_EXE PYTHON_DIR {{{','.join(CASES)}}}",
              file=sys.stderr)
        return 2
    exe, pydir, case = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3]
    with tempfile.TemporaryDirectory() as tmp:
        return CASES[case](exe, pydir, tmp)


if __name__ == "__main__":
    sys.exit(main())
