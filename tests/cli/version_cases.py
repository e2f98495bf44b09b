#!/usr/bin/env python3
"""Which asperity made an output: `asperity --version` prints the version, the git revision
of the source and the build type, and every JSON output (stdout of --json and the JSON
files of --out) carries the same text as its first key, `asperity_version`.

Usage: version_cases.py ASPERITY_EXE SOURCE_DIR BUILD_TYPE CASE. Standard library only.
Exit 0 = pass. Registered in tests/cli/CMakeLists.txt (cli.version.<case>).
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

MATERIALS = ["--E1", "200GPa", "--nu1", "0.24", "--G1", "80.7GPa", "--E2", "200GPa",
             "--nu2", "0.24", "--G2", "80.7GPa", "--H", "5.8GPa"]


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


def expected_version(source_dir, build_type):
    """The version text the build should carry: CMakeLists.txt's project version, `git
    describe` of the source (as cmake/version_info.cmake runs it), the build type."""
    with open(os.path.join(source_dir, "CMakeLists.txt")) as f:
        version = re.search(r"project\(asperity VERSION (\S+)", f.read()).group(1)
    revision = "unknown"
    if shutil.which("git"):
        r = subprocess.run(["git", "-C", source_dir, "describe", "--always", "--dirty",
                            "--abbrev=12"], capture_output=True, text=True)
        if r.returncode == 0 and r.stdout.strip():
            revision = r.stdout.strip()
    return f"{version} (git {revision}, {build_type})"


def run(exe, args, cwd):
    r = subprocess.run([exe, *args], capture_output=True, text=True, cwd=cwd, timeout=300)
    if r.returncode != 0:
        raise AssertionError(f"asperity {' '.join(args)} exited {r.returncode}: {r.stderr}")
    return r.stdout


def check_json(text, where, want):
    doc = json.loads(text)
    if not isinstance(doc, dict) or next(iter(doc), None) != "asperity_version":
        return fail(f"{where}: asperity_version is not the first key: {list(doc)[:3]}")
    if doc["asperity_version"] != want:
        return fail(f"{where}: asperity_version = {doc['asperity_version']!r}, expected {want!r}")
    return 0


def case_version_flag(exe, source, want, tmp):
    out = run(exe, ["--version"], tmp)
    if out.strip() != f"asperity {want}":
        return fail(f"--version printed {out!r}, expected 'asperity {want}'")
    # The revision may be "unknown" only outside a git checkout.
    if "git unknown" in out and os.path.exists(os.path.join(source, ".git")):
        return fail("--version says 'git unknown' in a git checkout")
    return 0


def case_json_outputs(exe, source, want, tmp):
    examples = os.path.join(source, "examples")
    stdout_cases = {
        "sphere --json": ["sphere", *MATERIALS, "--R1", "2.5mm", "--P", "35N", "--mu-cfc",
                          "0.284", "--delta-max", "1.5um", "--json"],
        "flat --json": ["flat", "--beta", "0.04", "--psi", "0.5", "--nu", "0.3", "--P-star",
                        "1e-3", "--model", "bke", "--delta-star-max", "0.6", "--json"],
        "roughness --json": ["roughness", "--params", "sigma=1.763um,eta=3.34e-4um^-2,R=40.76um",
                             "--json"],
        "predict --json": ["predict", os.path.join(examples, "joints", "steel420_two_bolts.toml"),
                           "--json"],
    }
    for where, args in stdout_cases.items():
        if check_json(run(exe, args, tmp), where, want):
            return 1
    # The JSON files of --out.
    run(exe, ["predict", os.path.join(examples, "joints", "steel420_two_bolts.toml"), "--out",
              "predict", "--no-plots"], tmp)
    run(exe, ["dynamics", os.path.join(examples, "dynamics", "impulse_coulomb.toml"), "--out",
              "dynamics", "--no-plots"], tmp)
    run(exe, ["synthesize", os.path.join(examples, "joints", "steel420_two_bolts.toml"),
              "--preload", "526N", "--imposed", "6.75um", "--out", "fretting.csv"], tmp)
    analyze = run(exe, ["analyze", "fretting.csv", "--P", "526N", "--json"], tmp)
    if check_json(analyze, "analyze --json", want):
        return 1
    run(exe, ["analyze", "fretting.csv", "--P", "526N", "--out", "analysis", "--no-plots"], tmp)
    files = ["predict/summary.json", "dynamics/summary.json", "analysis/analysis.json"]
    for name in files:
        with open(os.path.join(tmp, name)) as f:
            if check_json(f.read(), name, want):
                return 1
    return 0


def case_one_json_writer(exe, source, want, tmp):
    """Every JSON text of the CLI goes through cli::json_output (which adds
    asperity_version): no other nlohmann dump() in src/cli, so a new --json output or JSON
    file cannot leave the version out."""
    cli = os.path.join(source, "src", "cli")
    offenders = []
    for name in sorted(os.listdir(cli)):
        if not name.endswith((".cpp", ".hpp")) or name in ("common.cpp",):
            continue
        with open(os.path.join(cli, name)) as f:
            for number, line in enumerate(f, 1):
                if ".dump(" in line:
                    offenders.append(f"src/cli/{name}:{number}: {line.strip()}")
    if offenders:
        return fail("JSON written without cli::json_output (no asperity_version):\n"
                    + "\n".join(offenders))
    return 0


def main():
    exe, source, build_type, case = sys.argv[1:5]
    want = expected_version(source, build_type)
    cases = {"version_flag": case_version_flag, "json_outputs": case_json_outputs,
             "one_json_writer": case_one_json_writer}
    with tempfile.TemporaryDirectory() as tmp:
        return cases[case](exe, source, want, tmp)


if __name__ == "__main__":
    sys.exit(main())
