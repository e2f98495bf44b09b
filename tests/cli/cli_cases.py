#!/usr/bin/env python3
"""Behaviour of `asperity sphere` on bad input, gross slip and output files.

Usage: cli_cases.py ASPERITY_EXE CASE   (CASE: one of CASES below, or "list")

Standard library only. Exit 0 = pass, 1 = fail (also when gnuplot, which setup.sh installs,
is missing).
Contract checked (issue 2, "Bad input"): every input error exits 2, prints one message
on stderr naming the flag, and prints nothing on stdout (no partial JSON); an amplitude
beyond gross slip is not an error (exit 0, regime gross_slip); --loop and --plot write
whole files, and an unwritable output path exits 2 leaving no file behind.
"""
import csv
import json
import math
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
    "unknown_interference": (args(extra=["--interference=hertzian"]), "--interference", "own"),
    # BKE's fits need nu in about (0.118, 0.5): asked for explicitly, the message names
    # the Poisson's ratio flags and suggests another model.
    "bke_small_nu": (args({"--nu1": "0.1", "--nu2": "0.1"}, extra=["--model=bke"]), "--nu1",
                     "another --model"),
    "equal_H_different_nu": (args({"--nu1": "0.25", "--H1": "6GPa", "--H2": "6GPa"},
                                  drop=("--H",)), "--H1", "--nu1"),
    # Derived quantities beyond the double range name the input that caused them, not an
    # internal variable (4th element: text that must not appear).
    "omega_star_overflow": (args(drop=("--P",), extra=["--omega-star=1e300"]), "--omega-star",
                            "too large", "P = inf"),
    "tiny_modulus": (args({"--E1": "1e-300Pa", "--E2": "1e-300Pa", "--G1": "4e-301Pa",
                           "--G2": "4e-301Pa"}), "--E1", "critical values",
                     "contact radius a = 0"),
    "delta_max_overflow": (args(extra=["--delta-max=1e307m"]), "--delta-max", "too large",
                           "delta~max"),
    "number_overflow": (args({"--P": "1e400N"}), "--P", "overflows", "does not start"),
    "number_underflow": (args({"--P": "1e-400N"}), "--P", "underflows", "does not start"),
    "points_one": (args(extra=["--delta-max=1um", "--points=1"]), "--points",
                   "1 is not allowed: it must be a whole number in [2, 100000]"),
    # Issue 13: shown as typed, not wrapped to 18446744073709551615.
    "points_overflow": (args(extra=["--delta-max=1um", "--points=99999999999999999999"]),
                        "--points", "99999999999999999999 is not allowed"),
}


def run(exe, argv):
    return subprocess.run([exe] + argv, capture_output=True, text=True, timeout=60)


def fail(message):
    print("FAIL:", message, file=sys.stderr)
    return 1


def bad_input(exe, name):
    argv, flag, text, *forbidden = BAD_INPUT[name]
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
    for bad in forbidden:
        if bad in r.stderr:
            problems.append(f"stderr names the internal {bad!r}: {r.stderr!r}")
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


