#!/usr/bin/env python3
"""Behaviour of `asperity sphere` on bad input, gross slip and output files.

Usage: cli_cases.py ASPERITY_EXE CASE   (CASE: one of CASES below, or "list")

Standard library only. Exit 0 = pass, 1 = fail (also when gnuplot, which setup.sh installs, is missing).
Contract checked (issue 2, "Bad input"): every input error exits 2, prints one message
on stderr naming the flag, and prints nothing on stdout (no partial JSON); an amplitude
beyond gross slip is not an error (exit 0, regime gross_slip); --loop and --plot write
whole files, and an unwritable output path exits 2 leaving no file behind.
"""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile

BASE = {
    "--E1": "207GPa", "--nu1": "0.3", "--G1": "82.7GPa", "--E2": "207GPa", "--nu2": "0.3",
    "--G2": "82.7GPa", "--H": "6.83GPa", "--R1": "2.5mm", "--P": "35N", "--mu-cfc": "0.284",
}


def args(overrides=None, drop=(), extra=()):
    """Table 3.2 experiment 1 command with some options replaced, dropped or added.
    Values are passed as --flag=value so that negative numbers stay values."""
    opts = dict(BASE)
    opts.update(overrides or {})
    out = ["sphere"]
    for k, v in opts.items():
        if k not in drop:
            out.append(f"{k}={v}")
    return out + list(extra)


# name -> (argument list, flag the message must name, other text it must contain)
BAD_INPUT = {
    "negative_E": (args({"--E1": "-207GPa"}), "--E1", "> 0"),
    "zero_E": (args({"--E2": "0GPa"}), "--E2", "> 0"),
    "nu_half": (args({"--nu1": "0.5"}), "--nu1", "[0, 0.5)"),
    "nu_negative": (args({"--nu2": "-0.1"}), "--nu2", "[0, 0.5)"),
    "malformed_unit": (args({"--E1": "207 GPaa"}), "--E1", "GPaa"),
    "not_a_number": (args({"--E1": "abc"}), "--E1", "abc"),
    "wrong_dimension": (args({"--P": "35mm"}), "--P", "force"),
    "bare_number_for_pressure": (args({"--H": "6.83"}), "--H", "pressure"),
    "unknown_model": (args(extra=["--model=xyz"]), "--model", "xyz"),
    "negative_P": (args({"--P": "-35N"}), "--P", "> 0"),
    "negative_radius": (args({"--R1": "-2.5mm"}), "--R1", "> 0"),
    "negative_hardness": (args({"--H": "-6.83GPa"}), "--H", "> 0"),
    "negative_amplitude": (args(extra=["--delta-max=-1um"]), "--delta-max", ">= 0"),
    "missing_E1": (args(drop=("--E1",)), "--E1", "required"),
    "missing_load": (args(drop=("--P",)), "--P", "required"),
    "both_loads": (args(extra=["--omega-star=0.3"]), "--omega-star", "not both"),
    "cfc_without_mu": (args(drop=("--mu-cfc",)), "--mu-cfc", "cfc"),
}


def run(exe, argv):
    return subprocess.run([exe] + argv, capture_output=True, text=True, timeout=60)


def fail(message):
    print("FAIL:", message, file=sys.stderr)
    return 1


def bad_input(exe, name):
    argv, flag, text = BAD_INPUT[name]
    r = run(exe, argv + ["--json"])
    problems = []
    if r.returncode != 2:
        problems.append(f"exit {r.returncode}, expected 2")
    if r.stdout != "":
        problems.append(f"stdout not empty: {r.stdout[:200]!r}")
    if flag not in r.stderr:
        problems.append(f"stderr does not name {flag}: {r.stderr!r}")
    if text not in r.stderr:
        problems.append(f"stderr does not contain {text!r}: {r.stderr!r}")
    if problems:
        return fail(f"{name} ({' '.join(argv)}): " + "; ".join(problems))
    return 0


def gross_slip(exe):
    # 100 um is 20 to 100 slip displacements for every model at 35 N (slip displacements
    # 0.9-4.5 um): gross slip, reported, exit 0. Energy per cycle ~ 4 mu P delta_max.
    r = run(exe, args(extra=["--delta-max=100um", "--json"]))
    if r.returncode != 0:
        return fail(f"exit {r.returncode}: {r.stderr}")
    j = json.loads(r.stdout)
    for name, m in j["models"].items():
        if m["regime"] != "gross_slip":
            return fail(f"{name}: regime {m['regime']}")
        if m["Q_at_delta_max"] != m["Q_max"]:
            return fail(f"{name}: Q at delta_max {m['Q_at_delta_max']} != mu P {m['Q_max']}")
        # Delta W = 4 mu P (dm - s) + 0.15 (mu P)^2/(G* a), s = 3 mu P/(16 G* a) (B.19 at Q~ = 1)
        s = m["slip_displacement"]
        ref = 4 * m["Q_max"] * (100e-6 - s) + 0.15 * m["Q_max"] ** 2 / (j["G_star"] * m["a"])
        if abs(m["energy"] - ref) > 1e-12 * ref:
            return fail(f"{name}: energy {m['energy']} vs {ref}")
    # A force amplitude beyond mu P: the contact slides under force control. Not an
    # error either: regime gross_slip, no finite displacement or energy.
    r = run(exe, args(extra=["--Q-max=1000N", "--json"]))
    if r.returncode != 0:
        return fail(f"--Q-max 1000N: exit {r.returncode}: {r.stderr}")
    for name, m in json.loads(r.stdout)["models"].items():
        if m["regime"] != "gross_slip" or m["energy"] is not None:
            return fail(f"--Q-max 1000N, {name}: {m}")
    # And the readable table says so too.
    r = run(exe, args(extra=["--delta-max=100um"]))
    if r.returncode != 0 or r.stdout.count("gross_slip") != 4:
        return fail(f"table output: exit {r.returncode}, {r.stdout}")
    return 0


