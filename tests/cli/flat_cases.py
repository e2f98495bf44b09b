#!/usr/bin/env python3
"""Behaviour of `asperity flat`: the JSON contract of the issue, the history mode, and
bad input (exit 2, a message naming what to change, nothing on stdout, no output file).

Usage: flat_cases.py ASPERITY_EXE CASE. Standard library only. Exit 0 = pass, 1 = fail.
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

NORMALIZED = ["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e-3", "--model=bke"]
STEEL = ["--E1=200GPa", "--nu1=0.24", "--G1=80.7GPa", "--E2=200GPa", "--nu2=0.24",
         "--G2=80.7GPa", "--H=5.8GPa"]
DIMENSIONAL = ["flat"] + STEEL + ["--sigma=2.677um", "--eta=2.91e-4um^-2", "--R=30.14um",
                                  "--area=170mm^2", "--P=526N", "--model=bke"]


def run(exe, argv):
    return subprocess.run([exe] + argv, capture_output=True, text=True, timeout=120)


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


def check_json(exe, argv, keys):
    r = run(exe, argv + ["--json"])
    if r.returncode != 0:
        return fail(f"exit {r.returncode}: {r.stderr}")
    j = json.loads(r.stdout)
    missing = [k for k in keys if k not in j]
    if missing:
        return fail(f"missing keys {missing}")
    for k, v in j.items():
        if isinstance(v, float) and not math.isfinite(v):
            return fail(f"{k} is not finite")
    return j


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def bad(exe, argv, must_contain, tmp=None):
    r = run(exe, argv)
    if r.returncode != 2:
        return fail(f"expected exit 2, got {r.returncode}; stderr: {r.stderr}")
    if r.stdout:
        return fail(f"stdout not empty: {r.stdout!r}")
    if must_contain.lower() not in r.stderr.lower():
        return fail(f"message does not mention {must_contain!r}: {r.stderr}")
    if tmp and os.path.exists(os.path.join(tmp, "out.csv")):
        return fail("an output file was left behind")
    return 0


def main():
    exe, case = sys.argv[1], sys.argv[2]
    tmp = tempfile.mkdtemp()
    norm_keys = ["beta", "psi", "sigma_a_over_sigma", "omega_c_star", "separation_star", "P_star",
                 "Q_max_star", "mu", "stiffness_star"]
    amp_keys = ["delta_max_star", "Q_at_delta_max_star", "energy_star"]
    if case == "normalized_json":
        j = check_json(exe, NORMALIZED + ["--delta-star-max=0.6"], norm_keys + amp_keys)
        if not isinstance(j, dict):
            return 1
        # Eq. 4.4 inverted: the load is the one asked for; BKE mu at psi = 0.5 above 1.
        if abs(j["P_star"] - 1e-3) > 1e-15 or not (j["mu"] > 1.0) or j["energy_star"] <= 0:
            return fail(str(j))
        return 0
    if case == "dimensional_json":
        j = check_json(exe, DIMENSIONAL + ["--delta-max=1um"],
                       norm_keys + amp_keys + ["separation", "P", "Q_max", "stiffness", "energy"])
        if not isinstance(j, dict):
            return 1
        # Chapter 5: BKE mu at 526 N printed as 0.335 (SEED_NOTES.md); within 5 %.
        if abs(j["mu"] - 0.335) / 0.335 > 0.05:
            return fail(f"mu = {j['mu']}")
        # SI consistency: Q_max = mu P.
        if abs(j["Q_max"] - j["mu"] * j["P"]) > 1e-9 * j["Q_max"]:
            return fail("Q_max != mu P")
        return 0
    if case in ("history_star", "history_si"):
        hist = os.path.join(tmp, "h.csv")
        out = os.path.join(tmp, "out.csv")
        xs = [0.5 * math.sin(2 * math.pi * k / 50) * (1 + k / 200) for k in range(400)]
        if case == "history_star":
            write(hist, "delta_star\n" + "\n".join(f"{x:.10g}" for x in xs) + "\n")
            r = run(exe, NORMALIZED + ["--history", hist, "--out", out])
        else:
            write(hist, "delta[um]\n" + "\n".join(f"{x:.10g}" for x in xs) + "\n")
            r = run(exe, DIMENSIONAL + ["--history", hist, "--out", out])
        if r.returncode != 0:
            return fail(r.stderr)
        with open(out) as f:
            rows = list(csv.reader(f))
        expected_header = ["delta_star", "Q_star"] if case == "history_star" else ["delta[m]", "Q[N]"]
        if rows[0] != expected_header or len(rows) != len(xs) + 1:
            return fail(f"header {rows[0]}, {len(rows)} rows")
        Q = [float(r[1]) for r in rows[1:]]
        # Odd history start: Q has the sign of delta on the virgin branch, and |Q| is bounded.
        if not all(math.isfinite(q) for q in Q) or Q[1] <= 0:
            return fail("forces not finite or wrong sign")
        return 0
    if case == "loop_and_plot":
        loop = os.path.join(tmp, "loop.csv")
        png = os.path.join(tmp, "loop.png")
        r = run(exe, NORMALIZED + ["--delta-star-max=0.6", "--loop", loop, "--plot", png])
        if r.returncode != 0:
            return fail(r.stderr)
        with open(png, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                return fail("not a PNG")
        with open(loop) as f:
            rows = list(csv.reader(f))[1:]
        # The loop closes: the last point equals the end of the first loading.
        first_peak = next(r for r in rows if abs(float(r[0]) - 0.6) < 1e-12)
        if abs(float(rows[-1][1]) - float(first_peak[1])) > 1e-12:
            return fail("loop does not close")
        return 0
    hist = os.path.join(tmp, "h.csv")
    out = os.path.join(tmp, "out.csv")
    cases = {
        "bad_input.beta_too_small": (["flat", "--beta=0.019", "--psi=0.5", "--nu=0.3", "--P-star=1e-3"], "beta"),
        "bad_input.psi_zero": (["flat", "--beta=0.04", "--psi=0", "--nu=0.3", "--P-star=1e-3"], "--psi"),
        "bad_input.preload_too_large": (["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e3"], "preload"),
        "bad_input.negative_amplitude": (NORMALIZED + ["--delta-star-max=-0.1"], "--delta-star-max"),
        "bad_input.mixed_inputs": (NORMALIZED + ["--sigma=2um"], "mixing"),
        "bad_input.unknown_model": (["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e-3", "--model=xyz"], "xyz"),
        "bad_input.cfc_without_mu": (["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e-3", "--model=cfc"], "--mu-cfc"),
    }
    history_cases = {
        "bad_input.history_not_a_number": ("delta_star\n0.1\nabc\n", "abc"),
        "bad_input.history_nan": ("delta_star\n0.1\nnan\n", "finite"),
        "bad_input.history_missing_column": ("x\n0.1\n", "delta_star"),
        "bad_input.history_wrong_unit": ("delta[N]\n0.1\n", "length"),
    }
    if case in cases:
        argv, text = cases[case]
        return bad(exe, argv, text)
    if case in history_cases:
        content, text = history_cases[case]
        write(hist, content)
        argv = (DIMENSIONAL if case.endswith("wrong_unit") else NORMALIZED) + ["--history", hist, "--out", out]
        return bad(exe, argv, text, tmp)
    return fail(f"unknown case {case}")


if __name__ == "__main__":
    sys.exit(main())