def plot_path_is_not_code(exe):
    """A plot path with a backquote and quotes of both kinds is a file name, nothing else:
    gnuplot expands `...` in double-quoted strings, so none of it may reach gnuplot."""
    if shutil.which("gnuplot") is None:
        print("gnuplot is not installed: scripts/setup.sh installs it", file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory() as tmp:
        name = "a`touch PWNED1`'b\"$(touch PWNED2)\".png"
        r = subprocess.run(
            [os.path.abspath(exe)] + args(extra=["--delta-max=1.5um", f"--plot={name}"]),
            capture_output=True, text=True, timeout=60, cwd=tmp)
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        if sorted(os.listdir(tmp)) != [name]:
            return fail(f"files in the working directory: {sorted(os.listdir(tmp))}")
        with open(os.path.join(tmp, name), "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                return fail(f"{name!r} is not a PNG")
    return 0


def plot_without_gnuplot(exe):
    """No gnuplot on PATH: a clear message and exit 2 (the user's environment, like an
    unwritable directory; README), no file, no stdout."""
    with tempfile.TemporaryDirectory() as tmp:
        empty = os.path.join(tmp, "bin")
        os.mkdir(empty)
        png = os.path.join(tmp, "loop.png")
        r = subprocess.run([exe] + args(extra=["--delta-max=1.5um", f"--plot={png}", "--json"]),
                           capture_output=True, text=True, timeout=60,
                           env=dict(os.environ, PATH=empty))
        if r.returncode != 2:
            return fail(f"exit {r.returncode}, expected 2: {r.stderr}")
        for text in ("gnuplot", png, "scripts/setup.sh"):
            if text not in r.stderr:
                return fail(f"message does not contain {text!r}: {r.stderr!r}")
        if r.stdout != "" or sorted(os.listdir(tmp)) != ["bin"]:
            return fail(f"stdout {r.stdout[:100]!r}, files {sorted(os.listdir(tmp))}")
    return 0


def same_output_twice(exe):
    """Two outputs into one file would overwrite each other: exit 2, nothing written."""
    with tempfile.TemporaryDirectory() as tmp:
        a = os.path.join(tmp, "x.png")
        b = os.path.join(tmp, ".", "x.png")  # the same file, spelt differently
        for extra in ([f"--loop={a}", f"--plot={a}"], [f"--loop={a}", f"--energy-curve={b}"]):
            r = run(exe, args(extra=["--delta-max=1.5um", "--json"] + extra))
            flags = [e.split("=")[0] for e in extra]
            if r.returncode != 2 or r.stdout != "":
                return fail(f"{extra}: exit {r.returncode}, stdout {r.stdout[:100]!r}")
            if not all(f in r.stderr for f in flags):
                return fail(f"{extra}: message does not name {flags}: {r.stderr!r}")
            if os.listdir(tmp):
                return fail(f"{extra}: files written: {os.listdir(tmp)}")
    return 0


def bke_skipped_for_small_nu(exe):
    """--model all with nu in [0, 0.118): BKE's fits do not apply, the other three run."""
    small = {"--nu1": "0.1", "--nu2": "0.1"}
    r = run(exe, args(small, extra=["--delta-max=1.5um", "--json"]))
    if r.returncode != 0:
        return fail(f"exit {r.returncode}: {r.stderr}")
    models = json.loads(r.stdout)["models"]
    if sorted(models) != ["bke", "ceb", "cfc", "ke"]:
        return fail(f"models {sorted(models)}")
    if set(models["bke"]) != {"skipped"} or "nu = 0.1" not in models["bke"]["skipped"]:
        return fail(f"models.bke = {models['bke']}")
    for name in ("cfc", "ceb", "ke"):
        if "mu" not in models[name] or "skipped" in models[name]:
            return fail(f"models.{name} = {models[name]}")
    r = run(exe, args(small))
    if r.returncode != 0 or "bke   skipped: " not in r.stdout:
        return fail(f"table: exit {r.returncode}, {r.stdout!r}")
    return 0


def softer_body_rule(exe):
    """Hardness rule (README): H and nu are the softer material's. One of --H1/--H2 alone
    marks that body as the softer one, and the output says so; with both, the smaller."""
    cases = [  # overrides, softer body, its H, its nu
        ({"--nu1": "0.25", "--H2": "6GPa"}, 2, 6e9, 0.3),
        ({"--nu1": "0.25", "--H1": "6GPa"}, 1, 6e9, 0.25),
        ({"--nu1": "0.25", "--H1": "7GPa", "--H2": "6GPa"}, 2, 6e9, 0.3),
        ({"--nu1": "0.25", "--H1": "5GPa", "--H2": "6GPa"}, 1, 5e9, 0.25),
    ]
    for overrides, body, H, nu in cases:
        r = run(exe, args(overrides, drop=("--H",), extra=["--json"]))
        if r.returncode != 0:
            return fail(f"{overrides}: exit {r.returncode}: {r.stderr}")
        j = json.loads(r.stdout)
        if (j["softer_body"], j["H"], j["nu"]) != (body, H, nu):
            return fail(f"{overrides}: softer_body {j['softer_body']}, H {j['H']}, nu {j['nu']}")
        t = run(exe, args(overrides, drop=("--H",)))
        if f"softer material (H, nu): body {body}" not in t.stdout:
            return fail(f"{overrides}: the table does not name body {body}: {t.stdout[:400]!r}")
    # --H (nu1 = nu2): which body is softer does not matter, and the JSON says null.
    j = json.loads(run(exe, args(extra=["--json"])).stdout)
    if j["softer_body"] is not None or "--H" not in j["softer_rule"]:
        return fail(f"--H: softer_body {j['softer_body']}, rule {j['softer_rule']!r}")
    return 0


def huge_load(exe):
    """Any finite load has an interference (the BKE inverse brackets in closed form):
    --P 1e300N with each model's own normal law runs, all numbers finite."""
    r = run(exe, args({"--P": "1e300N"}, extra=["--interference=own", "--json"]))
    if r.returncode != 0:
        return fail(f"exit {r.returncode}: {r.stderr}")
    for name, m in json.loads(r.stdout)["models"].items():
        if not all(isinstance(v, float) and math.isfinite(v) for v in m.values()):
            return fail(f"{name}: {m}")
        if m["P"] != 1e300:
            return fail(f"{name}: P = {m['P']}")
    # Such a load is far outside small-strain contact (a >> R): said in JSON and on stderr.
    warnings = json.loads(r.stdout)["warnings"]
    if len(warnings) != 4 or "a << R" not in r.stderr:
        return fail(f"warnings {warnings}, stderr {r.stderr!r}")
    # The Table 3.2 load gives none.
    r = run(exe, args({}, extra=["--json"]))
    if r.returncode != 0 or json.loads(r.stdout)["warnings"] != []:
        return fail(f"35 N: {r.returncode} {r.stdout[-300:]}")
    return 0


CASES = {"gross_slip": gross_slip, "loop_file": loop_file, "plot_file": plot_file,
         "unwritable_output": unwritable_output, "plot_path_is_not_code": plot_path_is_not_code,
         "plot_without_gnuplot": plot_without_gnuplot, "same_output_twice": same_output_twice,
         "bke_skipped_for_small_nu": bke_skipped_for_small_nu,
         "softer_body_rule": softer_body_rule, "huge_load": huge_load}
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