def loop_file(exe):
    points = 21
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "loop.csv")
        r = run(exe, args(extra=["--delta-max=1.5um", f"--loop={path}", f"--points={points}",
                                 "--json"]))
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        json.loads(r.stdout)  # stdout is still the JSON object
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        if set(rows[0]) != {"model", "branch", "delta[m]", "Q[N]"}:
            return fail(f"header {list(rows[0])}")
        if len(rows) != 4 * 3 * points:
            return fail(f"{len(rows)} rows, expected {4 * 3 * points}")
        leftovers = [n for n in os.listdir(tmp) if n != "loop.csv"]
        if leftovers:
            return fail(f"temporary files left: {leftovers}")
        for model in ("cfc", "ceb", "ke", "bke"):
            mine = [r for r in rows if r["model"] == model]
            d = [float(r["delta[m]"]) for r in mine]
            q = [float(r["Q[N]"]) for r in mine]
            # Loading 0 -> 1.5 um, unloading to -1.5 um, reloading back; the loop closes.
            if d[0] != 0.0 or abs(d[points - 1] - 1.5e-6) > 1e-18 or abs(d[-1] - 1.5e-6) > 1e-18:
                return fail(f"{model}: loop ends {d[0]}, {d[points - 1]}, {d[-1]}")
            if abs(q[-1] - q[points - 1]) > 1e-9 * abs(q[points - 1]):
                return fail(f"{model}: reloading ends at {q[-1]}, loading at {q[points - 1]}")
            if abs(q[2 * points - 1] + q[points - 1]) > 1e-9 * abs(q[points - 1]):
                return fail(f"{model}: unloading ends at {q[2 * points - 1]}")
    return 0


def plot_file(exe):
    if shutil.which("gnuplot") is None:
        print("gnuplot is not installed: scripts/setup.sh installs it", file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "loop.png")
        r = run(exe, args(extra=["--delta-max=1.5um", f"--plot={path}"]))
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        with open(path, "rb") as f:
            head = f.read(8)
        if head != b"\x89PNG\r\n\x1a\n":
            return fail(f"{path} is not a PNG: {head!r}")
        if os.listdir(tmp) != ["loop.png"]:
            return fail(f"files left: {os.listdir(tmp)}")
    return 0


def unwritable_output(exe):
    # The output directory is a regular file, so nothing can be created below it.
    with tempfile.TemporaryDirectory() as tmp:
        blocker = os.path.join(tmp, "not_a_dir")
        with open(blocker, "w") as f:
            f.write("x")
        for flag, name in (("--loop", "loop.csv"), ("--plot", "loop.png"),
                           ("--loop", os.path.join("missing", "loop.csv"))):
            target = os.path.join(blocker if "missing" not in name else tmp, name)
            r = run(exe, args(extra=["--delta-max=1.5um", f"{flag}={target}", "--json"]))
            if r.returncode != 2:
                return fail(f"{flag} {target}: exit {r.returncode}, expected 2: {r.stderr}")
            if r.stdout != "":
                return fail(f"{flag} {target}: stdout not empty")
            if target not in r.stderr:
                return fail(f"{flag} {target}: message does not name the path: {r.stderr!r}")
            if sorted(os.listdir(tmp)) != ["not_a_dir"]:
                return fail(f"{flag} {target}: files left: {os.listdir(tmp)}")
        # An amplitude is needed for a loop: asking for one without is bad input.
        r = run(exe, args(extra=[f"--loop={os.path.join(tmp, 'x.csv')}"]))
        if r.returncode != 2 or "--delta-max" not in r.stderr or os.path.exists(
                os.path.join(tmp, "x.csv")):
            return fail(f"--loop without amplitude: exit {r.returncode}, {r.stderr!r}")
    return 0


CASES = {"gross_slip": gross_slip, "loop_file": loop_file, "plot_file": plot_file,
         "unwritable_output": unwritable_output}
CASES.update({f"bad_input.{n}": (lambda exe, n=n: bad_input(exe, n)) for n in BAD_INPUT})


def main():
    if len(sys.argv) == 2 and sys.argv[1] == "list":
        print(";".join(CASES))
        return 0
    if len(sys.argv) != 3 or sys.argv[2] not in CASES:
        print(__doc__, file=sys.stderr)
        return 1
    return CASES[sys.argv[2]](sys.argv[1])


if __name__ == "__main__":
    sys.exit(main())
