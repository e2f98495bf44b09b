#!/usr/bin/env python3
"""Behaviour of `asperity dynamics`: the summary.json contract of issue 6, the shipped
Table 7.2 examples, and bad input (exit 2, a message naming what to change, nothing on
stdout) or numerical failure (exit 3).

Usage: dynamics_cases.py ASPERITY_EXE CASE. Standard library only. Exit 0 = pass.
Registered in tests/cli/CMakeLists.txt, one CTest per case (cli.dynamics.<case>).
"""
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "..", "examples", "dynamics")
KEYS = ["modal_frequency", "modal_damping", "energy_balance_error", "steps", "force_evaluations"]


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


def run(exe, case_text, tmp, extra=()):
    path = os.path.join(tmp, "case.toml")
    with open(path, "w") as f:
        f.write(case_text)
    out = os.path.join(tmp, "out")
    return subprocess.run([exe, "dynamics", path, "--out", out, "--no-plots", *extra],
                          capture_output=True, text=True, timeout=300), out


def bad(exe, case_text, must_contain, code=2):
    with tempfile.TemporaryDirectory() as tmp:
        r, _ = run(exe, case_text, tmp)
    if r.returncode != code:
        return fail(f"expected exit {code}, got {r.returncode}; stderr: {r.stderr}")
    if r.stdout:
        return fail(f"stdout not empty: {r.stdout!r}")
    if must_contain.lower() not in r.stderr.lower():
        return fail(f"message does not mention {must_contain!r}: {r.stderr}")
    return 0


def summary_keys(exe):
    case = """[dynamics]
excitation = "impulse"
duration = 100
[dynamics.friction]
model = "dankowicz"
F_max = 1.5
delta = 0.011
"""
    with tempfile.TemporaryDirectory() as tmp:
        r, out = run(exe, case, tmp)
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        j = json.load(open(os.path.join(out, "summary.json")))
        if not os.path.exists(os.path.join(out, "timeseries.csv")):
            return fail("no timeseries.csv")
    missing = [k for k in KEYS if k not in j]
    if missing:
        return fail(f"missing keys {missing}")
    if not (1.8 < j["modal_frequency"] < 1.95):  # sqrt(1 + 1.5/0.011)/(2 pi) = 1.87
        return fail(f"modal_frequency {j['modal_frequency']}")
    if not j["energy_balance_error"] < 1e-5:
        return fail(f"energy_balance_error {j['energy_balance_error']}")
    return 0


def examples_table_7_2(exe):
    cases = sorted(glob.glob(os.path.join(EXAMPLES, "*.toml")))
    if len(cases) < 10:
        return fail(f"only {len(cases)} example cases in {EXAMPLES}")
    for path in cases:
        with tempfile.TemporaryDirectory() as tmp:
            r = subprocess.run([exe, "dynamics", path, "--out", tmp, "--no-plots"],
                               capture_output=True, text=True, timeout=300)
            if r.returncode != 0:
                return fail(f"{path}: exit {r.returncode}: {r.stderr}")
            j = json.load(open(os.path.join(tmp, "summary.json")))
        for k in KEYS:
            if k not in j:
                return fail(f"{path}: missing {k}")
        for k, v in j.items():
            if isinstance(v, float) and not math.isfinite(v):
                return fail(f"{path}: {k} is not finite")
        # BS23 at rtol 1e-6, atol 1e-7 (the thesis's settings): balance to ~1e-6.
        if not j["energy_balance_error"] < 1e-5:
            return fail(f"{path}: energy_balance_error {j['energy_balance_error']}")
    return 0


BAD = {
    "bad_input.negative_mass": ('[dynamics]\nmass = "-1 kg"\nstiffness = "1e5 N/m"\n', "mass"),
    "bad_input.negative_stiffness": ('[dynamics]\nstiffness = "-1e5 N/m"\n', "stiffness"),
    "bad_input.zero_frequency":
        ('[dynamics]\nexcitation = "harmonic"\n[dynamics.harmonic]\nfrequency = 0\n', "frequency"),
    "bad_input.rtol_out_of_range": ('[dynamics]\n[dynamics.integrator]\nrtol = 2\n', "rtol"),
    "bad_input.unknown_key": ('[dynamics]\nfoo = 1\n', "foo"),
    "bad_input.missing_parameter":
        ('[dynamics]\n[dynamics.friction]\nmodel = "dankowicz"\nF_max = 1.5\n', "delta"),
    "bad_input.units_without_scales":
        ('[dynamics]\n[dynamics.friction]\nmodel = "coulomb"\nF_max = "150 N"\nk_tan = 6.32\n',
         "amplitude"),
}


def main():
    exe, case = sys.argv[1], sys.argv[2]
    if case == "summary_keys":
        return summary_keys(exe)
    if case == "examples_table_7_2":
        return examples_table_7_2(exe)
    if case in BAD:
        text, word = BAD[case]
        return bad(exe, text, word)
    if case == "numerical.step_collapse":
        text = ('[dynamics]\nexcitation = "harmonic"\n[dynamics.friction]\nmodel = "jenkins"\n'
                'F_max = 1.5\nstiffness = 136\n[dynamics.integrator]\nmethod = "bs23"\nmin_step = 0.5\n')
        return bad(exe, text, "step size collapsed", code=3)
    return fail(f"unknown case {case}")


if __name__ == "__main__":
    sys.exit(main())
