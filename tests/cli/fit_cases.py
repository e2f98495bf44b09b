#!/usr/bin/env python3
"""`asperity analyze --fit jenkins|iwan4`: the fitted element in the form a vibration case
takes (its [[element]] table runs in `asperity vibration`), the outputs, and bad input (exit
2, a message naming the flag, nothing on stdout).

Usage: fit_cases.py ASPERITY SOURCE_DIR CASE. Standard library only.
"""
import json
import os
import subprocess
import sys
import tempfile


def run(exe, argv, cwd):
    return subprocess.run([exe] + argv, capture_output=True, text=True, timeout=300, cwd=cwd)


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


STRUCTURE = """[structure]
mass = [[1.0]]
stiffness = [[1e8]]
damping = [[10.0]]
output_dofs = [0]

[harmonic_balance]
harmonics = [0, 1, 2, 3]
time_points = 256

[quasi_static_mode]
mode = 1
amplitude = { from = 1e-8, to = 1e-5 }
points = 12

"""


def check(exe, src, case, tmp):
    joint = os.path.join(src, "examples", "joints", "steel420_two_bolts.toml")
    runs = []
    for a in ("2um", "8um"):
        path = os.path.join(tmp, f"run_{a}.csv")
        r = run(exe, ["synthesize", joint, "--imposed", a, "--P", "526N", "--noise-delta", "0um",
                      "--noise-Q", "0N", "--out", path], tmp)
        if r.returncode != 0:
            return fail(r.stderr)
        runs.append(path)
    if case in ("element_runs_in_vibration", "element_out_matches_json"):
        model = "iwan4" if case == "element_runs_in_vibration" else "jenkins"
        el = os.path.join(tmp, "element.toml")
        r = run(exe, ["analyze", *runs, "--P", "526N", "--fit", model, "--element-out", el,
                      "--json"], tmp)
        if r.returncode != 0:
            return fail(r.stderr)
        fit = json.loads(r.stdout)["fit"]
        text = open(el).read()
        if text != fit["element_toml"]:
            return fail("--element-out differs from the JSON's element_toml")
        if case == "element_out_matches_json":
            if set(fit["parameters"]) != {"k_t", "F_s"} or fit["loops"] != runs:
                return fail(f"fit: {fit}")
            return 0
        # The table, appended to a structure, is a vibration case whose element has the
        # fitted parameters (to the 10 digits the table prints).
        with open(os.path.join(tmp, "case.toml"), "w") as f:
            f.write(STRUCTURE + text)
        r = run(exe, ["vibration", "case.toml", "--json"], tmp)
        if r.returncode != 0:
            return fail(f"vibration refused the fitted element: {r.stderr}")
        e = json.loads(r.stdout)["elements"][0]
        p = fit["parameters"]
        for key, name in (("F_S_N", "F_S"), ("K_T_N_per_m", "K_T"), ("chi", "chi"), ("beta", "beta")):
            want = p[name]["value"]
            if abs(e[key] - want) > 1e-9 * abs(want):
                return fail(f"{key} = {e[key]}, fitted {want}")
        return 0
    if case == "bad_input":
        for argv, words in ((["--fit", "iwan"], ["--fit", "jenkins or iwan4"]),
                            (["--element-out", "x.toml"], ["--element-out", "--fit"]),
                            (["--fit", "jenkins", "--element-out", runs[0]], ["--element-out"])):
            r = run(exe, ["analyze", *runs, "--P", "526N", *argv], tmp)
            if r.returncode != 2 or r.stdout:
                return fail(f"{argv}: exit {r.returncode}, stdout {r.stdout!r}")
            for w in words:
                if w not in r.stderr:
                    return fail(f"{argv}: message lacks {w!r}: {r.stderr}")
        return 0
    return fail(f"unknown case {case}")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        return check(sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3], tmp)


if __name__ == "__main__":
    sys.exit(main())
